// Panel edits as recorded actions, end to end: the viewer's loop without a window (the session step, a
// renderer, a recording) edits the transfer function, mesh sizes and shapes, the LAO settings (in cao), the
// shading, a light's colour and the ray step (in phong), adds and removes meshes and moves the camera; (a) the recorded session replays (`curette replay`,
// following the recording and re-deriving from the reports) to the live image hashes; (b) the state saved as
// a scene renders (`curette render`) to the live last image; (c) `curette view --play` in a real window under
// Xvfb, screenshot of the window, against the headless render of the same state.
#include "session/live_input.h"
#include "session/loaded_scene.h"
#include "session/plan_scene.h"
#include "session/session.h"
#include "session/session_step.h"
#include "base/atomic_file.h"
#include "input/devices/encoders.h"
#include "input/hid/fake_backend.h"
#include "render/renderer.h"

#include "tests/tools/run_curette.h"
#include "tests/tools/tool_test_support.h"

#include <gtest/gtest.h>


#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>

namespace curette {
namespace {

using curette::testing::Invocation;
using curette::testing::runCurette;

std::filesystem::path scratch(const std::string& name) { return curette::testing::freshScratchFolder("curette-panels", name); }

std::string readText(const std::filesystem::path& path) { return curette::testing::readTextFile(path); }

// A 32^3 ball with a soft shell and an LAO scene with two small clip meshes. (b) and (c) compare a renderer
// that played the session with a fresh one, so two histories of the renderer must not show:
//  - LAO, not CAO: a renderer that has drawn cao frames keeps the dilated clip maps for later frames;
//  - every mesh (scaled, plus twice the LAO reach as dilation margin) stays within the smallest clip-map
//    resolution (64 pixels of 1 mm): ClipMeshSet grows its maps by 25 % more than needed and shrinks them only
//    below half (render/passes/clip_mesh_set.cpp, update), so a renderer that once had a larger mesh keeps finer maps
//    than a fresh one and the cut differs in a few pixels (with a 24 mm sphere scaled 1.4 and 8 LAO samples:
//    31 channels, up to 6 levels, in a 48 x 48 image).
std::filesystem::path writeBallScene(const std::filesystem::path& dir) {
    return curette::testing::writeNoisyBallScene(dir, nlohmann::json::parse(R"({"clip_meshes": [
    {"name": "sphere", "mesh": {"shape": "sphere", "radius_mm": 8}, "position_mm": [30, 30, 44]},
    {"name": "box", "mesh": {"shape": "box", "size_mm": [10, 10, 24]}, "position_mm": [22, 40, 24]}]})"));
}

nlohmann::json json(const std::string& text) { return nlohmann::json::parse(text); }

// The edits a user makes in the panels on frame f of the run (as the panels build them: the key's current
// JSON with one field changed), with the frame's keys and camera moves.
std::vector<SettingEdit> panelEdits(int f, const InteractionState& state, const Scene& scene) {
    switch (f) {
        case 1: {   // dragging an opacity point up
            nlohmann::json tf = state.keyJson(scene, "transfer_function");
            tf["opacity"][2] = {110, 0.45};
            return {{Setting::TransferFunction, -1, tf}};
        }
        case 2: return {{Setting::MeshScale, 0, 1.4}};
        case 4: {
            nlohmann::json ao = state.keyJson(scene, "ambient_occlusion");
            ao["samples"] = 3;
            return {{Setting::AmbientOcclusion, -1, ao}};
        }
        case 5: return {{Setting::MeshAdd, -1, json(R"({"mesh": {"shape": "box", "size_mm": [12, 12, 12]}, "position_mm": [40, 30, 38]})")}};
        case 6: return {{Setting::MeshScale, 2, json("[1, 1.5, 1]")}};
        case 7: {   // phong, where the light's colour shows
            nlohmann::json light = state.keyJson(scene, "lights[0]");
            light["color"] = {1, 0.6, 0.3};
            return {{Setting::Shading, -1, "phong"}, {Setting::Light, 0, light}};
        }
        case 8: return {{Setting::MeshShape, 1, json(R"({"shape": "cylinder", "radius_mm": 7, "height_mm": 30})")}};
        case 9: {   // a preset-like TF replaced whole, and a second mesh size in the same frame
            nlohmann::json tf = json(R"({"color": [[0, 0, 0, 0], [120, 0.2, 0.7, 0.9], [255, 1, 0.9, 0.8]], "opacity": [[0, 0], [70, 0], [130, 0.35], [255, 0.9]]})");
            return {{Setting::TransferFunction, -1, tf}, {Setting::MeshScale, 1, 0.8}};
        }
        case 10: return {{Setting::Raycast, -1, json(R"({"step_mm": 0.7})")}};
        case 11: return {{Setting::MeshRemove, 0, nullptr}};
        default: return {};
    }
}

struct LiveRun {
    std::vector<std::string> hashes;
    std::vector<std::vector<SessionMesh>> poses;   // per frame
    InteractionState state;
    OrbitCamera camera;
    int settingChanges = 0;
};

// What a user does on frame f: panel edits (given the state and the scene), keys held, a camera move, the
// hold requests the mesh panel made on the frame before (handed to frame f's input step, as the viewer's loop
// does), and the reports of the devices plugged in at the start.
struct Script {
    int frames = 0;
    std::function<std::vector<SettingEdit>(int, const InteractionState&, const Scene&)> edits =
        [](int, const InteractionState&, const Scene&) { return std::vector<SettingEdit>{}; };
    std::function<input::KeyboardMouseState(int)> keys = [](int) { return input::KeyboardMouseState{}; };
    std::function<void(int, OrbitCamera&)> camera = [](int, OrbitCamera&) {};
    std::function<std::vector<input::HoldRequest>(int)> holds = [](int) { return std::vector<input::HoldRequest>{}; };
    std::vector<input::HidDeviceDescription> devices;
    std::function<void(int, input::FakeHidBackend::Ports&)> reports = [](int, input::FakeHidBackend::Ports&) {};
};

// The viewer's loop, headless: live (no) devices and keys, panel edits, the step, the recording, the renderer.
LiveRun recordPanelSession(const std::filesystem::path& scene, const std::filesystem::path& session, const Script& script) {
    LiveRun run;
    LoadedScene loaded = loadSceneWithVolume(scene);
    auto context = gl::createHeadlessContext();
    Renderer renderer(*context, loaded.volume, loaded.scene.transferFunction);
    configureRenderer(loaded, renderer);
    SessionStep step(InteractionState::fromScene(loaded.scene), initialFrame(loaded.scene, renderer.geometry()));
    step.attachRemoval(loaded.volume.dims, loaded.volume.indexToWorld);   // as the viewer: drilling and the undo history
    auto ports = std::make_shared<input::FakeHidBackend::Ports>();
    for (const input::HidDeviceDescription& d : script.devices) input::FakeHidBackend::plug(*ports, d);
    LiveInput input(std::make_unique<input::FakeHidBackend>(ports), input::defaultMapping(), 40.0, 60.0);
    LiveRecording recording(session, "scene.json", step.state(), input, 0.0);
    for (int f = 0; f < script.frames; ++f) {
        script.reports(f, *ports);
        input::KeyboardMouseState keys = script.keys(f);
        script.camera(f, step.frame().camera);
        double now = f / 10.0, dt = f == 0 ? 0.0 : 0.1;
        InputFrame in = input.step(now, keys, dt, static_cast<int>(step.state().meshes.size()), script.holds(f));
        StepChanges changes = step.apply(in.actions, step.frame().size.y, script.edits(f, step.state(), loaded.scene));
        run.settingChanges += changes.settings;
        recording.addFrame(now, dt, step.frame().size, step.frame().camera, step.state(), keys, in);
        step.syncTo(renderer, loaded.tracts);
        renderer.render(step.frame());
        run.hashes.push_back(imageHash(toRgba8(renderer.readImage(), glm::vec4(loaded.scene.background))));
        run.poses.push_back(step.state().sessionPoses());
    }
    recording.finish();
    run.state = step.state();
    run.camera = step.frame().camera;
    return run;
}

// The edit session of (a), (b) and (c): panelEdits, the camera moved on frame 3, W held on frames 9 and 10
// (the keyboard moves mesh 0 as well).
LiveRun recordEditSession(const std::filesystem::path& scene, const std::filesystem::path& session) {
    Script script;
    script.frames = 12;
    script.edits = panelEdits;
    script.keys = [](int f) {
        input::KeyboardMouseState keys;
        if (f == 9 || f == 10) keys.keys |= 1u << static_cast<int>(input::Key::W);
        return keys;
    };
    script.camera = [](int f, OrbitCamera& camera) {
        if (f == 3) camera.orbit(15, -5), camera.zoom(0.9);
    };
    return recordPanelSession(scene, session, script);
}

using curette::testing::Png;
using curette::testing::readPng;

// `curette replay` of `session`, following the recorded poses and re-deriving them from the reports, writes
// frames with the live run's image hashes (and the re-derived poses equal the recorded ones).
void expectReplaysToTheLiveHashes(const std::filesystem::path& session, const std::vector<std::string>& live) {
    for (const char* mode : {"", " --from-reports"}) {
        std::filesystem::path out = session.parent_path() / (session.stem().string() + "-replay" + (*mode ? "-reports" : ""));
        Invocation r = runCurette("replay " + session.string() + " --out " + out.string() + mode);
        ASSERT_EQ(r.exitCode, 0) << r.output;
        std::vector<std::string> replayed;
        for (std::size_t f = 0; f < live.size(); ++f) {
            char name[32];
            std::snprintf(name, sizeof name, "frame_%06zu.png", f);
            replayed.push_back(imageHash(readPng(out / name).rgba));
        }
        EXPECT_EQ(replayed, live) << "replay" << mode << " differs from the live frames";
        if (*mode) {
            EXPECT_NE(r.output.find("identical to the recorded ones"), std::string::npos) << r.output;
        }
    }
}

// (a) The recorded session with TF and mesh-size edits replays to the live image hashes.
TEST(PanelSessions, EditsReplayToTheLiveImageHashes) {
    auto dir = scratch("replay");
    auto scene = writeBallScene(dir);
    auto session = dir / "edits.jsonl";
    LiveRun live = recordEditSession(scene, session);
    EXPECT_EQ(live.settingChanges, 10) << "frames 1, 2, 4-11 edit a setting";
    for (std::size_t f : {1u, 2u, 4u, 5u, 6u, 7u, 8u, 9u, 10u, 11u})
        EXPECT_NE(live.hashes[f], live.hashes[f - 1]) << "frame " << f << "'s edit shows in the image";
    Session s = readSession(session, false);
    ASSERT_EQ(s.frames.size(), 12u);
    EXPECT_EQ(s.header.version, kSessionVersion);
    ASSERT_EQ(s.frames[5].edits.size(), 1u);
    EXPECT_EQ(s.frames[5].edits[0].target, 2) << "the added mesh's edit is recorded with its id";
    EXPECT_EQ(s.frames[9].edits.size(), 2u);
    expectReplaysToTheLiveHashes(session, live.hashes);
}

// Strokes and setting edits in one undo history, recorded and replayed: B and W held on frames 1-2 drill a
// path with mesh 0, frame 3 edits the transfer function, then Ctrl+Z on frames 4 and 6 undoes the edit and
// then the stroke, Ctrl+Shift+Z on frames 8 and 10 redoes them. Undoing the edit shows the image from before
// it, redoing shows the images after each step again; the session replays (--check), following the frames
// and re-deriving from the reports, to the live images and removal.
TEST(PanelSessions, UndoAndRedoOfStrokesAndEditsReplay) {
    auto dir = scratch("undo");
    auto scene = writeBallScene(dir);
    auto session = dir / "undo.jsonl";
    Script script;
    script.frames = 12;
    script.edits = [](int f, const InteractionState& state, const Scene& loadedScene) {
        if (f != 3) return std::vector<SettingEdit>{};
        nlohmann::json tf = state.keyJson(loadedScene, "transfer_function");
        tf["opacity"][2] = {110, 0.45};
        return std::vector<SettingEdit>{{Setting::TransferFunction, -1, tf}};
    };
    script.keys = [](int f) {
        input::KeyboardMouseState keys;
        auto press = [&](input::Key k) { keys.keys |= std::uint64_t(1) << static_cast<int>(k); };
        if (f == 1 || f == 2) press(input::Key::Drill), press(input::Key::W);
        if (f == 4 || f == 6) press(input::Key::Undo);
        if (f == 8 || f == 10) press(input::Key::Redo);
        return keys;
    };
    LiveRun live = recordPanelSession(scene, session, script);
    const std::vector<std::string>& h = live.hashes;
    ASSERT_EQ(h.size(), 12u);
    EXPECT_NE(h[3], h[2]) << "the edit shows";
    EXPECT_EQ(h[4], h[2]) << "the first Ctrl+Z undoes the edit, not the stroke before it";
    EXPECT_NE(h[6], h[4]) << "the second undoes the stroke";
    EXPECT_TRUE(h[5] == h[4] && h[7] == h[6] && h[9] == h[8] && h[11] == h[10]) << "one step a press";
    EXPECT_EQ(h[8], h[2]) << "Ctrl+Shift+Z redoes the stroke";
    EXPECT_EQ(h[10], h[3]) << "and then the edit";
    std::string text = readText(session);
    EXPECT_NE(text.find("\"history_edits\""), std::string::npos) << "the edits undo and redo applied are recorded";
    for (const char* mode : {"", " --from-reports"}) {
        std::filesystem::path out = dir / (std::string("replay") + (*mode ? "-reports" : ""));
        Invocation r = runCurette("replay " + session.string() + " --check --out " + out.string() + mode);
        ASSERT_EQ(r.exitCode, 0) << r.output;
        std::vector<std::string> replayed;
        for (std::size_t f = 0; f < h.size(); ++f) {
            char name[32];
            std::snprintf(name, sizeof name, "frame_%06zu.png", f);
            replayed.push_back(imageHash(readPng(out / name).rgba));
        }
        EXPECT_EQ(replayed, h) << "replay" << mode;
        EXPECT_EQ(curette::testing::removalDigest(r.output), live.state.removal->digest()) << "replay" << mode;
        if (*mode) {
            EXPECT_NE(r.output.find("identical to the recorded ones"), std::string::npos) << r.output;
        }
    }
}

// The mesh panel's "which device holds it": a SpaceMouse (binding 0 of the default mapping, holding mesh 0)
// pushes all the time; on frame 3 the panel makes it hold mesh 1, on frame 7 the keyboard (W held on frames
// 5-8) too. The requests go to the next input step, as the viewer's loop hands them on.
LiveRun recordHoldSession(const std::filesystem::path& scene, const std::filesystem::path& session) {
    input::HidDeviceDescription mouse;
    mouse.path = "/dev/hidraw-test-spacemouse";
    mouse.vendorId = 0x256f;
    mouse.productId = 0xc62e;
    mouse.product = "SpaceMouse Wireless (test)";
    mouse.bus = input::Bus::Usb;
    mouse.usagePage = 0x01;
    mouse.usage = 0x08;
    Script script;
    script.frames = 10;
    script.devices = {mouse};
    script.reports = [path = mouse.path](int, input::FakeHidBackend::Ports& ports) {
        input::DeviceState pushed;
        pushed.axes[0] = 0.5f;   // tx
        pushed.axes[4] = 0.3f;   // ry
        input::FakeHidBackend::queue(ports, path, input::encodeSpaceMouseCombined(pushed));
    };
    script.keys = [](int f) {
        input::KeyboardMouseState keys;
        if (f >= 5 && f <= 8) keys.keys |= 1u << static_cast<int>(input::Key::W);
        return keys;
    };
    script.holds = [](int f) {
        if (f == 3) return std::vector<input::HoldRequest>{{0, 1}};                        // the SpaceMouse's combo (frame 2): mesh 1
        if (f == 7) return std::vector<input::HoldRequest>{{input::kKeyboardBinding, 1}};  // the keyboard's combo (frame 6): mesh 1
        return std::vector<input::HoldRequest>{};
    };
    return recordPanelSession(scene, session, script);
}

// A hold change from the panel replays, following the recorded poses and re-deriving them from the
// reports, to the live image hashes: the request is recorded with the frame whose input step applied it.
TEST(PanelSessions, AHoldChangeReplaysFromPosesAndFromReports) {
    auto dir = scratch("holds");
    auto scene = writeBallScene(dir);
    auto session = dir / "holds.jsonl";
    LiveRun live = recordHoldSession(scene, session);
    // Live, the change shows from the frame that applied it: mesh 0 stops (no key held on frames 3 and 4),
    // mesh 1 moves; from frame 7 the keyboard's W moves mesh 1 and no longer mesh 0.
    auto position = [&](std::size_t frame, std::size_t mesh) { return live.poses[frame][mesh].position; };
    EXPECT_NE(position(2, 0), position(1, 0)) << "the SpaceMouse moves mesh 0 at first";
    EXPECT_EQ(position(2, 1), position(1, 1));
    EXPECT_EQ(position(3, 0), position(2, 0)) << "from frame 3 the SpaceMouse holds mesh 1";
    EXPECT_NE(position(3, 1), position(2, 1));
    EXPECT_NE(position(6, 0), position(5, 0)) << "the keyboard moves mesh 0 on frame 6";
    EXPECT_EQ(position(7, 0), position(6, 0)) << "from frame 7 the keyboard holds mesh 1";
    for (std::size_t f = 1; f < 10; ++f) EXPECT_NE(live.hashes[f], live.hashes[f - 1]) << "frame " << f << " moves a mesh";
    Session s = readSession(session, false);
    ASSERT_EQ(s.frames.size(), 10u);
    EXPECT_EQ(s.header.version, kSessionVersion);
    EXPECT_EQ(s.frames[3].holds, (std::vector<input::HoldRequest>{{0, 1}}));
    EXPECT_EQ(s.frames[7].holds, (std::vector<input::HoldRequest>{{input::kKeyboardBinding, 1}}));
    for (std::size_t f : {0u, 1u, 2u, 4u, 5u, 6u, 8u, 9u}) EXPECT_TRUE(s.frames[f].holds.empty()) << "frame " << f;
    EXPECT_EQ(s.frames.back().meshes.size(), 2u);
    for (std::size_t f = 0; f < 10; ++f) EXPECT_TRUE(samePoses(s.frames[f].meshes, live.poses[f])) << "frame " << f << " is recorded as it was live";
    expectReplaysToTheLiveHashes(session, live.hashes);
}

// A recording started after edits carries them in its header: it replays from the edited state.
TEST(PanelSessions, ARecordingStartedAfterEditsStartsFromTheEditedState) {
    auto dir = scratch("mid-run");
    auto scene = writeBallScene(dir);
    LoadedScene loaded = loadSceneWithVolume(scene);
    InteractionState state = InteractionState::fromScene(loaded.scene);
    state.applyEdits({{Setting::AmbientOcclusion, -1, json(R"({"rays": "6", "samples": 5, "step_mm": 2.0, "antialiasing_samples": 4})")},
                      {Setting::MeshClipsTubes, 1, true}},
                     "<panel>");
    LiveInput input(std::make_unique<input::FakeHidBackend>(std::make_shared<input::FakeHidBackend::Ports>()), input::defaultMapping(), 40.0, 60.0);
    {
        LiveRecording recording(dir / "late.jsonl", "scene.json", state, input, 0.0);
        recording.finish();
    }
    Session s = readSession(dir / "late.jsonl", false);
    ASSERT_EQ(s.header.edits.size(), 1u) << "the edited key (mesh settings are in the header's meshes)";
    InteractionState replayed = InteractionState::fromSessionStart(s.header, loaded.scene, dir, "late.jsonl");
    EXPECT_EQ(replayed.lao.samples, 5);
    EXPECT_TRUE(replayed.meshes[1].clipsTubes);
}

// Lights added and removed in the light panel, in phong (and one frame in ismos, whose light shapes follow
// the lights), on a scene with two lights L0 and L1 (L1 coloured, with its own ISMOS disk): frame 1 adds a
// blue light A, O selects L1 (2) and J turns it (3), A's colour is edited (4), ismos (5), L0 is removed, so
// L1 (never edited) becomes light 0 and A light 1 (6), J turns L1 (7), a light B is added (8) and A removed
// (9). The session replays to the live image hashes (following the poses and re-deriving from the keys);
// the saved scene renders the last image (L1 written as light 0 with its own colour and disk); a recording
// started at the end starts from the same lights.
TEST(PanelSessions, LightsAddedAndRemovedReplayAndSaveToTheSameImages) {
    auto dir = scratch("lights");
    auto scene = writeBallScene(dir);
    nlohmann::json edited = nlohmann::json::parse(readText(scene));
    edited["shading"] = "phong";
    edited["lights"] = json(R"([{"direction": [0.3, 0.5, 1.0]}, {"direction": [0.6, -0.2, 0.8], "color": [1, 0.8, 0.5], "disk_radius": 0.15}])");
    writeFileAtomically(scene, edited.dump(2));
    auto session = dir / "lights.jsonl";
    Script script;
    script.frames = 10;
    script.edits = [](int f, const InteractionState& state, const Scene& sceneNow) -> std::vector<SettingEdit> {
        switch (f) {
            case 1: return {{Setting::LightAdd, -1, json(R"({"direction": [-1, 0.2, 0.6], "color": [0.3, 0.5, 1], "intensity": 1.5})")}};
            case 4: {
                nlohmann::json light = state.keyJson(sceneNow, "lights[2]");
                light["color"] = {0.2, 1, 0.4};
                return {{Setting::Light, 2, light}};
            }
            case 5: return {{Setting::Shading, -1, "ismos"}};
            case 6: return {{Setting::Shading, -1, "phong"}, {Setting::LightRemove, 0, nullptr}};
            case 8: return {{Setting::LightAdd, -1, json(R"({"direction": [0, 1, 0.3], "color": [1, 0.2, 0.2]})")}};
            case 9: return {{Setting::LightRemove, 1, nullptr}};
            default: return {};
        }
    };
    script.keys = [](int f) {
        input::KeyboardMouseState keys;
        if (f == 2) keys.keys |= 1u << static_cast<int>(input::Key::O);
        if (f == 3 || f == 7) keys.keys |= 1u << static_cast<int>(input::Key::J);
        return keys;
    };
    LiveRun live = recordPanelSession(scene, session, script);
    for (std::size_t f : {1u, 3u, 4u, 5u, 6u, 7u, 8u, 9u}) EXPECT_NE(live.hashes[f], live.hashes[f - 1]) << "frame " << f << " changes a light";
    LoadedScene loaded = loadSceneWithVolume(scene);
    ASSERT_EQ(live.state.lights.size(), 2u);
    EXPECT_EQ(live.state.lights[0].color, glm::dvec3(1, 0.8, 0.5)) << "L1 is light 0";
    EXPECT_NE(live.state.lights[0].direction, loaded.scene.lights[1].direction) << "turned by J";
    EXPECT_EQ(live.state.lights[1].color, glm::dvec3(1, 0.2, 0.2)) << "B is light 1";
    ASSERT_EQ(live.state.ismos.lightShapes.size(), 2u);
    EXPECT_EQ(live.state.ismos.lightShapes[0].diskRadius, 0.15) << "L1's ISMOS disk moved down with it";
    EXPECT_EQ(live.state.keyJson(loaded.scene, "lights[0]").at("color"), json("[1, 0.8, 0.5]")) << "and its scene key";
    EXPECT_EQ(live.state.selectedLight, 0) << "the selected L1 moved down too";

    Session s = readSession(session, false);
    ASSERT_EQ(s.frames.size(), 10u);
    std::vector<std::size_t> counts;
    for (const SessionFrame& f : s.frames) counts.push_back(f.lights ? f.lights->size() : 0);
    EXPECT_EQ(counts, (std::vector<std::size_t>{2, 3, 3, 3, 3, 3, 2, 2, 3, 2})) << "each frame records its lights after its edits";
    expectReplaysToTheLiveHashes(session, live.hashes);

    // Saved as a scene: the lights as they are (their JSON, turned), rendering the last image.
    std::filesystem::create_directories(dir / "saved");
    writeFileAtomically(dir / "saved" / "scene.json", planSceneJson(loaded.scene, readText(scene), live.state, &live.camera));
    Invocation r = runCurette("render --scene " + (dir / "saved" / "scene.json").string() + " --out " + (dir / "saved.png").string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(imageHash(readPng(dir / "saved.png").rgba), live.hashes.back()) << readText(dir / "saved" / "scene.json");

    // A recording started now carries the light changes as header edits and starts from the same lights.
    LiveInput input(std::make_unique<input::FakeHidBackend>(std::make_shared<input::FakeHidBackend::Ports>()), input::defaultMapping(), 40.0, 60.0);
    {
        LiveRecording late(dir / "late.jsonl", "scene.json", live.state, input, 0.0);
        late.finish();
    }
    Session lateSession = readSession(dir / "late.jsonl", false);
    InteractionState started = InteractionState::fromSessionStart(lateSession.header, loaded.scene, dir, "late.jsonl");
    EXPECT_EQ(started.lights, live.state.lights);
    EXPECT_EQ(started.ismos.lightShapes, live.state.ismos.lightShapes);
    EXPECT_EQ(started.keyJson(loaded.scene, "lights[0]"), live.state.keyJson(loaded.scene, "lights[0]"));
}

// (b) "Save scene": the state written as a scene renders to the live run's last image.
TEST(PanelSessions, ASavedSceneRendersToTheSameImage) {
    auto dir = scratch("save");
    auto scene = writeBallScene(dir);
    LiveRun live = recordEditSession(scene, dir / "edits.jsonl");
    LoadedScene loaded = loadSceneWithVolume(scene);
    std::filesystem::create_directories(dir / "saved");
    writeFileAtomically(dir / "saved" / "scene.json", planSceneJson(loaded.scene, readText(scene), live.state, &live.camera));
    Invocation r = runCurette("render --scene " + (dir / "saved" / "scene.json").string() + " --out " + (dir / "saved.png").string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    Png png = readPng(dir / "saved.png");
    ASSERT_EQ(png.width, 48);
    EXPECT_EQ(imageHash(png.rgba), live.hashes.back()) << readText(dir / "saved" / "scene.json");
}

// (c) The viewer in a real window (Xvfb) plays the session through its own loop; its window, without the
// overlay, shows the headless render of the same state. The window's 8-bit back buffer holds the presenter's
// composite (shaders/present.frag) of the same image the PNG writer composites: allowed to differ by one
// level per channel (the framebuffer's rounding of the shader output against toRgba8's lround).
TEST(PanelSessions, TheViewerPlaysASessionInAWindowToTheHeadlessImage) {
    if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0) GTEST_SKIP() << "xvfb-run is not installed (package xvfb)";
    auto dir = scratch("xvfb");
    auto scene = writeBallScene(dir);
    auto session = dir / "edits.jsonl";
    recordEditSession(scene, session);
    const glm::ivec2 size{64, 56};
    auto shot = dir / "window.png";
    std::string command = "xvfb-run -a -s '-screen 0 320x240x24' " + std::string(CURETTE_BINARY) + " view --play " + session.string() +
                          " --screenshot " + shot.string() + " --size " + std::to_string(size.x) + "x" + std::to_string(size.y) + " 2>&1";
    FILE* pipe = popen(command.c_str(), "r");
    std::string output;
    char buffer[4096];
    while (std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) output.append(buffer, n);
    int status = pclose(pipe);
    ASSERT_EQ(WIFEXITED(status) ? WEXITSTATUS(status) : -1, 0) << output;
    EXPECT_NE(output.find("played 12 frames"), std::string::npos) << output;
    Png window = readPng(shot);
    ASSERT_EQ(window.width, size.x) << output;
    ASSERT_EQ(window.height, size.y) << output;

    // The same state headless: the session followed by the same step, rendered at the window's size.
    Session s = readSession(session, false);
    LoadedScene loaded = loadSceneWithVolume(scene);
    auto context = gl::createHeadlessContext();
    Renderer renderer(*context, loaded.volume, loaded.scene.transferFunction);
    configureRenderer(loaded, renderer);
    SessionStep step(InteractionState::fromSessionStart(s.header, loaded.scene, dir, session.string()), initialFrame(loaded.scene, renderer.geometry()));
    for (const SessionFrame& f : s.frames) step.follow(f, dir, session.string());
    step.syncTo(renderer, loaded.tracts);
    FrameDescription frame = step.frame();
    frame.size = size;
    renderer.render(frame);
    std::vector<std::uint8_t> headless = toRgba8(renderer.readImage(), glm::vec4(loaded.scene.background));
    writePngRgba8(dir / "headless.png", size.x, size.y, headless);   // beside window.png, to look at
    ASSERT_EQ(headless.size(), window.rgba.size());
    int maxDifference = 0;
    std::size_t differing = 0;
    for (std::size_t i = 0; i < headless.size(); ++i) {
        int d = std::abs(int(headless[i]) - int(window.rgba[i]));
        maxDifference = std::max(maxDifference, d);
        differing += d > 0;
    }
    EXPECT_LE(maxDifference, 1) << differing << " of " << headless.size() << " channels differ";
    std::size_t lit = 0;
    for (std::size_t i = 0; i < headless.size(); i += 4) lit += headless[i] + headless[i + 1] + headless[i + 2] > 30;
    EXPECT_GT(lit, headless.size() / 4 / 10) << "the picture shows the ball, so the comparison means something";
}

// The viewer's window at 1024x768 (Xvfb): the side bar holds the panels and leaves the 3-D view more than three
// quarters of the window, with no panel pixel in it (the window's view rectangle equals the view's screenshot
// outside the orientation marker); once the played session has settled, the idle window draws nothing for 5 s,
// in phong and in ismos (whose idle window used to render on).
struct WindowRun {
    std::string output;
    glm::ivec4 view{0}, sidebar{0}, marker{0};   // x, y, w, h
    std::vector<nlohmann::json> log;
};

WindowRun runWindow(const std::filesystem::path& session, const std::filesystem::path& dir, const std::string& extra) {
    WindowRun run;
    std::string command = "xvfb-run -a -s '-screen 0 1280x1024x24' " + std::string(CURETTE_BINARY) + " view --play " + session.string() +
                          " --size 1024x768 --screenshot " + (dir / "view.png").string() + " --window-shot " + (dir / "window.png").string() +
                          " --frame-log " + (dir / "frames.jsonl").string() + " " + extra + " 2>&1";
    FILE* pipe = popen(command.c_str(), "r");
    char buffer[4096];
    while (std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) run.output.append(buffer, n);
    int status = pclose(pipe);
    EXPECT_EQ(WIFEXITED(status) ? WEXITSTATUS(status) : -1, 0) << run.output;
    std::size_t at = run.output.find("layout: window");
    EXPECT_NE(at, std::string::npos) << run.output;
    if (at == std::string::npos) return run;
    int w, h;
    glm::ivec4& v = run.view;
    glm::ivec4& s = run.sidebar;
    glm::ivec4& m = run.marker;
    EXPECT_EQ(std::sscanf(run.output.c_str() + at, "layout: window %dx%d, view %dx%d at %d,%d, side bar %dx%d at %d,%d, marker %dx%d at %d,%d", &w, &h,
                          &v.z, &v.w, &v.x, &v.y, &s.z, &s.w, &s.x, &s.y, &m.z, &m.w, &m.x, &m.y),
              14)
        << run.output;
    EXPECT_EQ(glm::ivec2(w, h), glm::ivec2(1024, 768));
    std::ifstream in(dir / "frames.jsonl");
    for (std::string line; std::getline(in, line);) run.log.push_back(nlohmann::json::parse(line));
    return run;
}

// Frames drawn after the view settled, and how long it stayed settled before exiting.
std::pair<int, double> drawnWhileSettled(const WindowRun& run) {
    double settled = -1, exit = -1;
    int drawn = 0;
    for (const nlohmann::json& e : run.log) {
        if (e["event"] == "settled") settled = e["t"].get<double>();
        else if (e["event"] == "exit") exit = e["t"].get<double>();
        else if (settled >= 0) ++drawn;
    }
    EXPECT_GE(settled, 0) << "the view settled";
    return {drawn, exit - settled};
}

TEST(PanelSessions, TheViewersSideBarLeavesTheViewFreeAndAnIdleWindowDrawsNothing) {
    if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0) GTEST_SKIP() << "xvfb-run is not installed (package xvfb)";
    auto dir = scratch("window");
    // The tools hidden: the view's pixels are then the renderer's image alone, so any difference is a panel.
    auto scene = curette::testing::writeNoisyBallScene(dir, nlohmann::json::parse(R"({"clip_meshes": [
    {"name": "sphere", "mesh": {"shape": "sphere", "radius_mm": 8}, "position_mm": [30, 30, 44]},
    {"name": "box", "mesh": {"shape": "box", "size_mm": [10, 10, 24]}, "position_mm": [22, 40, 24]}],
    "clip_mesh_display": {"show": false}})"));
    auto session = dir / "edits.jsonl";
    recordEditSession(scene, session);
    WindowRun run = runWindow(session, dir, "--idle-seconds 5");
    ASSERT_GT(run.view.z, 0) << run.output;
    EXPECT_GE(static_cast<double>(run.view.z) * run.view.w, 0.75 * 1024 * 768) << "the 3-D view keeps three quarters of the window";
    EXPECT_EQ(run.sidebar.x, run.view.x + run.view.z) << "the side bar is beside the view";
    Png window = readPng(dir / "window.png"), view = readPng(dir / "view.png");
    ASSERT_EQ(glm::ivec2(view.width, view.height), glm::ivec2(run.view.z, run.view.w));
    std::size_t differing = 0, sidebarInk = 0, viewLit = 0;
    auto inMarker = [&](int x, int y) { return x >= run.marker.x && y >= run.marker.y && x < run.marker.x + run.marker.z && y < run.marker.y + run.marker.w; };
    for (int y = 0; y < window.height; ++y)
        for (int x = 0; x < window.width; ++x) {
            const std::uint8_t* w = &window.rgba[(static_cast<std::size_t>(y) * window.width + x) * 4];
            if (x < run.view.z && y < run.view.w) {
                const std::uint8_t* v = &view.rgba[(static_cast<std::size_t>(y) * view.width + x) * 4];
                viewLit += v[0] + v[1] + v[2] > 60;
                if (!inMarker(x, y)) differing += std::abs(w[0] - v[0]) + std::abs(w[1] - v[1]) + std::abs(w[2] - v[2]) > 0;
            } else {
                sidebarInk += w[0] + w[1] + w[2] > 300;   // text and widgets
            }
        }
    EXPECT_EQ(differing, 0u) << "no panel pixel over the 3-D view";
    EXPECT_GT(viewLit, view.rgba.size() / 4 / 50) << "the view shows the ball, so the comparison means something";
    EXPECT_GT(sidebarInk, 500u) << "the side bar shows its panels";
    auto [drawn, settledFor] = drawnWhileSettled(run);
    EXPECT_EQ(drawn, 0) << "an idle window draws nothing";
    EXPECT_GE(settledFor, 5.0);

    // The same session ending in ismos.
    std::ifstream in(session);
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    nlohmann::json last = nlohmann::json::parse(lines.back());
    last["edits"].push_back({{"setting", "shading"}, {"value", "ismos"}});
    lines.back() = last.dump();
    auto ismos = dir / "ismos.jsonl";
    std::ofstream out(ismos);
    for (const std::string& line : lines) out << line << "\n";
    out.close();
    auto ismosDir = dir / "ismos";
    std::filesystem::create_directories(ismosDir);
    WindowRun idle = runWindow(ismos, ismosDir, "--idle-seconds 5");
    auto [ismosDrawn, ismosSettledFor] = drawnWhileSettled(idle);
    EXPECT_EQ(ismosDrawn, 0) << "an idle window in ismos draws nothing";
    EXPECT_GE(ismosSettledFor, 5.0);
}

}  // namespace
}  // namespace curette
