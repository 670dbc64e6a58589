// The one session step (session/session_step.h) that view, record, replay and the benches share: meshes reach
// the clip set by one path with every per-mesh setting, and every command agrees on when a pose changed.
#include "session/session_step.h"
#include "gl/context.h"
#include "render/renderer.h"

#include <numbers>

#include <gtest/gtest.h>

namespace curette {
namespace {

gl::Context& context() {
    static std::unique_ptr<gl::Context> c = gl::createHeadlessContext();
    c->makeCurrent();
    return *c;
}

InteractionState sceneWithTubeCutter() {
    InteractionState s;
    s.meshes.push_back(MeshState::make(s.nextMeshId++, {.name = "window",
                                                        .geometry = meshFromDescription(R"({"shape": "box", "size_mm": [20, 20, 20]})", "test", "."),
                                                        .clipsTubes = true}));   // scene key clips_tubes
    return s;
}

// Insert (AddMesh) rebuilds the clip set; the scene mesh must still cut tubes afterwards (it did not:
// the second path to the clip set dropped clips_tubes).
TEST(SessionStep, AddingAndRemovingMeshesKeepsClipsTubes) {
    context();
    clip::ClipMeshSet set;
    SessionStep step(sceneWithTubeCutter(), FrameDescription{});
    step.syncTo(set);
    ASSERT_EQ(set.count(), 1);
    EXPECT_TRUE(set.clipsTubes(0));
    StepChanges added = step.apply({input::AddMesh{}}, 100);
    EXPECT_TRUE(added.meshes);
    step.syncTo(set);
    ASSERT_EQ(set.count(), 2);
    EXPECT_TRUE(set.clipsTubes(0)) << "the scene mesh still cuts tubes after Insert";
    EXPECT_FALSE(set.clipsTubes(1)) << "an added mesh does not (as the scene default)";
    step.apply({input::RemoveMesh{1}}, 100);
    step.syncTo(set);
    ASSERT_EQ(set.count(), 1);
    EXPECT_TRUE(set.clipsTubes(0)) << "and after Delete";
}

// A replayed session that adds a mesh (followed from the recorded poses) keeps clips_tubes the same way.
TEST(SessionStep, AReplayedSessionThatAddsAMeshKeepsClipsTubes) {
    context();
    clip::ClipMeshSet set;
    SessionStep step(sceneWithTubeCutter(), FrameDescription{});
    step.syncTo(set);
    SessionFrame f;
    f.size = {64, 48};
    f.meshesAdded.push_back({7, "added 7", InteractionState::addedMeshDescription()});
    f.meshes = {{0, glm::dvec3(0.0), glm::dquat(1, 0, 0, 0), glm::dvec3(1.0)}, {7, glm::dvec3(5, 0, 0), glm::dquat(1, 0, 0, 0), glm::dvec3(1.0)}};
    StepChanges c = step.follow(f, ".", "session line 2");
    EXPECT_TRUE(c.meshes);
    step.syncTo(set);
    ASSERT_EQ(set.count(), 2);
    EXPECT_TRUE(set.clipsTubes(0));
    EXPECT_EQ(step.frame().size, glm::ivec2(64, 48));
}

// The viewer (live actions) and replay (recorded poses) use one definition of "the poses changed", and it
// counts a scale change: the viewer used to ignore scale where replay did not.
TEST(SessionStep, ViewerAndReplayAgreeOnWhenAPoseChanged) {
    SessionStep live(sceneWithTubeCutter(), FrameDescription{});
    EXPECT_FALSE(live.apply({}, 100).poses) << "no action, no change";
    EXPECT_TRUE(live.apply({input::MoveMesh{0, input::MotionFrame::World, {1, 0, 0}, {0, 0, 0}}}, 100).poses);

    SessionStep replayed(sceneWithTubeCutter(), FrameDescription{});
    SessionFrame f;
    f.meshes = {{0, glm::dvec3(0.0), glm::dquat(1, 0, 0, 0), glm::dvec3(1.0)}};
    EXPECT_FALSE(replayed.follow(f, ".", "line 2").poses);
    f.meshes[0].scale = glm::dvec3(1.0, 1.0, 1.5);
    EXPECT_TRUE(replayed.follow(f, ".", "line 3").poses) << "a scale change is a pose change";
    std::vector<SessionMesh> a = replayed.state().sessionPoses(), b = a;
    EXPECT_TRUE(samePoses(a, b));
    b[0].scale.x = 2.0;
    EXPECT_FALSE(samePoses(a, b));
    b = a;
    b[0].id = 3;
    EXPECT_FALSE(samePoses(a, b));
}

// A 32^3 ball of 2 mm voxels for the renderer.
VolumeData ball() {
    glm::ivec3 dims(32);
    std::vector<std::uint8_t> voxels(32 * 32 * 32);
    glm::dmat4 affine(1.0);
    for (int a = 0; a < 3; ++a) affine[a][a] = 2.0;
    affine[3] = glm::dvec4(glm::dvec3(-31.0), 1.0);
    std::size_t i = 0;
    for (int z = 0; z < 32; ++z)
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x, ++i) {
                double r = glm::length(glm::dvec3(x, y, z) - glm::dvec3(15.5));
                voxels[i] = static_cast<std::uint8_t>(r < 7 ? 220 : r < 11 ? 130 : 0);
            }
    return buildVolume("<ball>", dims, ScalarType::UInt8, voxels.data(), false, 1.0, 0.0, affine);
}

// A light move reaches the frame through the session step (so the renderer is no longer showing it) and the
// frame plan then runs only the two ISMOS passes; in cao it re-runs only the ray caster (V_AO does not
// depend on lights).
TEST(SessionStep, ALightMoveReachesTheFrameAndPlansOnlyTheIsmosPasses) {
    context();
    VolumeData volume = ball();
    TransferFunction tf;
    tf.color = {{0, {1, 1, 1}}, {255, {1, 1, 1}}};
    tf.opacity = {{0, 0}, {100, 0}, {140, 0.3}, {255, 0.9}};
    Renderer renderer(context(), volume, tf);
    FrameDescription first;
    first.size = {32, 32};
    first.camera.distanceMm = 250;
    first.lights = {Light{{0.5, 0.5, 0.7}, glm::dvec3(1), true}, Light{{-0.5, 0.2, 0.7}, glm::dvec3(0.5), false}};
    first.ismos.lightSamples = 4;
    first.ismos.testPoints = 8;
    InteractionState state;
    state.shading = ShadingMode::Ismos;
    SessionStep step(state, first);
    EXPECT_EQ(step.state().lights, first.lights) << "a state without lights adopts the frame's";
    renderer.render(step.frame());
    EXPECT_TRUE(renderer.showing(step.frame()));
    StepChanges none = step.apply({}, 32);
    EXPECT_FALSE(none.lights);
    EXPECT_TRUE(renderer.showing(step.frame()));
    StepChanges moved = step.apply({input::NextLight{}, input::MoveLight{-1, {0.2, 0.1}}}, 32);
    EXPECT_TRUE(moved.lights);
    EXPECT_FALSE(moved.poses || moved.meshes || moved.shading);
    EXPECT_NE(step.frame().lights[1].direction, first.lights[1].direction) << "the selected (second) light turned";
    EXPECT_EQ(step.frame().lights[0].direction, first.lights[0].direction);
    EXPECT_FALSE(renderer.showing(step.frame())) << "the moved light is not on screen yet";
    std::vector<Pass> planned;
    for (const PlannedPass& p : renderer.plan(step.frame()).passes) planned.push_back(p.pass);
    EXPECT_EQ(planned, (std::vector<Pass>{Pass::IsmosRayCast, Pass::IsmosOcclusion}));
    renderer.render(step.frame());
    EXPECT_EQ(renderer.ismos()->lightRebuilds(), 2) << "the light samples are rebuilt for the move";

    // In cao, a light move re-runs the ray caster only.
    step.apply({input::SetShading{"cao"}}, 32);
    renderer.render(step.frame());
    step.apply({input::MoveLight{-1, {-0.3, 0.0}}}, 32);
    EXPECT_FALSE(renderer.showing(step.frame()));
    planned.clear();
    for (const PlannedPass& p : renderer.plan(step.frame()).passes) planned.push_back(p.pass);
    EXPECT_EQ(planned, (std::vector<Pass>{Pass::RayCast}));
}

}  // namespace
}  // namespace curette
