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

// Each standard view shows the patient as a planner expects (3D Slicer's 3-D view buttons): where a point 10 mm
// to the patient's right, anterior or superior of the target lands on screen (x right, y up, in NDC).
TEST(Camera, StandardViewsShowThePatientTheWaySlicerDoes) {
    struct Expect {
        StandardView view;
        glm::dvec2 right, anterior, superior;   // screen direction of +R, +A, +S (0: along the view axis)
    };
    const Expect expected[] = {
        {StandardView::Anterior, {-1, 0}, {0, 0}, {0, 1}},   // facing the patient: their right on screen left
        {StandardView::Posterior, {1, 0}, {0, 0}, {0, 1}},
        {StandardView::Left, {0, 0}, {-1, 0}, {0, 1}},       // from the left: nose to the screen's left
        {StandardView::Right, {0, 0}, {1, 0}, {0, 1}},
        {StandardView::Superior, {1, 0}, {0, 1}, {0, 0}},    // from above, nose up: their right on the right
        {StandardView::Inferior, {-1, 0}, {0, 1}, {0, 0}},
    };
    OrbitCamera start = obliqueCamera();
    for (const Expect& e : expected) {
        OrbitCamera c = viewedFrom(start, e.view);
        EXPECT_EQ(c.target, start.target);
        EXPECT_EQ(c.distanceMm, start.distanceMm);
        glm::dmat4 vp = c.viewProjection({100, 100});
        auto screen = [&](glm::dvec3 offset) {
            glm::dvec4 p = vp * glm::dvec4(c.target + offset, 1.0), o = vp * glm::dvec4(c.target, 1.0);
            glm::dvec2 d = glm::dvec2(p) / p.w - glm::dvec2(o) / o.w;   // an in-plane 10 mm: about 0.1
            return glm::length(d) < 1e-2 ? glm::dvec2(0) : glm::normalize(d);
        };
        const glm::dvec2 got[] = {screen({10, 0, 0}), screen({0, 10, 0}), screen({0, 0, 10})};
        const glm::dvec2 want[] = {e.right, e.anterior, e.superior};
        for (int axis = 0; axis < 3; ++axis) {
            EXPECT_NEAR(got[axis].x, want[axis].x, 0.05) << standardViewName(e.view) << " axis " << axis;
            EXPECT_NEAR(got[axis].y, want[axis].y, 0.05) << standardViewName(e.view) << " axis " << axis;
        }
    }
}

}  // namespace
}  // namespace curette
