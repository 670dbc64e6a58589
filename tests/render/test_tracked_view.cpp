// A head-mounted display's eyes as curette renders them (render/model/tracked_view.h, render/stereo_render.h):
// the rolled camera, the volume on its table in the room, that each kept pixel of an eye's symmetric frame is
// the ray the runtime's asymmetric field of view puts through it, and that both eyes share one V_AO.
#include "render/model/camera.h"
#include "render/model/stereo.h"
#include "render/model/tracked_view.h"
#include "render/reference/camera_ray.h"
#include "render/stereo_render.h"
#include "tests/render/moving_sphere_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace curette {
namespace {

VolumeGeometry headBox() {
    VolumeGeometry g;
    g.dims = {90, 110, 80};
    g.indexToWorld = glm::dmat4(1.0);
    g.indexToWorld[0][0] = 2.0;
    g.indexToWorld[1][1] = 2.0;
    g.indexToWorld[2][2] = 2.5;
    g.indexToWorld[3] = glm::dvec4(-90, -126, -72, 1);
    return g;
}

// The unit ray of an eye through pixel (x, y) of its kept image, from the runtime's side: the field of view's
// tangents across the image, turned by the eye's orientation, in the room.
glm::dvec3 roomRay(const TrackedView& v, const FieldOfView& fov, glm::ivec2 size, glm::dvec2 pixel) {
    double tl = std::tan(fov.angleLeft), tr = std::tan(fov.angleRight), tu = std::tan(fov.angleUp), td = std::tan(fov.angleDown);
    glm::dvec3 eyeSpace(tl + (tr - tl) * (pixel.x / size.x), tu - (tu - td) * (pixel.y / size.y), -1.0);
    return glm::normalize(v.orientation * eyeSpace);
}

TEST(TrackedView, RollTurnsUpTowardsRightAndKeepsTheFrameRightHanded) {
    OrbitCamera c;
    c.azimuthDeg = 40;
    c.elevationDeg = -25;
    OrbitCamera rolled = c;
    rolled.rollDeg = 30;
    EXPECT_LT(glm::length(rolled.forward() - c.forward()), 1e-15);
    EXPECT_NEAR(glm::dot(rolled.up(), c.right()), std::sin(glm::radians(30.0)), 1e-12);
    EXPECT_NEAR(glm::dot(rolled.up(), c.up()), std::cos(glm::radians(30.0)), 1e-12);
    EXPECT_LT(glm::length(glm::cross(rolled.forward(), rolled.up()) - rolled.right()), 1e-12);
    EXPECT_NEAR(glm::dot(rolled.up(), rolled.right()), 0.0, 1e-12);
    // No roll: the same vectors bit for bit as before rolls existed (every image stays the same).
    EXPECT_TRUE(c.up() == glm::cross(glm::normalize(glm::cross(c.forward(), glm::dvec3(0, 0, 1))), c.forward()));
}

TEST(TrackedView, TheVolumeStandsOnTheTableFacingTheUser) {
    VolumeGeometry g = headBox();
    RoomAnchor stage = tableAnchor(g, RoomSpace::Stage), local = tableAnchor(g, RoomSpace::Local);
    double lowest = 1e9;
    for (glm::dvec3 corner : g.worldCorners()) lowest = std::min(lowest, corner.z);
    // The lowest corner, mapped into the room, lies on the table.
    glm::dvec3 centre = g.worldCenter();
    double lowestRoomY = stage.volumeCentreRoomM.y - (centre.z - lowest) / 1000.0;
    EXPECT_NEAR(lowestRoomY, kTableHeightM, 1e-12);
    EXPECT_NEAR(stage.volumeCentreRoomM.z, -kTableDistanceM, 1e-12);
    EXPECT_NEAR(local.volumeCentreRoomM.y, stage.volumeCentreRoomM.y - kStandingEyeHeightM, 1e-12);
    // Real size, anterior towards the user (+z), the patient's right on the user's left (-x), superior up.
    EXPECT_LT(glm::length(stage.roomToWorldMm(stage.volumeCentreRoomM + glm::dvec3(0, 0, 0.01)) - (centre + glm::dvec3(0, 10, 0))), 1e-9);
    EXPECT_LT(glm::length(stage.roomToWorldMm(stage.volumeCentreRoomM + glm::dvec3(-0.01, 0, 0)) - (centre + glm::dvec3(10, 0, 0))), 1e-9);
    EXPECT_LT(glm::length(stage.roomToWorldMm(stage.volumeCentreRoomM + glm::dvec3(0, 0.01, 0)) - (centre + glm::dvec3(0, 0, 10))), 1e-9);
}

// Every kept pixel's ray (the renderer's, through the symmetric frame) is the ray the runtime's field of view
// puts through that pixel, for random head poses (rolled and pitched) and asymmetric fields of view.
TEST(TrackedView, EachKeptPixelIsTheRuntimesRayThroughIt) {
    VolumeGeometry g = headBox();
    RoomAnchor anchor = tableAnchor(g, RoomSpace::Stage);
    std::mt19937 rng(34);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    FrameDescription base;
    for (int trial = 0; trial < 40; ++trial) {
        TrackedView v;
        v.positionM = {0.2 * u(rng), 1.5 + 0.2 * u(rng), 0.1 * u(rng)};
        glm::dvec3 axis = glm::normalize(glm::dvec3(u(rng), u(rng), u(rng)));
        v.orientation = glm::angleAxis(0.8 * u(rng), axis);
        v.fov = {-0.9 + 0.2 * u(rng), 0.7 + 0.2 * u(rng), 0.8 + 0.1 * u(rng), -0.9 + 0.1 * u(rng)};
        glm::ivec2 recommended(80 + trial, 72 + trial / 2);
        TrackedEye eye = trackedEye(base, v, anchor, recommended);
        ASSERT_LE(eye.size.x, recommended.x);
        ASSERT_LE(eye.size.y, recommended.y);
        // The axis that sets the pitch fills the recommended image but for the two edges moved inwards.
        EXPECT_TRUE(eye.size.x >= recommended.x - 2 || eye.size.y >= recommended.y - 2) << eye.size.x << "x" << eye.size.y;
        ASSERT_LE(eye.cropOrigin.x + eye.size.x, eye.frame.size.x);
        ASSERT_LE(eye.cropOrigin.y + eye.size.y, eye.frame.size.y);
        // The rendered field of view lies within the located one, less than a pixel inside.
        EXPECT_GE(eye.renderedFov.angleLeft, v.fov.angleLeft - 1e-9);
        EXPECT_LE(eye.renderedFov.angleRight, v.fov.angleRight + 1e-9);
        EXPECT_LE(eye.renderedFov.angleUp, v.fov.angleUp + 1e-9);
        EXPECT_GE(eye.renderedFov.angleDown, v.fov.angleDown - 1e-9);
        EXPECT_LT(glm::length(eye.frame.camera.position() - anchor.roomToWorldMm(v.positionM)), 1e-6);
        for (glm::ivec2 pixel : {glm::ivec2(0, 0), glm::ivec2(eye.size.x - 1, 0), glm::ivec2(0, eye.size.y - 1), eye.size - 1, eye.size / 2}) {
            reference::CameraRay ray = reference::cameraRay(eye.frame, eye.cropOrigin + pixel);
            glm::dvec3 expected = RoomAnchor::roomDirectionToWorld(roomRay(v, eye.renderedFov, eye.size, glm::dvec2(pixel) + 0.5));
            EXPECT_LT(glm::length(ray.direction - expected), 1e-9) << "trial " << trial << " pixel " << pixel.x << "," << pixel.y;
        }
    }
}

// The monitor's off-axis pair, located as a runtime would give it (each eye's pose and asymmetric field of
// view), is rendered as the stereo rig renders it: the same symmetric frame size and the same kept columns.
TEST(TrackedView, TheStereoRigsEyesAsTrackedViewsAreTheRigsFrames) {
    VolumeGeometry g = headBox();
    RoomAnchor anchor = tableAnchor(g, RoomSpace::Stage);
    FrameDescription centre;
    centre.size = {64, 48};
    centre.camera.fovYDeg = 30;
    centre.camera.distanceMm = 450;
    centre.camera.target = g.worldCenter();
    StereoRig rig = stereoRig(centre, 65.0);
    const double pitch = 2.0 * std::tan(glm::radians(15.0)) / centre.size.y;
    const int w = centre.size.x, k = rig.marginColumns;
    // The user looks at the volume's face from 0.45 m in front of it, level (azimuth 0 looks along -A: room -z).
    for (Eye e : {Eye::Left, Eye::Right}) {
        TrackedView v;
        v.positionM = anchor.volumeCentreRoomM + glm::dvec3(e == Eye::Left ? -0.0325 : 0.0325, 0, 0.45);
        int left = e == Eye::Left ? k - w / 2 : -(w / 2 + k);
        v.fov = {std::atan(left * pitch), std::atan((left + w) * pitch), std::atan(24 * pitch), std::atan(-24 * pitch)};
        TrackedEye eye = trackedEye(centre, v, anchor, centre.size);
        FrameDescription expected = rig.eyeFrame(e);
        EXPECT_EQ(eye.frame.size, expected.size);
        EXPECT_EQ(eye.cropOrigin, glm::ivec2(rig.firstColumn(e), 0));
        EXPECT_EQ(eye.size, centre.size);
        EXPECT_NEAR(eye.frame.camera.fovYDeg, 30.0, 1e-9);
        EXPECT_LT(glm::length(eye.frame.camera.position() - expected.camera.position()), 1e-9);
        EXPECT_LT(glm::length(eye.frame.camera.forward() - expected.camera.forward()), 1e-12);
        EXPECT_LT(glm::length(eye.frame.camera.up() - expected.camera.up()), 1e-12);
    }
}

// CAO runs once a frame: after the left eye, the right eye's plan is the ray cast alone (V_PAO, V_AO and the
// clip maps are current: none depends on the view), and its image is a fresh renderer's.
TEST(TrackedView, BothEyesShareOneAmbientOcclusionVolume) {
    test::MovingSphereScene scene;
    RoomAnchor anchor = tableAnchor(scene.renderer->geometry(), RoomSpace::Stage);
    std::array<TrackedEye, 2> eyes;
    for (int e = 0; e < 2; ++e) {
        TrackedView v;
        v.positionM = anchor.volumeCentreRoomM + glm::dvec3(e == 0 ? -0.032 : 0.032, 0.03, 0.12);
        v.orientation = glm::angleAxis(-0.2, glm::dvec3(1, 0, 0));
        v.fov = {e == 0 ? -0.35 : -0.28, e == 0 ? 0.28 : 0.35, 0.3, -0.32};
        eyes[static_cast<std::size_t>(e)] = trackedEye(scene.frame, v, anchor, {40, 36});
    }
    renderTrackedEye(*scene.renderer, eyes[0]);
    EXPECT_TRUE(scene.renderer->lastPlan().runs(Pass::VoxelClipping));
    EXPECT_TRUE(scene.renderer->lastPlan().runs(Pass::LaoRecompute));
    Image right = renderTrackedEye(*scene.renderer, eyes[1]);
    ASSERT_EQ(scene.renderer->lastPlan().passes.size(), 1u) << scene.renderer->lastPlan().describe();
    EXPECT_TRUE(scene.renderer->lastPlan().runs(Pass::RayCast));
    test::MovingSphereScene fresh;
    EXPECT_TRUE(test::sameImage(right, renderTrackedEye(*fresh.renderer, eyes[1])));
    // Not a blank view: the blobs are in it.
    int opaque = 0;
    for (const glm::vec4& p : right.pixels) opaque += p.a > 0.05f;
    EXPECT_GT(opaque, static_cast<int>(right.pixels.size()) / 10);
}

TEST(TrackedView, CropImageKeepsTheRectangle) {
    Image image;
    image.width = 5;
    image.height = 4;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 5; ++x) image.pixels.push_back(glm::vec4(float(x), float(y), 0, 1));
    Image crop = cropImage(image, {1, 2}, {3, 2});
    ASSERT_EQ(crop.width, 3);
    ASSERT_EQ(crop.height, 2);
    EXPECT_EQ(crop.at(0, 0), glm::vec4(1, 2, 0, 1));
    EXPECT_EQ(crop.at(2, 1), glm::vec4(3, 3, 0, 1));
    EXPECT_THROW(cropImage(image, {3, 0}, {3, 1}), std::logic_error);
}

}  // namespace
}  // namespace curette
