// Actions applied to the scene (session/interaction.h), and a recording started mid-run from live input: the
// header carries the state at its start, so poses re-derived from its reports match from the first frame.
#include "session/interaction.h"
#include "session/live_input.h"
#include "input/devices/encoders.h"
#include "input/hid/fake_backend.h"

#include "tests/tools/run_curette.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <numbers>
#include <fstream>
#include <sys/wait.h>

namespace curette {
namespace {

InteractionState twoSpheres() {
    InteractionState s;
    for (int i = 0; i < 2; ++i) {
        SceneClipMesh sphere{.name = "sphere " + std::to_string(i), .geometry = meshFromDescription(R"({"shape": "sphere", "radius_mm": 10})", "test", ".")};
        sphere.pose.position = {10.0 * i, 0, 0};
        s.meshes.push_back(MeshState::make(s.nextMeshId++, sphere));
    }
    return s;
}

// Every path that makes a mesh (scene, edit, device, session file) goes through MeshState::make: a scene
// mesh's keys all arrive, and reset_pose returns to the pose it was made with.
TEST(Interaction, AMeshStateKeepsEverySceneKey) {
    SceneClipMesh scene{.name = "cutter", .geometry = meshFromDescription(R"({"shape": "sphere", "radius_mm": 5})", "test", ".")};
    scene.pose.position = {1, 2, 3};
    scene.scale = {2, 1, 0.5};
    scene.clipsTubes = true;
    MeshState m = MeshState::make(7, scene, "{}");
    EXPECT_EQ(m.id, 7);
    EXPECT_EQ(m.name, "cutter");
    EXPECT_EQ(m.description, "{}");
    EXPECT_EQ(m.geometry, scene.geometry);
    EXPECT_EQ(m.pose.position, scene.pose.position);
    EXPECT_EQ(m.initialPose.position, scene.pose.position);
    EXPECT_EQ(m.scale, scene.scale);
    EXPECT_TRUE(m.clipsTubes);
    // A scene's meshes and one an edit adds keep clips_tubes and scale alike.
    InteractionState s;
    s.meshes.push_back(m);
    s.nextMeshId = 8;
    s.applyEdits({{Setting::MeshAdd, -1, nlohmann::json::parse(R"({"mesh": {"shape": "box", "size_mm": [4, 4, 4]}, "clips_tubes": true, "scale": 3})")}},
                 "test");
    ASSERT_EQ(s.meshes.size(), 2u);
    EXPECT_TRUE(s.meshes[1].clipsTubes);
    EXPECT_EQ(s.meshes[1].scale, glm::dvec3(3));
    EXPECT_EQ(s.meshes[1].name, "added 8");
}

TEST(Interaction, CameraFrameMotionDragsResetAddRemoveAndShading) {
    InteractionState s = twoSpheres();
    OrbitCamera camera;
    camera.azimuthDeg = 90;  // looking along another axis: camera right is not world x
    s.apply({input::MoveMesh{1, input::MotionFrame::Camera, {5, 0, 0}, {0, 0, 0}}}, camera, 100);
    glm::dvec3 moved = s.meshes[1].pose.position - s.meshes[1].initialPose.position;
    EXPECT_NEAR(glm::length(moved - 5.0 * camera.right()), 0.0, 1e-12);
    s.apply({input::MoveMesh{0, input::MotionFrame::World, {0, 0, 2}, {0, 0, 0.5}}}, camera, 100);
    EXPECT_EQ(s.meshes[0].pose.position, glm::dvec3(0, 0, 2));
    EXPECT_NEAR(glm::angle(s.meshes[0].pose.orientation), 0.5, 1e-12);
    EXPECT_NEAR(std::abs(glm::axis(s.meshes[0].pose.orientation).z), 1.0, 1e-12);

    // A drag of the full viewport height spans the view's height at the mesh's depth.
    InteractionState d = twoSpheres();
    camera = OrbitCamera{};
    d.apply({input::DragMesh{0, {0, -100}}}, camera, 100);
    double depth = glm::dot(d.meshes[0].initialPose.position - camera.position(), camera.forward());
    EXPECT_NEAR(glm::dot(d.meshes[0].pose.position - d.meshes[0].initialPose.position, camera.up()),
                2 * depth * std::tan(glm::radians(camera.fovYDeg) / 2), 1e-9);

    s.apply({input::ResetPose{1}, input::CycleShading{}}, camera, 100);
    EXPECT_EQ(s.meshes[1].pose, s.meshes[1].initialPose);
    EXPECT_EQ(s.shading, ShadingMode::Lao) << "phong -> lao";
    s.apply({input::SetShading{"dos"}, input::SetShading{"toon"}}, camera, 100);
    EXPECT_EQ(s.shading, ShadingMode::Dos) << "an unknown mode changes nothing";

    s.apply({input::AddMesh{}}, camera, 100);
    ASSERT_EQ(s.meshes.size(), 3u);
    EXPECT_EQ(s.meshes[2].id, 2);
    EXPECT_EQ(s.meshes[2].pose.position, camera.target);
    EXPECT_EQ(s.addedMeshIds, std::vector<int>{2});
    s.apply({input::RemoveMesh{0}, input::MoveMesh{7, input::MotionFrame::World, {1, 1, 1}, {}}}, camera, 100);
    ASSERT_EQ(s.meshes.size(), 2u);
    EXPECT_EQ(s.meshes[0].id, 1) << "ids stay with their meshes";
    EXPECT_EQ(s.removedMeshIds, std::vector<int>{0});
    for (int i = 0; i < 40; ++i) s.apply({input::AddMesh{}}, camera, 100);
    EXPECT_EQ(static_cast<int>(s.meshes.size()), clip::kMaxClipMeshes) << "adding stops at the limit";
}

// MoveLight turns the selected light's direction: yaw about the camera's up axis (towards the right of the
// screen), pitch towards the camera's up, the elevation held within +-89 degrees; a world-space light turns
// in the frame's camera and stays in world space; NextLight cycles; the length is kept.
TEST(Interaction, MoveLightTurnsTheSelectedLightInTheCameraFrame) {
    InteractionState s;
    s.lights = {Light{{0, 0, 2}, glm::dvec3(1), true}, Light{{0, 0, 1}, glm::dvec3(1), false}};
    OrbitCamera camera;
    camera.azimuthDeg = 90;
    camera.elevationDeg = 20;
    const double degree = std::numbers::pi / 180.0;
    s.apply({input::MoveLight{-1, {90 * degree, 0}}}, camera, 100);
    EXPECT_NEAR(glm::length(s.lights[0].direction - glm::dvec3(2, 0, 0)), 0.0, 1e-12) << "a front light turned 90 degrees right is at the right";
    s.apply({input::MoveLight{-1, {0, 30 * degree}}}, camera, 100);
    EXPECT_NEAR(s.lights[0].direction.y, 2 * std::sin(30 * degree), 1e-12) << "raised 30 degrees";
    EXPECT_NEAR(glm::length(s.lights[0].direction), 2.0, 1e-12) << "the length is kept";
    s.apply({input::MoveLight{-1, {0, 100 * degree}}}, camera, 100);
    EXPECT_NEAR(std::asin(s.lights[0].direction.y / 2.0), 89 * degree, 1e-9) << "held below the pole";
    EXPECT_EQ(s.lights[1].direction, glm::dvec3(0, 0, 1)) << "only the selected light turns";

    // A world-space light: turning it is the same motion in the camera's frame.
    s.apply({input::NextLight{}}, camera, 100);
    EXPECT_EQ(s.selectedLight, 1);
    glm::dvec3 world = glm::normalize(glm::dvec3(0.3, -0.5, 0.8));
    s.lights[1].direction = world;
    auto toCamera = [&](glm::dvec3 w) { return glm::dvec3(glm::dot(w, camera.right()), glm::dot(w, camera.up()), -glm::dot(w, camera.forward())); };
    Light asCamera{toCamera(world), glm::dvec3(1), true};
    s.apply({input::MoveLight{-1, {25 * degree, -10 * degree}}}, camera, 100);
    EXPECT_FALSE(s.lights[1].cameraSpace);
    glm::dvec3 expected = turnedLight(asCamera, {25 * degree, -10 * degree}, camera).direction;
    EXPECT_NEAR(glm::length(toCamera(s.lights[1].direction) - expected), 0.0, 1e-12);
    EXPECT_NEAR(std::atan2(expected.x, expected.z) - std::atan2(asCamera.direction.x, asCamera.direction.z), 25 * degree, 1e-12);
    s.apply({input::NextLight{}}, camera, 100);
    EXPECT_EQ(s.selectedLight, 0) << "cycles";
    s.apply({input::MoveLight{5, {1, 1}}}, camera, 100);   // no such light: nothing
    EXPECT_NEAR(glm::length(s.lights[0].direction), 2.0, 1e-12);
}

using curette::testing::Invocation;
Invocation run(const std::string& arguments) { return curette::testing::runCurette(arguments); }

TEST(Interaction, ARecordingStartedMidRunReplaysFromItsReports) {
    auto dir = std::filesystem::temp_directory_path() / ("curette-midrun-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "scene.json") << R"({"volume": {"path": "/usr/share/mricron/templates/ch2.nii.gz"}, "transfer_function": ")"
                                      << CURETTE_SOURCE_DIR << R"(/assets/tf/mri_t1.json",
        "clip_meshes": [{"name": "a", "mesh": {"shape": "sphere", "radius_mm": 20}}, {"name": "b", "mesh": {"shape": "box", "size_mm": [10, 10, 10]}}]})";
    Scene scene = loadScene(dir / "scene.json");
    InteractionState state = InteractionState::fromScene(scene);

    auto ports = std::make_shared<input::FakeHidBackend::Ports>();
    input::HidDeviceDescription pad;
    pad.path = "/dev/hidraw-test", pad.vendorId = 0x054c, pad.productId = 0x0ce6, pad.bus = input::Bus::Usb;
    input::FakeHidBackend::plug(*ports, pad);
    LiveInput live(std::make_unique<input::FakeHidBackend>(ports), input::defaultMapping(), 40.0, 60.0);
    OrbitCamera camera;
    std::unique_ptr<LiveRecording> recording;
    for (int f = 0; f < 60; ++f) {
        input::DeviceState s;
        s.axes[input::LeftX] = 0.8f * std::sin(static_cast<float>(f) * 0.2f);
        s.axes[input::RightY] = 0.6f;
        if (f == 5) s.buttons = 1u << input::South;       // cycle_mesh: the pad now holds mesh 0
        if (f == 12) s.buttons = 1u << input::DpadUp;     // add_mesh
        if (f == 29) s.buttons = 1u << input::North;      // cycle_shading: held while recording starts...
        if (f == 30) s.buttons = 1u << input::North;      // ...so no second press on the first recorded frame
        if (f == 45) s.buttons = 1u << input::DpadDown;   // remove_mesh
        input::FakeHidBackend::queue(*ports, pad.path, input::encodeDualSenseUsb(s));
        input::KeyboardMouseState keys;
        if (f == 35) keys.keys = 1u << static_cast<int>(input::Key::Tab);
        if (f >= 36 && f < 40) keys.keys = 1u << static_cast<int>(input::Key::W);
        double now = f / 30.0;
        InputFrame in = live.step(now, keys, 1 / 30.0, static_cast<int>(state.meshes.size()));
        state.addedMeshIds.clear();
        state.removedMeshIds.clear();
        state.apply(in.actions, camera, 480);
        if (recording) recording->addFrame(now, 1 / 30.0, {640, 480}, camera, state, keys, in);
        if (f == 29) recording = std::make_unique<LiveRecording>(dir / "midrun.jsonl", (dir / "scene.json").string(), state, live, now);
    }
    recording->finish();
    Session session = readSession(dir / "midrun.jsonl", false);
    ASSERT_EQ(session.frames.size(), 30u);
    EXPECT_EQ(session.header.meshes.size(), 3u) << "the added mesh is in the header, with its description";
    EXPECT_FALSE(session.header.meshes[2].description.empty());
    EXPECT_EQ(session.header.inputState.mapper.heldMeshes[1], 0);
    Invocation r = run("replay " + (dir / "midrun.jsonl").string() + " --from-reports --no-render");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("identical"), std::string::npos) << r.output;
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace curette
