// Label volumes in the classification (shaders/labels.glsl, render/label_overlay.h): a label region renders
// where the analytic mask says, a hidden label changes nothing, labels survive empty-space skipping, and
// the AO modes see the labels' opacity.
#include "render/label_overlay.h"
#include "render/renderer.h"
#include "tests/render/gl_test_support.h"

#include <gtest/gtest.h>

#include <cmath>

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
    FrameDescription f;
    f.camera.target = glm::dvec3(0.0);
    f.camera.distanceMm = 100;
    f.camera.azimuthDeg = 25;
    f.camera.elevationDeg = 15;
    f.camera.fovYDeg = 30;
    f.camera.nearMm = 1;
    f.camera.farMm = 1000;
    f.size = glm::ivec2(64, 64);
    f.shading = mode;
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

}  // namespace
}  // namespace curette
