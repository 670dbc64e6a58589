// The camera's two formulas every pass, shader binder and CPU reference shares (render/model/camera.h).
#include "render/model/camera.h"
#include "render/model/frame.h"
#include "render/reference/camera_ray.h"
#include "render/reference/stereo_match.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>

namespace curette {
namespace {

OrbitCamera obliqueCamera() {
    OrbitCamera c;
    c.target = {3, -2, 5};
    c.azimuthDeg = 37;
    c.elevationDeg = -21;
    c.fovYDeg = 41;
    c.distanceMm = 250;
    c.nearMm = 20;
    c.farMm = 900;
    return c;
}

// The matrix is projection(width / height) * view, bit for bit: the images made before it was one function
// stay the same.
TEST(Camera, ViewProjectionIsProjectionAtTheImageAspectTimesView) {
    OrbitCamera c = obliqueCamera();
    for (glm::ivec2 size : {glm::ivec2(256, 192), glm::ivec2(97, 311), glm::ivec2(1, 1)}) {
        glm::dmat4 expected = c.projection(double(size.x) / size.y) * c.view();
        EXPECT_TRUE(c.viewProjection(size) == expected) << size.x << "x" << size.y;
    }
}

// A millimetre across the view at depth z spans pixelsPerMmAtUnitDepth / z pixels of the projected image.
TEST(Camera, PixelsPerMillimetreIsWhatTheProjectionShows) {
    OrbitCamera c = obliqueCamera();
    FrameDescription frame;
    frame.camera = c;
    frame.size = {320, 200};
    const double depth = 180;
    glm::dvec3 centre = c.position() + depth * c.forward();
    glm::dvec2 a = projectToPixel(frame, centre), b = projectToPixel(frame, centre + c.up());
    EXPECT_NEAR(glm::length(b - a), c.pixelsPerMmAtUnitDepth(frame.size.y) / depth, 1e-9);
    EXPECT_NEAR(c.pixelsPerMmAtUnitDepth(200), 200 / (2 * std::tan(glm::radians(41.0) / 2)), 1e-12);
}

// The CPU reference's ray through a pixel centre lands on that pixel again.
TEST(Camera, CameraRayAndProjectionAgree) {
    FrameDescription frame;
    frame.camera = obliqueCamera();
    frame.size = {64, 48};
    for (glm::ivec2 pixel : {glm::ivec2(0, 0), glm::ivec2(63, 0), glm::ivec2(31, 20), glm::ivec2(5, 47)}) {
        reference::CameraRay ray = reference::cameraRay(frame, pixel);
        glm::dvec2 p = projectToPixel(frame, ray.origin + 300.0 * ray.direction);
        EXPECT_NEAR(p.x, pixel.x + 0.5, 1e-6);
        EXPECT_NEAR(p.y, pixel.y + 0.5, 1e-6);
    }
}

}  // namespace
}  // namespace curette
