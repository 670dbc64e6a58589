// One state, one answer: after a transfer-function edit made as the panel makes it (a SettingEdit applied by
// the session step), the viewer's plan table, F5's report.json, `curette report` on the plan-scene.json F5
// wrote and a fresh report of a scene with that TF all give the same removed volume; and a session recorded
// after the edit (F9: the edit is in its header) replays to the live images and the viewer's report.
#include "session/carve_report.h"
#include "session/live_input.h"
#include "session/loaded_scene.h"
#include "session/plan_scene.h"
#include "session/session.h"
#include "session/session_step.h"
#include "tools/commands/commands.h"
#include "viewer/viewer_driver.h"
#include "base/atomic_file.h"
#include "input/hid/fake_backend.h"
#include "render/renderer.h"

#include "tests/tools/run_curette.h"
#include "tests/tools/tool_test_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>


#include <filesystem>
#include <random>

namespace curette {
namespace {

namespace fs = std::filesystem;
using curette::testing::Invocation;
using curette::testing::runCurette;

fs::path scratch(const std::string& name) { return curette::testing::freshScratchFolder("curette-report-state", name); }

// A 32^3 ball of 2 mm voxels: a core (200) inside a shell (120) in noisy air; two clip meshes that reach
// from the core through the shell, so a TF that hides the shell removes less tissue.
const char* const kSceneTf = R"({"color": [[0, 0, 0, 0], [100, 0.8, 0.6, 0.5], [255, 1, 1, 1]], "opacity": [[0, 0], [60, 0], [100, 0.2], [255, 0.8]]})";

fs::path writeBallScene(const fs::path& dir, const std::string& tf = kSceneTf) {
    nlohmann::json changes = nlohmann::json::parse(R"({"clip_meshes": [
    {"name": "sphere", "mesh": {"shape": "sphere", "radius_mm": 8}, "position_mm": [30, 30, 50]},
    {"name": "box", "mesh": {"shape": "box", "size_mm": [10, 10, 24]}, "position_mm": [22, 40, 14]}]})");
    changes["transfer_function"] = nlohmann::json::parse(tf);
    return curette::testing::writeNoisyBallScene(dir, changes);
}

// The panel's opacity drag: the TF's current JSON with point 2 moved to (150, 0), which hides the shell.
SettingEdit hideTheShell(const InteractionState& state, const Scene& scene) {
    nlohmann::json tf = state.keyJson(scene, "transfer_function");
    tf["opacity"][2] = {150, 0.0};
    return {Setting::TransferFunction, -1, tf};
}

nlohmann::json readJson(const fs::path& path) { return nlohmann::json::parse(curette::testing::readTextFile(path)); }

double removedMl(const fs::path& reportJson) { return readJson(reportJson).at("removed_ml").get<double>(); }

// `curette report` of a scene, the removed mL of its report.json.
double reportOfScene(const fs::path& scene, const fs::path& out) {
    Invocation r = runCurette("report --no-exports --scene " + scene.string() + " --out " + out.string());
    EXPECT_EQ(r.exitCode, 0) << r.output;
    return removedMl(out / "report.json");
}

std::string pngHash(const fs::path& path) {
    const curette::testing::Png png = curette::testing::readPng(path);
    if (png.rgba.empty()) return "(no image " + path.string() + ")";
    return imageHash(png.rgba);
}

// The viewer's loop without a window: the step applying the frame's input and panel edits, the renderer in
// sync with it, and the plan table's report refreshed after each frame.
struct Viewer {
    explicit Viewer(const fs::path& scene)
        : loaded(loadSceneWithVolume(scene)),
          context(gl::createHeadlessContext()),
          renderer(*context, loaded.volume, loaded.scene.transferFunction),
          step(InteractionState::fromScene(loaded.scene), initialFrame(loaded.scene, renderer.geometry())),
          reporter(loaded, renderer.geometry(), commands::programVersion()) {
        configureRenderer(loaded, renderer);
    }

    // One iteration at `now` s: actions and edits through the step, the image, the plan table.
    std::string frame(double now, const std::vector<input::Action>& actions = {}, const std::vector<SettingEdit>& edits = {}) {
        step.apply(actions, step.frame().size.y, edits);
        return render(now);
    }
    std::string render(double now) {
        step.syncTo(renderer, loaded.tracts);
        renderer.render(step.frame());
        table.refresh(reporter, renderer.clipMeshes(), step.state(), now);
        return imageHash(toRgba8(renderer.readImage(), glm::vec4(loaded.scene.background)));
    }

    LoadedScene loaded;
    std::unique_ptr<gl::Context> context;
    Renderer renderer;
    SessionStep step;
    CarveReporter reporter;
    ViewerReport table;
};

// F5 writes into the working directory, as the viewer does: run it in `dir`.
std::string exportPlanIn(const fs::path& dir, Viewer& v) {
    fs::path before = fs::current_path();
    fs::current_path(dir);
    std::string line = v.table.exportPlan(v.reporter, v.renderer.clipMeshes(), v.step.state(), "test");
    fs::current_path(before);
    return line;
}

// (a) The TF edit changes the plan table, F5's report.json and the plan scene's report alike, to the report of
// a scene that has the edited TF.
TEST(ReportState, ATransferFunctionEditChangesEveryReportOfTheState) {
    fs::path dir = scratch("tf-edit");
    fs::path scene = writeBallScene(dir);
    Viewer v(scene);
    v.frame(0.0);
    v.frame(1.0);
    ASSERT_TRUE(v.table.report()) << "the meshes have been still for a second";
    const double unedited = v.table.report()->removedMl;

    SettingEdit edit = hideTheShell(v.step.state(), v.loaded.scene);
    v.frame(2.0, {}, {edit});
    v.frame(3.0);
    ASSERT_TRUE(v.table.report());
    const double table = v.table.report()->removedMl;

    std::string line = exportPlanIn(dir, v);
    fs::path plan = dir / "curette-plan-test";
    ASSERT_TRUE(fs::exists(plan / "report.json")) << line;
    const double f5 = removedMl(plan / "report.json");
    const double planScene = reportOfScene(plan / "plan-scene.json", dir / "plan-scene-report");

    fs::create_directories(dir / "edited");
    fs::path editedScene = writeBallScene(dir / "edited", edit.value.dump());
    const double fresh = reportOfScene(editedScene, dir / "edited-report");

    EXPECT_LT(fresh, unedited) << "hiding the shell leaves less tissue to remove, so the comparison means something";
    EXPECT_EQ(table, fresh) << "the plan table";
    EXPECT_EQ(f5, fresh) << "F5's report.json";
    EXPECT_EQ(planScene, fresh) << "curette report on F5's plan-scene.json";
}

// (b) F9 after the edit: the recording's header carries it; the replay shows the live frames and reports what
// the viewer reported, and so does `curette report --session`.
TEST(ReportState, ASessionRecordedAfterAnEditReplaysTheEditedState) {
    fs::path dir = scratch("record-after-edit");
    fs::path scene = writeBallScene(dir);
    fs::path session = dir / "after-edit.jsonl";
    Viewer v(scene);
    LiveInput input(std::make_unique<input::FakeHidBackend>(std::make_shared<input::FakeHidBackend::Ports>()), input::defaultMapping(), 40.0, 60.0);
    v.frame(0.0, {}, {hideTheShell(v.step.state(), v.loaded.scene)});
    std::vector<std::string> live;
    {
        LiveRecording recording(session, "scene.json", v.step.state(), input, 0.0);   // F9 on frame 0
        for (int f = 1; f <= 4; ++f) {
            double now = f / 10.0;
            input::KeyboardMouseState keys;
            if (f == 2 || f == 3) keys.keys |= 1u << static_cast<int>(input::Key::W);   // the keyboard moves mesh 0
            InputFrame in = input.step(now, keys, 0.1, static_cast<int>(v.step.state().meshes.size()));
            v.step.apply(in.actions, v.step.frame().size.y);
            recording.addFrame(now, 0.1, v.step.frame().size, v.step.frame().camera, v.step.state(), keys, in);
            live.push_back(v.render(now));
        }
        recording.finish();
    }
    v.render(2.0);
    ASSERT_TRUE(v.table.report());
    const double viewer = v.table.report()->removedMl;
    ASSERT_FALSE(readSession(session, false).header.edits.empty()) << "the edit is in the header";

    for (const char* mode : {"", " --from-reports"}) {
        fs::path out = dir / (std::string("replay") + (*mode ? "-reports" : ""));
        Invocation r = runCurette("replay " + session.string() + " --report --out " + out.string() + mode);
        ASSERT_EQ(r.exitCode, 0) << r.output;
        std::vector<std::string> replayed;
        for (std::size_t f = 0; f < live.size(); ++f) {
            char name[32];
            std::snprintf(name, sizeof name, "frame_%06zu.png", f);
            replayed.push_back(pngHash(out / name));
        }
        EXPECT_EQ(replayed, live) << "replay" << mode << " renders the edited TF from its first frame";
        EXPECT_EQ(removedMl(out / "report" / "report.json"), viewer) << "replay" << mode << " --report of the last frame";
    }

    Invocation direct = runCurette("report --no-exports --session " + session.string() + " --out " + (dir / "direct").string());
    ASSERT_EQ(direct.exitCode, 0) << direct.output;
    EXPECT_EQ(removedMl(dir / "direct" / "report.json"), viewer) << "report --session at its last frame";
}

// The shading combo, then a shading key: the state shows the key's mode, and so do the scene it is saved as
// and the state a recording started now starts from.
TEST(ReportState, ThePlanSceneAndASessionHeaderCarryTheShadingOnScreen) {
    fs::path dir = scratch("shading");
    fs::path scene = writeBallScene(dir);
    LoadedScene loaded = loadSceneWithVolume(scene);
    SessionStep step(InteractionState::fromScene(loaded.scene), initialFrame(loaded.scene, {loaded.volume.dims, loaded.volume.indexToWorld}));
    step.apply({}, 48, {{Setting::Shading, -1, "phong"}});
    step.apply({input::SetShading{"cao"}}, 48);
    ASSERT_EQ(step.state().shading, ShadingMode::Cao);

    writeFileAtomically(dir / "saved.json", planSceneJson(loaded.scene, curette::testing::readTextFile(scene), step.state()));
    EXPECT_EQ(loadScene(dir / "saved.json").shading, ShadingMode::Cao) << "the plan scene";

    LiveInput input(std::make_unique<input::FakeHidBackend>(std::make_shared<input::FakeHidBackend::Ports>()), input::defaultMapping(), 40.0, 60.0);
    {
        LiveRecording recording(dir / "late.jsonl", "scene.json", step.state(), input, 0.0);
        recording.finish();
    }
    Session s = readSession(dir / "late.jsonl", false);
    EXPECT_EQ(InteractionState::fromSessionStart(s.header, loaded.scene, dir, "late.jsonl").shading, ShadingMode::Cao) << "the session header";
}

}  // namespace
}  // namespace curette
