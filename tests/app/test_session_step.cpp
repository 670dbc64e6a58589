// The one session step (app/session_step.h) that view, record, replay and the benches share: meshes reach
// the clip set by one path with every per-mesh setting, and every command agrees on when a pose changed.
#include "app/session_step.h"
#include "gl/context.h"

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
    MeshState m;
    m.id = s.nextMeshId++;
    m.name = "window";
    m.geometry = meshFromDescription(R"({"shape": "box", "size_mm": [20, 20, 20]})", "test", ".");
    m.clipsTubes = true;   // scene key clips_tubes
    s.meshes.push_back(m);
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

}  // namespace
}  // namespace curette
