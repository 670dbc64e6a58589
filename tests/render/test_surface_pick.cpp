// The first-visible-surface pick (render/reference/surface_pick.h), GL-free: an analytic ball seen from the
// front lands on its surface within half a ray step; a clip mesh carving the front moves the hit behind the
// carve; a ray that misses lands nowhere.
#include "render/reference/surface_pick.h"

#include "mesh/primitives.h"
#include "render/reference/camera_ray.h"
#include "tests/render/gl_test_support.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

namespace curette {
namespace {

const glm::dvec3 kCentre(4.0, -3.0, 7.0);
constexpr double kRadius = 15.0;
constexpr double kStepMm = 0.5;

VolumeData ballVolume() {
    glm::ivec3 dims(40, 36, 28);
    glm::dmat4 affine = glm::translate(glm::dmat4(1.0), kCentre) *
                        glm::rotate(glm::dmat4(1.0), glm::radians(15.0), glm::normalize(glm::dvec3(2, -1, 1))) *
                        glm::scale(glm::dmat4(1.0), glm::dvec3(1.0, 1.1, 1.4)) *
                        glm::translate(glm::dmat4(1.0), -0.5 * glm::dvec3(dims - 1));
    return test::makeVolume(dims, affine, ScalarType::Float32, [](glm::dvec3 p) { return kRadius - glm::length(p - kCentre); });
}

// Opaque where the signed distance is positive: the surface is the ball's.
TransferFunction opaqueInside() {
    TransferFunction tf;
    tf.color = {{-100.0, glm::dvec3(1.0)}};
    tf.opacity = {{0.0, 0.0}, {0.001, 1.0}};
    return tf;
}

FrameDescription anteriorFrame() {
    FrameDescription frame;
    frame.camera.target = kCentre;
    frame.camera.distanceMm = 150.0;
    frame.camera = viewedFrom(frame.camera, StandardView::Anterior);
    frame.size = {64, 64};
    return frame;
}

// The ray's parameters where it enters and leaves a sphere (nothing when it misses).
std::optional<std::pair<double, double>> sphereHits(const reference::CameraRay& ray, glm::dvec3 centre, double radius) {
    glm::dvec3 o = ray.origin - centre;
    double b = glm::dot(o, ray.direction), c = glm::dot(o, o) - radius * radius;
    double disc = b * b - c;
    if (disc < 0) return std::nullopt;
    return std::make_pair(-b - std::sqrt(disc), -b + std::sqrt(disc));
}

TEST(SurfacePick, TheCentrePixelLandsOnTheBallWithinHalfAStep) {
    VolumeData volume = ballVolume();
    FrameDescription frame = anteriorFrame();
    const glm::ivec2 pixel(32, 32);
    auto hit = reference::pickFirstVisible(volume, opaqueInside(), frame, kStepMm, pixel, {});
    ASSERT_TRUE(hit);
    reference::CameraRay ray = reference::cameraRay(frame, pixel);
    auto expected = sphereHits(ray, kCentre, kRadius);
    ASSERT_TRUE(expected);
    glm::dvec3 analytic = ray.origin + expected->first * ray.direction;
    // Half a step, and what trilinear samples of the distance field move its zero (its curvature 1 / R over a
    // cell: (1 + 1.1^2 + 1.4^2) / (8 R) < 0.04 mm).
    EXPECT_LT(glm::length(*hit - analytic), 0.5 * kStepMm + 0.04);
    EXPECT_GT(analytic.y, kCentre.y + kRadius - 0.1);   // the front (anterior) of the ball
}

TEST(SurfacePick, ACarvedFrontMovesTheHitBehindTheCarve) {
    VolumeData volume = ballVolume();
    FrameDescription frame = anteriorFrame();
    const glm::ivec2 pixel(32, 32);
    const glm::dvec3 carveCentre = kCentre + glm::dvec3(0, kRadius, 0);
    const double carveRadius = 6.0;
    auto sphere = std::make_shared<clip::TriangleMesh>(clip::makeSphere(carveRadius));
    plan::PosedMesh mesh{sphere, {}, glm::dvec3(1.0)};
    mesh.pose.position = carveCentre;
    plan::InsideTest carved = plan::insideAnyMesh({mesh});
    auto uncarved = reference::pickFirstVisible(volume, opaqueInside(), frame, kStepMm, pixel, {});
    auto hit = reference::pickFirstVisible(volume, opaqueInside(), frame, kStepMm, pixel, carved);
    ASSERT_TRUE(hit && uncarved);
    reference::CameraRay ray = reference::cameraRay(frame, pixel);
    auto leaves = sphereHits(ray, carveCentre, carveRadius);
    ASSERT_TRUE(leaves);
    glm::dvec3 analytic = ray.origin + leaves->second * ray.direction;   // where the ray leaves the carve
    ASSERT_LT(glm::length(analytic - kCentre), kRadius);                  // inside the ball: the carve's back wall
    // Half a step, the trilinear samples (as above) and the icosphere's facets (inside the sphere by under 0.01 mm).
    EXPECT_LT(glm::length(*hit - analytic), 0.5 * kStepMm + 0.05);
    EXPECT_LT(hit->y, uncarved->y - carveRadius + 1.0);
}

TEST(SurfacePick, ARayThatMissesTheBallLandsNowhere) {
    VolumeData volume = ballVolume();
    FrameDescription frame = anteriorFrame();
    EXPECT_FALSE(reference::pickFirstVisible(volume, opaqueInside(), frame, kStepMm, {1, 1}, {}));
}

}  // namespace
}  // namespace curette
