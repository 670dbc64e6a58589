// curette bench view through the real binary: the viewer's frame loop driven headless by the recorded session of
// a mesh moving in the carved head (assets/sessions/head-carved-move.jsonl), at a tiny size. The JSON has its
// fields, step I ran in slices, the playback previewed the motion, and the last frame is exact and equals a fresh
// renderer's image of the session's last state (what `curette render` gives: a new renderer, the scene
// configured, one frame). With 6 LAO rays instead of the scene's 26 (step I twice on the head is most of the
// test's time). No time is asserted.
#include "session/loaded_scene.h"
#include "session/session.h"
#include "session/session_step.h"
#include "viewer/viewer_driver.h"
#include "render/model/lao_directions.h"
#include "render/renderer.h"

#include <nlohmann/json.hpp>

#include "tests/tools/run_curette.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace curette {
namespace {

const std::string kSource = CURETTE_SOURCE_DIR;

// The image hash of the session's last state rendered by a fresh renderer at `size`.
std::string freshRenderOfLastState(const std::filesystem::path& sessionFile, glm::ivec2 size, int rays) {
    Session session = readSession(sessionFile, false);
    std::filesystem::path scenePath = sessionFile.parent_path() / session.header.scene;
    LoadedScene loaded = loadSceneWithVolume(scenePath);
    EXPECT_TRUE(parseLaoPattern(std::to_string(rays), loaded.scene.lao.directions));
    auto context = gl::createHeadlessContext();
    Renderer renderer(*context, loaded.volume, loaded.scene.transferFunction);
    configureRenderer(loaded, renderer);
    SessionStep step(InteractionState::fromSessionStart(session.header, loaded.scene, scenePath.parent_path(), sessionFile.string()),
                     initialFrame(loaded.scene, renderer.geometry()));
    for (std::size_t n = 0; n < session.frames.size(); ++n) step.follow(session.frames[n], scenePath.parent_path(), "frame " + std::to_string(n));
    step.syncTo(renderer.clipMeshes());
    FrameDescription frame = step.frame();
    frame.shading = step.state().shading;
    frame.size = size;
    renderer.render(frame);
    return imageHash(toRgba8(renderer.readImage(), glm::vec4(loaded.scene.background)));
}

TEST(BenchView, TheLastFrameIsExactAndEqualsAFreshRenderOfTheSessionsLastState) {
    std::filesystem::path session = kSource + "/assets/sessions/head-carved-move.jsonl";
    auto dir = std::filesystem::temp_directory_path() / ("curette-bench-view-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    std::filesystem::path json = dir / "bench-view.json";
    curette::testing::Invocation r =
        curette::testing::runCurette("bench view --session " + session.string() + " --size 64x48 --rays 6 --quality adaptive --exact-budget 1 --json " + json.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("motion frame p99"), std::string::npos) << "the table is printed:\n" << r.output;
    nlohmann::json j;
    std::ifstream(json) >> j;
    for (const char* key : {"first_image_ms", "first_exact_ms", "exact_after_motion_ms", "exact_render_ms", "setup_ms"})
        EXPECT_TRUE(j.contains(key) && j[key].is_number()) << key;
    for (const char* key : {"p50", "p90", "p99", "max"}) EXPECT_TRUE(j["motion"]["frame_ms"][key].is_number()) << key;
    EXPECT_TRUE(j["motion"]["fps"].is_number());
    EXPECT_TRUE(j["step1"]["wall_ms"].is_number());
    EXPECT_GE(j["step1"]["frames"].get<int>(), 2) << "step I ran in slices over several frames";
    EXPECT_GE(j["motion"]["frames"].get<int>(), 1) << "the playback presented frames in motion";
    int previews = 0;
    for (const nlohmann::json& f : j["playback_frames"]) previews += f["kind"] == "preview" && f["in_motion"].get<bool>();
    EXPECT_GE(previews, 1) << "the motion was previewed";
    EXPECT_EQ(j["quality"], "adaptive");
    EXPECT_GE(j["exact_slices"].get<int>(), 2) << "at a 1 ms budget the last exact frame came in slices";
    // The exact frame's work by pass: steps IV, V and VI, in the JSON and in the table.
    for (const char* pass : {"IV voxel clipping", "V LAO recompute", "VI ray casting"}) {
        EXPECT_TRUE(j["exact_pass_ms"].contains(pass) && j["exact_pass_ms"][pass].is_number()) << pass;
        EXPECT_NE(r.output.find(std::string("  ") + pass), std::string::npos) << pass << " in the table:\n" << r.output;
    }
    ASSERT_TRUE(j["last_frame"]["exact"].get<bool>());
    EXPECT_EQ(j["last_frame"]["image_hash"].get<std::string>(), freshRenderOfLastState(session, {64, 48}, 6))
        << "the exact frame after the previews differs from a fresh render of the last state";
    std::filesystem::remove_all(dir);
}

// The viewer's iteration itself (viewer/viewer_driver.h, what the window and bench view both run): from the
// session's last state it previews while step I runs in slices, then shows the exact frame, which is a fresh
// renderer's image of that state.
TEST(ViewerDriver, PreviewsDuringStepIThenShowsTheExactFrameOfAFreshRender) {
    std::filesystem::path file = kSource + "/assets/sessions/head-carved-move.jsonl";
    Session session = readSession(file, false);
    std::filesystem::path scenePath = file.parent_path() / session.header.scene;
    LoadedScene loaded = loadSceneWithVolume(scenePath);
    ASSERT_TRUE(parseLaoPattern("6", loaded.scene.lao.directions));
    auto context = gl::createHeadlessContext();
    Renderer renderer(*context, loaded.volume, loaded.scene.transferFunction);
    configureRenderer(loaded, renderer);
    SessionStep step(InteractionState::fromSessionStart(session.header, loaded.scene, scenePath.parent_path(), file.string()),
                     initialFrame(loaded.scene, renderer.geometry()));
    for (std::size_t n = 0; n < session.frames.size(); ++n) step.follow(session.frames[n], scenePath.parent_path(), "frame " + std::to_string(n));
    FrameLoopSettings settings;
    settings.quality = ViewQuality::Adaptive;
    settings.exactBudgetMs = 1;   // the exact frame in slices
    ViewerState viewer(settings);
    const glm::ivec2 size{64, 48};
    const glm::vec4 background(loaded.scene.background);
    int previewsDuringStepI = 0, exactSlices = 0;
    bool exact = false;
    for (int i = 0; i < 100000 && !exact; ++i) {
        ViewerIteration it = stepViewer(viewer, renderer, step, loaded.tracts, size, 10.0 + i, false, background);
        previewsDuringStepI += it.precomputing && it.decision.render == FrameKind::Preview;
        exactSlices += it.decision.render == FrameKind::Exact;
        exact = it.exactCompleted;
        if (it.precomputing) {
            EXPECT_NE(it.decision.render, FrameKind::Exact) << "no exact frame before step I is done";
        }
    }
    ASSERT_TRUE(exact);
    EXPECT_GE(previewsDuringStepI, 1);
    EXPECT_GE(exactSlices, 2) << "at a 1 ms budget the exact frame came in slices";
    EXPECT_TRUE(viewer.shownExact);
    EXPECT_EQ(viewer.stereo, StereoMode::Off);
    // Nothing moved and the exact frame is on screen: the next iteration renders nothing.
    ViewerIteration idle = stepViewer(viewer, renderer, step, loaded.tracts, size, 1e6, false, background);
    EXPECT_EQ(idle.decision.render, FrameKind::None);
    EXPECT_FALSE(idle.rendered);
    // Read before the fresh render, which makes its own context current.
    std::string hash = imageHash(toRgba8(renderer.readImage(), background));
    EXPECT_EQ(hash, freshRenderOfLastState(file, size, 6));
}

}  // namespace
}  // namespace curette
