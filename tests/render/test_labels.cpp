// Label volumes in the classification (shaders/labels.glsl, render/label_overlay.h): a label region renders
// where the analytic mask says, a hidden label changes nothing, labels survive empty-space skipping, the AO
// modes see the labels' opacity, and a label's surface reads as the smooth surface its voxels sample.
#include "render/label_overlay.h"
#include "render/renderer.h"
#include "render/lighting.h"
#include "tests/render/gl_test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace curette {
namespace {

using test::glContext;

constexpr int kSize = 40;
const glm::dvec3 kCentre(3.0, -2.0, 1.0);
constexpr double kRadius = 8.0;
constexpr std::uint16_t kId = 5;

// A volume the TF makes fully transparent, so whatever shows is the label.
struct LabelScene {
    VolumeData volume = test::makeVolume(glm::ivec3(kSize), test::centredAffine(glm::ivec3(kSize)), ScalarType::UInt8,
                                         [](glm::dvec3) { return 20.0; });
    TransferFunction tf = test::rampTransferFunction(100, 255, 0.5);  // value 20: opacity 0
    std::vector<std::uint16_t> ids;
    LabelScene() {
        ids.assign(volume.voxelCount(), 0);
        for (int k = 0; k < kSize; ++k)
            for (int j = 0; j < kSize; ++j)
                for (int i = 0; i < kSize; ++i) {
                    glm::dvec3 p(volume.indexToWorld * glm::dvec4(i, j, k, 1));
                    if (glm::length(p - kCentre) <= kRadius) ids[volume.linearIndex(i, j, k)] = kId;
                }
    }
    std::vector<glm::vec4> styles(float opacity) const {
        std::vector<glm::vec4> s(kId + 1, glm::vec4(0.0f));
        s[kId] = glm::vec4(1.0f, 0.1f, 0.1f, opacity);
        return s;
    }
};

FrameDescription frame(ShadingMode mode) {
    FrameDescription f = test::frameLookingAt(glm::dvec3(0.0), 100, 25, 15, {64, 64}, mode);
    f.raycast.stepMm = 0.5;
    return f;
}

// Distance from the sphere centre to the camera ray through pixel (x, y) (row 0 at the top).
double rayDistanceToCentre(const FrameDescription& f, int x, int y) {
    double t = std::tan(glm::radians(f.camera.fovYDeg) / 2);
    double aspect = double(f.size.x) / f.size.y;
    double u = ((x + 0.5) / f.size.x * 2 - 1) * t * aspect, v = (1 - (y + 0.5) / f.size.y * 2) * t;
    glm::dvec3 d = glm::normalize(f.camera.forward() + u * f.camera.right() + v * f.camera.up());
    glm::dvec3 o = f.camera.position();
    glm::dvec3 w = kCentre - o;
    return glm::length(w - glm::dot(w, d) * d);
}

TEST(Labels, ALabelRegionRendersWhereTheAnalyticMaskSays) {
    LabelScene scene;
    Renderer renderer(glContext(), scene.volume, scene.tf);
    renderer.setLabels(std::make_unique<LabelOverlay>(scene.volume.dims, scene.ids, scene.styles(1.0f)));
    FrameDescription f = frame(ShadingMode::Solid);
    ASSERT_TRUE(f.raycast.skipEmptySpace) << "the test must run with empty-space skipping (the TF alone skips everything)";
    renderer.render(f);
    Image image = renderer.readImage();
    int inside = 0, outside = 0;
    for (int y = 0; y < f.size.y; ++y)
        for (int x = 0; x < f.size.x; ++x) {
            double d = rayDistanceToCentre(f, x, y);
            glm::vec4 c = image.at(x, y);
            // A voxel's label covers its cell: the region is the voxelised ball, within a cell diagonal of r.
            if (d < kRadius - 2.0) {
                ++inside;
                ASSERT_GT(c.a, 0.99f) << "pixel " << x << ", " << y << " is " << d << " mm from the centre";
                ASSERT_GT(c.r, 5.0f * c.g) << "pixel " << x << ", " << y << " is not the label's red";
            } else if (d > kRadius + 2.0) {
                ++outside;
                ASSERT_EQ(c.a, 0.0f) << "pixel " << x << ", " << y << " is " << d << " mm from the centre";
            }
        }
    EXPECT_GT(inside, 100);
    EXPECT_GT(outside, 1000);
}

TEST(Labels, AHiddenLabelLeavesTheImageAsWithoutLabels) {
    LabelScene scene;
    scene.tf = test::rampTransferFunction(0, 255, 0.3);  // now the volume itself shows
    FrameDescription f = frame(ShadingMode::Phong);
    Renderer plain(glContext(), scene.volume, scene.tf);
    plain.render(f);
    Image expected = plain.readImage();
    Renderer labelled(glContext(), scene.volume, scene.tf);
    labelled.setLabels(std::make_unique<LabelOverlay>(scene.volume.dims, scene.ids, scene.styles(0.0f)));
    labelled.render(f);
    Image got = labelled.readImage();
    ASSERT_EQ(got.pixels.size(), expected.pixels.size());
    for (std::size_t i = 0; i < got.pixels.size(); ++i) ASSERT_EQ(got.pixels[i], expected.pixels[i]) << "pixel " << i;
    // Showing it changes the image, and styles change without a new overlay.
    labelled.setLabelStyles(scene.styles(0.8f));
    labelled.render(f);
    Image shown = labelled.readImage();
    int changed = 0;
    for (std::size_t i = 0; i < shown.pixels.size(); ++i) changed += shown.pixels[i] != expected.pixels[i];
    EXPECT_GT(changed, 100);
}

TEST(Labels, AmbientOcclusionSeesTheLabelsOpacity) {
    LabelScene scene;
    scene.tf = test::rampTransferFunction(0, 255, 0.02);  // faint tissue, so a label's shadow shows in V_AO
    FrameDescription f = frame(ShadingMode::Lao);
    auto meanAmbientNearTheBall = [&](bool withLabel) {
        Renderer renderer(glContext(), scene.volume, scene.tf);
        LaoSettings lao;
        lao.samples = 6;
        renderer.setLaoSettings(lao);
        if (withLabel) renderer.setLabels(std::make_unique<LabelOverlay>(scene.volume.dims, scene.ids, scene.styles(0.9f)));
        renderer.render(f);
        std::vector<std::uint16_t> ambient = renderer.ambientOcclusion()->readAmbient();
        double sum = 0;
        int n = 0;
        for (int k = 0; k < kSize; ++k)
            for (int j = 0; j < kSize; ++j)
                for (int i = 0; i < kSize; ++i) {
                    glm::dvec3 p(scene.volume.indexToWorld * glm::dvec4(i, j, k, 1));
                    double r = glm::length(p - kCentre);
                    if (r > kRadius + 1 && r < kRadius + 3) sum += ambient[scene.volume.linearIndex(i, j, k)] / 65535.0, ++n;
                }
        return sum / n;
    };
    double without = meanAmbientNearTheBall(false), with = meanAmbientNearTheBall(true);
    EXPECT_LT(with, without - 0.05) << "voxels next to an opaque label must be occluded by it (without " << without << ", with " << with << ")";
}

// A label's surface reads as a surface, not as the staircase of its voxels' cells: the labelled ball (voxels
// whose centres lie within r of the centre) shows as the analytic sphere of radius r, in its silhouette (the
// staircase of cells reaches r + 0.87 mm at their corners) and, in phong, in its shading by the sphere's
// normal (the data inside it is uniform: its gradient says nothing).
TEST(Labels, ALabelSurfaceReadsAsTheSphereItsVoxelsSample) {
    LabelScene scene;
    Renderer labelled(glContext(), scene.volume, scene.tf);
    labelled.setLabels(std::make_unique<LabelOverlay>(scene.volume.dims, scene.ids, scene.styles(1.0f)));
    for (ShadingMode mode : {ShadingMode::Solid, ShadingMode::Phong}) {
        FrameDescription f = frame(mode);
        f.size = glm::ivec2(128, 128);
        f.lights = {Light{}};
        labelled.render(f);
        Image image = labelled.readImage();
        const glm::dvec3 light = worldLightDirection(f.lights[0], f.camera), eye = f.camera.position();
        const TransferFunction::Material& m = scene.tf.material;
        const glm::dvec3 albedo(1.0, 0.1, 0.1);
        int silhouetteWrong = 0, rimPixels = 0, shaded = 0;
        double sum = 0, worst = 0;
        for (int y = 0; y < f.size.y; ++y)
            for (int x = 0; x < f.size.x; ++x) {
                double d = rayDistanceToCentre(f, x, y);
                const glm::vec4& c = image.at(x, y);
                if (std::abs(d - kRadius) > 0.35 && std::abs(d - kRadius) < 1.5) {
                    ++rimPixels;
                    silhouetteWrong += d < kRadius ? c.a < 0.9f : c.a > 0.1f;
                }
                if (mode != ShadingMode::Phong || d > kRadius - 1.5) continue;
                // The sphere's first hit along the pixel's ray and its normal there.
                glm::dvec3 w = kCentre - eye;
                double t = std::tan(glm::radians(f.camera.fovYDeg) / 2), aspect = double(f.size.x) / f.size.y;
                double u = ((x + 0.5) / f.size.x * 2 - 1) * t * aspect, v = (1 - (y + 0.5) / f.size.y * 2) * t;
                glm::dvec3 dir = glm::normalize(f.camera.forward() + u * f.camera.right() + v * f.camera.up());
                double along = glm::dot(w, dir), hit = along - std::sqrt(kRadius * kRadius - d * d);
                glm::dvec3 normal = glm::normalize(eye + hit * dir - kCentre);
                double diffuse = std::max(glm::dot(normal, light), 0.0);
                double specular = diffuse > 0 ? std::pow(std::max(glm::dot(normal, glm::normalize(light - dir)), 0.0), m.specularPower) : 0;
                glm::dvec3 expected = m.ambient * albedo + f.lights[0].color * (m.diffuse * diffuse * albedo + m.specular * specular);
                double e = glm::length(glm::dvec3(c) / double(c.a) - expected) / std::sqrt(3.0);
                sum += e * e;
                worst = std::max(worst, e);
                ++shaded;
            }
        std::printf("[ labels ] %s: %d of %d rim pixels on the wrong side of the sphere's silhouette", shadingModeName(mode), silhouetteWrong, rimPixels);
        if (shaded) std::printf(", colour RMS %.4f (max %.4f) against the sphere's phong over %d pixels", std::sqrt(sum / shaded), worst, shaded);
        std::printf("\n");
        ASSERT_GT(rimPixels, 200);
        EXPECT_LE(silhouetteWrong, rimPixels / 50) << shadingModeName(mode);
        if (mode == ShadingMode::Phong) {
            ASSERT_GT(shaded, 300);
            EXPECT_LT(std::sqrt(sum / shaded), 0.05) << "phong lights the label by the sphere's normal";
        }
    }
}

}  // namespace
}  // namespace curette
