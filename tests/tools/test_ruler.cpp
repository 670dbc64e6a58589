// The ruler (viewer/ruler.h) against analytic distances: two points picked in the 3-D view on a ball's surface
// (the first-visible-surface pick the viewer's Ctrl + click uses) measure the distance between where the two
// pixels' rays meet the analytic sphere, within the ruler's stated uncertainty; and its points placement rule.
#include "viewer/ruler.h"

#include "base/volume.h"
#include "render/reference/camera_ray.h"
#include "render/reference/surface_pick.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

namespace curette {
namespace {

const glm::dvec3 kCentre(-6.0, 12.0, 3.0);
constexpr double kRadius = 14.0;
constexpr double kStepMm = 0.4;

// A ball as a signed distance (positive inside) on an anisotropic grid.
VolumeData ballVolume() {
    const glm::ivec3 dims(44, 40, 30);
    const glm::dvec3 spacing(0.9, 1.0, 1.3);
    glm::dmat4 indexToWorld = glm::translate(glm::dmat4(1.0), kCentre) * glm::scale(glm::dmat4(1.0), spacing) *
                              glm::translate(glm::dmat4(1.0), -0.5 * glm::dvec3(dims - 1));
    std::vector<float> values(static_cast<std::size_t>(dims.x) * dims.y * dims.z);
    for (int k = 0; k < dims.z; ++k)
        for (int j = 0; j < dims.y; ++j)
            for (int i = 0; i < dims.x; ++i) {
                glm::dvec3 p(indexToWorld * glm::dvec4(i, j, k, 1.0));
                values[(static_cast<std::size_t>(k) * dims.y + j) * dims.x + i] = static_cast<float>(kRadius - glm::length(p - kCentre));
            }
    std::vector<std::uint8_t> bytes(values.size() * sizeof(float));
    std::memcpy(bytes.data(), values.data(), bytes.size());
    return buildVolume("<ball>", dims, ScalarType::Float32, bytes.data(), false, 1.0, 0.0, indexToWorld);
}

TransferFunction opaqueInside() {
    TransferFunction tf;
    tf.color = {{-100.0, glm::dvec3(1.0)}};
    tf.opacity = {{0.0, 0.0}, {0.001, 1.0}};
    return tf;
}

// Where a pixel's ray enters the analytic sphere.
glm::dvec3 analyticHit(const FrameDescription& frame, glm::ivec2 pixel) {
    reference::CameraRay ray = reference::cameraRay(frame, pixel);
    glm::dvec3 o = ray.origin - kCentre;
    double b = glm::dot(o, ray.direction), c = glm::dot(o, o) - kRadius * kRadius;
    EXPECT_GE(b * b - c, 0.0) << "the pixel's ray meets the ball";
    return ray.origin + (-b - std::sqrt(std::max(0.0, b * b - c))) * ray.direction;
}

TEST(Ruler, TwoPointsPickedOnABallMeasureTheAnalyticDistance) {
    VolumeData volume = ballVolume();
    FrameDescription frame;
    frame.camera.target = kCentre;
    frame.camera.distanceMm = 120.0;
    frame.camera.azimuthDeg = 35.0;
    frame.camera.elevationDeg = 20.0;
    frame.size = {96, 80};
    const std::pair<glm::ivec2, glm::ivec2> pairs[] = {{{48, 40}, {56, 47}}, {{38, 36}, {58, 44}}, {{44, 51}, {52, 29}}};
    for (const auto& [first, second] : pairs) {
        Ruler ruler;
        for (glm::ivec2 pixel : {first, second}) {
            std::optional<glm::dvec3> hit = reference::pickFirstVisible(volume, opaqueInside(), frame, kStepMm, pixel, {});
            ASSERT_TRUE(hit) << pixel.x << "," << pixel.y;
            ruler.place({*hit, 0.5 * kStepMm});
        }
        std::optional<RulerLength> length = ruler.length();
        ASSERT_TRUE(length);
        const double analytic = glm::length(analyticHit(frame, second) - analyticHit(frame, first));
        EXPECT_GT(analytic, 5.0) << "points far enough apart for the comparison to mean something";
        EXPECT_DOUBLE_EQ(length->uncertaintyMm, kStepMm);
        // Each point within half a step of its ray's crossing, and trilinear samples of the distance field move
        // its zero by less than (0.9^2 + 1 + 1.3^2) / (8 R) = 0.032 mm.
        EXPECT_NEAR(length->mm, analytic, length->uncertaintyMm + 2 * 0.032);
    }
}

TEST(Ruler, ASecondPointCompletesItAndAThirdStartsAgain) {
    Ruler ruler;
    EXPECT_FALSE(ruler.length());
    ruler.place({{0, 0, 0}, 0.1});
    EXPECT_FALSE(ruler.length());
    ruler.place({{3, 4, 12}, 0.2});
    ASSERT_TRUE(ruler.length());
    EXPECT_DOUBLE_EQ(ruler.length()->mm, 13.0);
    EXPECT_NEAR(ruler.length()->uncertaintyMm, 0.3, 1e-12);
    ruler.place({{1, 1, 1}, 0.0});
    EXPECT_FALSE(ruler.length()) << "a third point starts a new measurement";
    EXPECT_EQ(ruler.first()->world, glm::dvec3(1, 1, 1));
    ruler.clear();
    EXPECT_FALSE(ruler.first());
}

}  // namespace
}  // namespace curette
