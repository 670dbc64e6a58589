// A tracked controller as an action source (input/tracked_hand.h) applied to the scene (session/interaction.h):
// while squeezed, the held mesh moves rigidly with the grip, turns about it, and stays put otherwise.
#include "input/tracked_hand.h"
#include "session/interaction.h"
#include "session/xr_hands.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <random>

namespace curette {
namespace {

InteractionState oneBox() {
    InteractionState s;
    SceneClipMesh box{.name = "box", .geometry = meshFromDescription(R"({"shape": "box", "size_mm": [4, 6, 8]})", "test", ".")};
    box.pose.position = {30, -10, 5};
    box.pose.orientation = glm::angleAxis(0.4, glm::normalize(glm::dvec3(1, 2, 3)));
    s.meshes.push_back(MeshState::make(s.nextMeshId++, box));
    return s;
}

input::HandSample sample(glm::dvec3 grip, glm::dquat orientation, double squeeze) {
    return {.tracked = true, .gripMm = grip, .gripOrientation = orientation, .squeeze = squeeze, .dtSeconds = 1.0 / 90.0};
}

// The mesh in the grip's frame stays what it was at the grab, whatever the hand does while it holds it.
TEST(TrackedHand, AHeldMeshFollowsTheGripRigidly) {
    InteractionState s = oneBox();
    OrbitCamera camera;
    input::TrackedHand hand(0);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    glm::dvec3 grip(10, 20, 30);
    glm::dquat q = glm::angleAxis(0.3, glm::dvec3(0, 0, 1));
    s.apply(hand.step(sample(grip, q, 1.0)), camera, 100);   // the grab: nothing moves yet
    EXPECT_TRUE(hand.holding());
    const clip::RigidPose start = s.meshes[0].pose;
    const glm::dvec3 local = glm::conjugate(q) * (start.position - grip);
    const glm::dquat localTurn = glm::conjugate(q) * start.orientation;
    for (int i = 0; i < 20; ++i) {
        grip += glm::dvec3(5 * u(rng), 5 * u(rng), 5 * u(rng));
        q = glm::normalize(glm::angleAxis(0.3 * u(rng), glm::normalize(glm::dvec3(u(rng), u(rng), u(rng)))) * q);
        s.apply(hand.step(sample(grip, q, 0.5)), camera, 100);   // 0.5: still held (released below 0.3)
        const clip::RigidPose& now = s.meshes[0].pose;
        EXPECT_LT(glm::length(now.position - (grip + q * local)), 1e-9) << "step " << i;
        glm::dquat turn = glm::conjugate(q) * now.orientation;
        EXPECT_GT(std::abs(glm::dot(turn, localTurn)), 1.0 - 1e-12) << "step " << i;
    }
}

TEST(TrackedHand, SqueezeHysteresisGrabsAndReleases) {
    InteractionState s = oneBox();
    OrbitCamera camera;
    input::TrackedHand hand(0);
    const glm::dquat q(1, 0, 0, 0);
    const glm::dvec3 start = s.meshes[0].pose.position;
    s.apply(hand.step(sample({0, 0, 0}, q, 0.6)), camera, 100);   // below the grab threshold
    s.apply(hand.step(sample({10, 0, 0}, q, 0.6)), camera, 100);
    EXPECT_FALSE(hand.holding());
    EXPECT_EQ(s.meshes[0].pose.position, start);
    s.apply(hand.step(sample({10, 0, 0}, q, 0.8)), camera, 100);   // grabbed
    s.apply(hand.step(sample({15, 0, 0}, q, 0.35)), camera, 100);  // held: above the release threshold
    EXPECT_LT(glm::length(s.meshes[0].pose.position - (start + glm::dvec3(5, 0, 0))), 1e-12);
    s.apply(hand.step(sample({20, 0, 0}, q, 0.2)), camera, 100);   // released: this motion is not the mesh's
    EXPECT_FALSE(hand.holding());
    EXPECT_LT(glm::length(s.meshes[0].pose.position - (start + glm::dvec3(5, 0, 0))), 1e-12);
    // Lost tracking drops the mesh; tracking back while squeezed is a new grab, not a jump.
    s.apply(hand.step(sample({20, 0, 0}, q, 1.0)), camera, 100);
    input::HandSample lost = sample({90, 0, 0}, q, 1.0);
    lost.tracked = false;
    s.apply(hand.step(lost), camera, 100);
    s.apply(hand.step(sample({90, 0, 0}, q, 1.0)), camera, 100);
    EXPECT_LT(glm::length(s.meshes[0].pose.position - (start + glm::dvec3(5, 0, 0))), 1e-12);
}

// A held mesh grows while the stick is up, kScalePerSecond a second at full deflection; a resting stick's drift
// and a mesh not held are left alone.
TEST(TrackedHand, TheThumbstickScalesTheHeldMesh) {
    InteractionState s = oneBox();
    input::TrackedHand hand(0);
    input::HandSample stick = sample({0, 0, 0}, glm::dquat(1, 0, 0, 0), 0.0);
    stick.thumbstickY = 1.0;
    s.apply(hand.step(stick), OrbitCamera{}, 100);   // not held
    EXPECT_EQ(s.meshes[0].scale, glm::dvec3(1.0));
    stick.squeeze = 1.0;
    for (int i = 0; i < 90; ++i) s.apply(hand.step(stick), OrbitCamera{}, 100);   // one second, full up
    EXPECT_NEAR(s.meshes[0].scale.x, input::kScalePerSecond, 1e-9);
    EXPECT_NEAR(s.meshes[0].scale.z, input::kScalePerSecond, 1e-9);
    stick.thumbstickY = -0.5;
    for (int i = 0; i < 90; ++i) s.apply(hand.step(stick), OrbitCamera{}, 100);   // one second, half down
    EXPECT_NEAR(s.meshes[0].scale.y, std::sqrt(input::kScalePerSecond), 1e-9);
    stick.thumbstickY = 0.1;   // within the dead zone
    s.apply(hand.step(stick), OrbitCamera{}, 100);
    EXPECT_NEAR(s.meshes[0].scale.y, std::sqrt(input::kScalePerSecond), 1e-9);
}

TEST(TrackedHand, TheButtonCyclesTheShading) {
    InteractionState s = oneBox();
    s.shading = ShadingMode::Phong;
    input::TrackedHand hand(0);
    input::HandSample pressed = sample({0, 0, 0}, glm::dquat(1, 0, 0, 0), 0.0);
    pressed.cycleShading = true;
    s.apply(hand.step(pressed), OrbitCamera{}, 100);
    EXPECT_EQ(s.shading, nextShadingMode(ShadingMode::Phong));
}

// The trigger drills with the mesh in hand (HoldDrill for the hand's mesh, after its motion), with the squeeze's
// hysteresis; a trigger on an empty hand drills nothing.
TEST(TrackedHand, TheTriggerDrillsWithTheHeldMesh) {
    input::TrackedHand hand(1);
    auto drills = [](const std::vector<input::Action>& actions) {
        int n = 0;
        for (const input::Action& a : actions)
            if (auto* d = std::get_if<input::HoldDrill>(&a)) {
                EXPECT_EQ(d->mesh, 1);
                EXPECT_FALSE(d->erase);
                ++n;
            }
        return n;
    };
    const glm::dquat q(1, 0, 0, 0);
    input::HandSample s = sample({0, 0, 0}, q, 0.0);
    s.trigger = 1.0;
    EXPECT_EQ(drills(hand.step(s)), 0) << "nothing in hand";
    s.squeeze = 1.0;
    s.trigger = 0.6;
    EXPECT_EQ(drills(hand.step(s)), 0) << "below the press threshold";
    s.trigger = 0.75;
    std::vector<input::Action> first = hand.step(s);
    EXPECT_EQ(drills(first), 1);
    EXPECT_TRUE(std::holds_alternative<input::HoldDrill>(first.back()));
    s.trigger = 0.35;   // held: above the release threshold
    s.gripMm = {3, 0, 0};
    std::vector<input::Action> moved = hand.step(s);
    EXPECT_EQ(drills(moved), 1);
    ASSERT_EQ(moved.size(), 2u);
    EXPECT_TRUE(std::holds_alternative<input::GripMesh>(moved.front())) << "the drill sweeps to where the hand moved the mesh";
    s.trigger = 0.25;
    EXPECT_EQ(drills(hand.step(s)), 0) << "released";
    EXPECT_FALSE(hand.drilling());
    s.trigger = 1.0;
    s.squeeze = 0.0;   // let go of the mesh: no drilling with it
    EXPECT_EQ(drills(hand.step(s)), 0);
}


// The erase button erases with the mesh in hand (HoldDrill with erase), the trigger winning when both are held
// (the gamepad's rule, input::heldDrill); an empty hand erases nothing.
TEST(TrackedHand, TheEraseButtonErasesWithTheHeldMesh) {
    input::TrackedHand hand(0);
    auto drill = [](const std::vector<input::Action>& actions) -> std::optional<input::HoldDrill> {
        for (const input::Action& a : actions)
            if (auto* d = std::get_if<input::HoldDrill>(&a)) return *d;
        return std::nullopt;
    };
    input::HandSample s = sample({0, 0, 0}, glm::dquat(1, 0, 0, 0), 0.0);
    s.erase = true;
    EXPECT_FALSE(drill(hand.step(s))) << "nothing in hand";
    s.squeeze = 1.0;
    std::optional<input::HoldDrill> d = drill(hand.step(s));
    ASSERT_TRUE(d);
    EXPECT_TRUE(d->erase);
    EXPECT_EQ(d->mesh, 0);
    s.trigger = 1.0;
    d = drill(hand.step(s));
    ASSERT_TRUE(d);
    EXPECT_FALSE(d->erase) << "drill over erase";
    s.trigger = 0.0;
    s.erase = false;
    EXPECT_FALSE(drill(hand.step(s)));
}

// A sideways flick of the thumbstick undoes (left) or redoes (right) once, until the stick comes back towards
// the centre; a push mostly up or down scales and undoes nothing; sessions before version 7 have no flicks.
TEST(TrackedHand, AThumbstickFlickUndoesOrRedoesOnce) {
    auto history = [](const std::vector<input::Action>& actions) {
        std::string h;
        for (const input::Action& a : actions) {
            if (std::holds_alternative<input::Undo>(a)) h += "u";
            if (std::holds_alternative<input::Redo>(a)) h += "r";
        }
        return h;
    };
    input::TrackedHand hand(0);
    input::HandSample s = sample({0, 0, 0}, glm::dquat(1, 0, 0, 0), 0.0);
    std::string seen;
    for (double x : {0.0, -0.5, -0.8, -1.0, -0.5, -0.9, -0.2, -0.9, 0.0, 0.75, 0.4, 0.25, 0.8}) {
        s.thumbstickX = x;
        seen += history(hand.step(s));
    }
    EXPECT_EQ(seen, "uurr");
    s.thumbstickX = 0.0;
    hand.step(s);
    s.thumbstickX = -0.8;
    s.thumbstickY = 0.9;   // mostly up: a scale, not a flick
    EXPECT_EQ(history(hand.step(s)), "");
    input::TrackedHand old(0, false);
    s.thumbstickY = 0.0;
    EXPECT_EQ(history(old.step(s)), "") << "a version 6 recording";
}

// A hand holding its volume button carries the whole scene in the room (session/xr_hands.h): its grip keeps
// its place on the anatomy (the same world point and turn, to rounding), a point fixed in the world moves in
// the room with the grip, and neither hand's mesh moves in world space, so nothing of the carve changes.
TEST(XrHands, TheVolumeButtonCarriesTheSceneAndNothingMovesInWorld) {
    VolumeGeometry g{glm::ivec3(64, 64, 48), glm::dmat4(1.0)};
    const RoomAnchor table = tableAnchor(g, RoomSpace::Stage);
    XrHands hands(table);
    std::array<SessionXrHand, 2> h{};
    h[0].tracked = true;
    h[0].grip.positionM = {-0.1, 1.0, -0.4};
    h[0].moveVolume = true;
    h[0].squeeze = 1.0;   // holding its tool too: the tool rides along, it does not move on the anatomy
    h[1].tracked = true;
    h[1].grip.positionM = {0.1, 1.0, -0.4};
    const glm::dvec3 world = table.roomToWorldMm(glm::dvec3(0.02, 0.95, -0.45));
    auto gripMoves = [](const std::vector<input::Action>& actions) {
        return std::count_if(actions.begin(), actions.end(), [](const input::Action& a) { return std::holds_alternative<input::GripMesh>(a); });
    };
    EXPECT_EQ(gripMoves(hands.step(h, 0.0)), 0);
    EXPECT_EQ(hands.anchor(), table) << "a grab's first frame moves nothing";
    const glm::dvec3 gripWorld = table.roomToWorldMm(h[0].grip.positionM);
    glm::dquat turn(1, 0, 0, 0);
    glm::dvec3 roomPoint = glm::dvec3(0.02, 0.95, -0.45);
    for (int i = 1; i <= 6; ++i) {
        const TrackedView before = h[0].grip;
        h[0].grip.positionM += glm::dvec3(0.01 * i, -0.005, 0.02);
        const glm::dquat step = glm::angleAxis(0.1, glm::normalize(glm::dvec3(0.2, 1.0, 0.3)));
        h[0].grip.orientation = glm::normalize(step * h[0].grip.orientation);
        turn = step * turn;
        roomPoint = step * (roomPoint - before.positionM) + h[0].grip.positionM;
        EXPECT_EQ(gripMoves(hands.step(h, 1.0 / 90.0)), 0) << i;
        ASSERT_EQ(hands.volumeHand(), 0);
        const RoomAnchor& a = hands.anchor();
        EXPECT_LT(glm::length(a.roomToWorldMm(h[0].grip.positionM) - gripWorld), 1e-9) << i;
        EXPECT_LT(glm::length(a.roomToWorldMm(roomPoint) - world), 1e-9) << i << ": a world point rides with the grip";
        EXPECT_GT(std::abs(glm::dot(a.volumeTurnRoom, turn)), 1.0 - 1e-12) << i;
        EXPECT_EQ(a.volumeCentreWorldMm, table.volumeCentreWorldMm);
    }
    // Let go: the volume stays where it was left; the other hand's button now carries it.
    const RoomAnchor left = hands.anchor();
    h[0].moveVolume = false;
    h[1].moveVolume = true;
    hands.step(h, 1.0 / 90.0);
    EXPECT_EQ(hands.anchor(), left);
    EXPECT_EQ(hands.volumeHand(), 1);
}

}  // namespace
}  // namespace curette
