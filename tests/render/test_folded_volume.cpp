// Scans beyond one 3D texture (render/model/volume_layout.h): a volume folded into pieces renders what the
// same volume renders unfolded, in every mode, CAO equals full LAO on it, drilling and labels follow the
// layout, and a volume over llvmpipe's real limit opens and renders. The fold is forced on small volumes with
// CURETTE_MAX_3D_TEXTURE_SIZE (GpuVolume::textureSizeLimit), so the tests stay small.
#include "mesh/primitives.h"
#include "plan/drill_sweep.h"
#include "render/label_overlay.h"
#include "render/renderer.h"
#include "tests/render/gl_test_support.h"

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>

namespace curette {
namespace {

using test::glContext;

// Renderers made while it lives fold any axis longer than `limit`.
struct ForcedTextureLimit {
    explicit ForcedTextureLimit(int limit) { setenv("CURETTE_MAX_3D_TEXTURE_SIZE", std::to_string(limit).c_str(), 1); }
    ~ForcedTextureLimit() { unsetenv("CURETTE_MAX_3D_TEXTURE_SIZE"); }
};

// Blobs along a long z axis, several across the fold at z = 0 (voxel 35 of 70).
double longBlobs(glm::dvec3 p) {
    const glm::dvec4 centres[] = {{-3, -2, 0.3, 5}, {4, 3, -20, 5}, {1, -4, 18, 4}, {0, 4, -2, 4}, {-2, 1, 29, 4}};
    double v = 0;
    for (const glm::dvec4& c : centres) v += 240.0 * std::exp(-glm::dot(p - glm::dvec3(c), p - glm::dvec3(c)) / (2 * c.w * c.w));
    return std::min(v, 255.0);
}

const glm::ivec3 kDims(24, 20, 70);
constexpr int kLimit = 64;   // z folds into 2 pieces of 36 along y (VolumeLayout.TheLongAxisFoldsAlongTheShortestOtherAxis)

struct LongScene {
    VolumeData volume;
    std::unique_ptr<Renderer> renderer;
    FrameDescription frame;
    LongScene(bool folded, double azimuth = 75) {
        glContext();
        volume = test::makeVolume(kDims, test::centredAffine(kDims), ScalarType::UInt8, longBlobs);
        {
            std::optional<ForcedTextureLimit> limit;   // while the renderer picks its layout
            if (folded) limit.emplace(kLimit);
            renderer = std::make_unique<Renderer>(glContext(), volume, test::rampTransferFunction(30, 180, 0.3));
        }
        EXPECT_EQ(renderer->volumeLayout().folded(), folded);
        // A folded scan keeps phong's six gradient reads (render/gradient_volume.h): the unfolded one takes them
        // too, so these tests compare the layouts alone.
        renderer->setGradientVolume(false);
        renderer->setLaoSettings(test::lightLao(5));
        frame.camera.fit(glm::dvec3(0), 0.55 * glm::length(glm::dvec3(kDims)) / 2);
        frame.camera.azimuthDeg = azimuth;
        frame.camera.elevationDeg = 15;
        frame.size = {40, 64};
    }
    using Result = test::AmbientAndImage;
    Result render(ShadingMode mode) {
        frame.shading = mode;
        return test::renderAmbientAndImage(*renderer, frame);
    }
};

struct Difference {
    double maxPixel = 0;            // largest difference of any channel of any pixel
    int differingPixels = 0;
    int maxAmbient = 0;             // largest difference of V_AO (unorm16 steps)
    std::size_t differingVoxels = 0;
};

Difference differenceOf(const LongScene::Result& a, const LongScene::Result& b) {
    Difference d;
    EXPECT_EQ(a.image.pixels.size(), b.image.pixels.size());
    for (std::size_t i = 0; i < a.image.pixels.size() && i < b.image.pixels.size(); ++i) {
        double m = 0;
        for (int c = 0; c < 4; ++c) m = std::max(m, double(std::abs(a.image.pixels[i][c] - b.image.pixels[i][c])));
        d.maxPixel = std::max(d.maxPixel, m);
        d.differingPixels += m > 0;
    }
    EXPECT_EQ(a.ambient.size(), b.ambient.size());
    for (std::size_t i = 0; i < a.ambient.size() && i < b.ambient.size(); ++i) {
        int m = std::abs(int(a.ambient[i]) - int(b.ambient[i]));
        d.maxAmbient = std::max(d.maxAmbient, m);
        d.differingVoxels += m > 0;
    }
    return d;
}

bool anyVisible(const Image& image) {
    for (const glm::vec4& p : image.pixels)
        if (p.a > 0.05f) return true;
    return false;
}

void setSphere(Renderer& r, glm::dvec3 at) {
    static auto sphere = std::make_shared<const clip::TriangleMesh>(clip::makeSphere(5.0, 3));
    if (r.clipMeshes().count() == 0) r.clipMeshes().add(sphere, glm::dvec3(1.0), {}, "sphere");
    r.clipMeshes().setPose(0, clip::RigidPose{at, {}});
}

// The folded volume's images against the unfolded render of the same volume, in solid, phong, lao and cao,
// with a clip sphere over the fold. Trilinear weights come from the folded coordinate, (t - piece start) /
// piece length, which the GPU scales back by the piece length: rounding can move a weight by an ulp, and an
// ulp of a weight moves a value by far less than a unorm8/unorm16 step, so V_AO agrees to one unorm16 step and
// the images to 1e-4 (llvmpipe filters with 8-bit weights: a rounding that crosses a weight step shows).
TEST(FoldedVolume, ImagesEqualTheUnfoldedRenderInEveryMode) {
    LongScene unfolded(false), folded(true);
    for (LongScene* s : {&unfolded, &folded}) setSphere(*s->renderer, glm::dvec3(2, 1, 1.5));
    for (ShadingMode mode : {ShadingMode::Solid, ShadingMode::Phong, ShadingMode::Lao, ShadingMode::Cao}) {
        LongScene::Result a = unfolded.render(mode), b = folded.render(mode);
        ASSERT_TRUE(anyVisible(a.image));
        Difference d = differenceOf(a, b);
        std::printf("[ fold ] %s: max pixel difference %.3g (%d of %zu pixels differ), V_AO max %d unorm16 steps (%zu voxels differ)\n",
                    traits(mode).name, d.maxPixel, d.differingPixels, a.image.pixels.size(), d.maxAmbient, d.differingVoxels);
        EXPECT_LE(d.maxPixel, 1e-4) << traits(mode).name;
        EXPECT_LE(d.maxAmbient, 1) << traits(mode).name;
    }
}

// CAO == full LAO, bit for bit, on the folded volume while a sphere moves across the fold: the voxels on the
// cut are written to both pieces by every pass, or CAO's partial updates would leave a stale copy that full
// LAO does not.
TEST(FoldedVolume, CaoEqualsFullLaoAfterMeshMoves) {
    LongScene cao(true), lao(true);
    int partial = 0;
    for (int i = 0; i < 8 && !HasFailure(); ++i) {
        glm::dvec3 at(2.0 * std::sin(i), 1.0, -12.0 + 3.5 * i);   // walks through z = 0, the cut
        setSphere(*cao.renderer, at);
        setSphere(*lao.renderer, at);
        LongScene::Result c = cao.render(ShadingMode::Cao), l = lao.render(ShadingMode::Lao);
        const AmbientOcclusionStats& stats = cao.renderer->ambientOcclusion()->lastStats();
        partial += stats.dispatched < stats.voxels;
        test::expectSameAmbientAndImage(l.ambient, l.image, c.ambient, c.image, "sphere at z " + std::to_string(at.z));
    }
    EXPECT_GT(partial, 4) << "most CAO updates must visit part of the volume for the test to mean something";
}

// Drilling and labels write and read the folded textures: a drilled stroke across the cut, and a label over
// it, give the unfolded render's image (same tolerance as above).
TEST(FoldedVolume, ADrilledStrokeAndLabelsEqualTheUnfoldedRender) {
    LongScene unfolded(false), folded(true);
    auto removal = std::make_shared<plan::RemovalVolume>(kDims, test::centredAffine(kDims));
    plan::DrillTool tool{clip::SolidShape{clip::SolidShape::Kind::Sphere, 2.5, 4.0}};
    plan::DrillSweep sweep(tool, clip::RigidPose{glm::dvec3(-3, -2, -6), {}}, clip::RigidPose{glm::dvec3(-3, -2, 7), {}});
    plan::applySweep(*removal, sweep, false, nullptr);
    std::vector<std::uint16_t> ids(std::size_t(kDims.x) * kDims.y * kDims.z, 0);
    for (int z = 30; z < 42; ++z)
        for (int y = 12; y < 17; ++y)
            for (int x = 4; x < 10; ++x) ids[(std::size_t(z) * kDims.y + y) * kDims.x + x] = 1;
    std::vector<glm::vec4> styles{glm::vec4(0), glm::vec4(0.9f, 0.2f, 0.2f, 0.5f)};
    for (LongScene* s : {&unfolded, &folded}) {
        s->renderer->setRemoval(removal);
        s->renderer->setLabels(std::make_unique<LabelOverlay>(kDims, ids, styles));
    }
    for (ShadingMode mode : {ShadingMode::Phong, ShadingMode::Cao}) {
        LongScene::Result a = unfolded.render(mode), b = folded.render(mode);
        Difference d = differenceOf(a, b);
        std::printf("[ fold ] drilled + labels, %s: max pixel difference %.3g (%d pixels differ), V_AO max %d (%zu voxels differ)\n",
                    traits(mode).name, d.maxPixel, d.differingPixels, d.maxAmbient, d.differingVoxels);
        EXPECT_LE(d.maxPixel, 1e-4) << traits(mode).name;
        EXPECT_LE(d.maxAmbient, 1) << traits(mode).name;
    }
}

// llvmpipe's own limit (2048): a thin 4 x 4 x 2100 volume was refused ("between 1 and 2048 voxels"); now it is
// folded into 2 pieces and renders.
TEST(FoldedVolume, AVolumeOverTheRealLimitOpensAndRenders) {
    glContext();
    const glm::ivec3 dims(4, 4, 2100);
    if (glContext().info().max3DTextureSize >= dims.z) GTEST_SKIP() << "this GL holds 2100 texels per axis";
    VolumeData volume = test::makeVolume(dims, test::centredAffine(dims), ScalarType::UInt8,
                                         [](glm::dvec3 p) { return 128.0 + 120.0 * std::sin(p.z / 40.0); });
    Renderer renderer(glContext(), volume, test::rampTransferFunction(30, 180, 0.3));
    EXPECT_TRUE(renderer.volumeLayout().folded());
    FrameDescription frame;
    frame.camera.fit(glm::dvec3(0), 6);   // around the cut at z = 0
    frame.camera.azimuthDeg = 90;
    frame.size = {32, 32};
    frame.shading = ShadingMode::Solid;
    renderer.render(frame);
    EXPECT_TRUE(anyVisible(renderer.readImage()));
}

}  // namespace
}  // namespace curette
