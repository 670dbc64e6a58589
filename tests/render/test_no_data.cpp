// "No data" (NaN/Inf voxels) on the GPU: no branch in the shaders, only a stored value far below the data
// (base/volume.h noDataTexelBelow) and a transfer-function table transparent that far below its first point
// (render/transfer_function_texture.h). A NaN background must render exactly like the same volume with the
// background at its lowest value under a TF that is transparent there, and must stay transparent under a TF
// that is opaque at every value.
#include "render/passes/ambient_occlusion.h"
#include "render/reference/lao_reference.h"
#include "render/reference/raycast_reference.h"
#include "render/renderer.h"
#include "tests/render/gl_test_support.h"

#include <gtest/gtest.h>

#include <cstdio>

#include <cmath>
#include <limits>

namespace curette {
namespace {

using test::glContext;

FrameDescription frame(ShadingMode shading, double azimuth) {
    FrameDescription f;
    f.camera.target = glm::dvec3(0);
    f.camera.distanceMm = 90;
    f.camera.azimuthDeg = azimuth;
    f.camera.elevationDeg = 20;
    f.camera.fovYDeg = 30;
    f.camera.nearMm = 1;
    f.camera.farMm = 1000;
    f.size = {96, 96};
    f.shading = shading;
    return f;
}

// The blobby field of the GL tests (gl_test_support.h).
double blobs(glm::dvec3 p) { return test::blobField(p); }

// Where the blobs fall below 2 is "background". The blobs' level 40, where the TF below starts to be opaque,
// lies more than 1.2 sigma (6 mm) inside it: every sample with opacity, and every voxel its trilinear
// footprint and its central-difference gradient reach (within 2 sqrt(3) voxels), is away from the background.
constexpr double kBackground = 2.0;

TransferFunction transparentBelow40() {
    TransferFunction tf;
    tf.color = {{0, {0.1, 0.2, 0.6}}, {80, {0.9, 0.4, 0.2}}, {160, {1.0, 0.9, 0.7}}, {255, {1, 1, 1}}};
    tf.opacity = {{0, 0}, {40, 0}, {120, 0.15}, {200, 0.5}, {255, 0.6}};
    return tf;
}

VolumeData blobVolume(double backgroundValue) {
    glm::ivec3 dims(40);
    return test::makeVolume(dims, test::centredAffine(dims), ScalarType::Float32, [&](glm::dvec3 p) {
        double v = blobs(p);
        return v < kBackground ? backgroundValue : v;
    });
}

Image render(const VolumeData& volume, const TransferFunction& tf, const FrameDescription& f) {
    Renderer renderer(glContext(), volume, tf);
    renderer.render(f);
    return renderer.readImage();
}

TEST(NoData, NaNBackgroundRendersAsTheLowestValueUnderATfTransparentThere) {
    glContext();
    VolumeData withNaN = blobVolume(std::numeric_limits<double>::quiet_NaN());
    VolumeData withZero = blobVolume(0.0);  // the background at the lowest value, where the TF has no opacity
    ASSERT_GT(withNaN.noDataVoxels, 2000u) << "the test needs a real background (the box's corners)";
    ASSERT_EQ(withZero.noDataVoxels, 0u);
    EXPECT_GE(withNaN.minValue, kBackground);  // the range leaves the background out
    // A sample whose footprint (or gradient stencil) reaches a no-data voxel is transparent with NaN, and has a
    // value below 40, so is transparent, with the zeros; every other sample reads the same TF. Not bit for bit:
    // only the volume with no data gets the table's transparent lead (16384 texels instead of 4096), so the same
    // value lands at another table coordinate and the linear filter rounds differently (a few float ulps of a
    // piecewise-linear TF). The bound, 2e-5 per channel, is far under the 8-bit display step (3.9e-3).
    for (ShadingMode mode : {ShadingMode::Solid, ShadingMode::Phong, ShadingMode::Lao})
        for (double azimuth : {30.0, 200.0}) {
            FrameDescription f = frame(mode, azimuth);
            Image a = render(withNaN, transparentBelow40(), f), b = render(withZero, transparentBelow40(), f);
            ASSERT_EQ(a.pixels.size(), b.pixels.size());
            std::size_t visible = 0;
            float maxDifference = 0;
            for (std::size_t i = 0; i < a.pixels.size(); ++i) {
                for (int c = 0; c < 4; ++c) maxDifference = std::max(maxDifference, std::abs(a.pixels[i][c] - b.pixels[i][c]));
                visible += b.pixels[i].a > 0.05f;
            }
            EXPECT_GT(visible, 500u) << "the view must show the blobs";
            EXPECT_LT(maxDifference, 2e-5f) << shadingModeName(mode) << " azimuth " << azimuth;
            std::printf("[ no data ] %s azimuth %.0f: max difference %.2e\n", shadingModeName(mode), azimuth, maxDifference);
        }
}

TEST(NoData, StaysTransparentUnderATfOpaqueAtEveryValue) {
    glContext();
    TransferFunction fog;
    fog.color = {{0, {0.5, 0.5, 0.5}}, {255, {1, 1, 1}}};
    fog.opacity = {{0, 0.05}, {255, 0.05}};  // every value has opacity, the TF's first point included
    VolumeData withNaN = blobVolume(std::numeric_limits<double>::quiet_NaN());
    VolumeData withZero = blobVolume(0.0);
    for (ShadingMode mode : {ShadingMode::Solid, ShadingMode::Phong}) {
        FrameDescription f = frame(mode, 30);
        Image a = render(withNaN, fog, f), b = render(withZero, fog, f);
        std::size_t fogOnly = 0;
        for (std::size_t i = 0; i < a.pixels.size(); ++i) {
            // No data never adds opacity: along each ray its samples are transparent or the same as with zeros.
            EXPECT_LE(a.pixels[i].a, b.pixels[i].a + 1e-6f) << "pixel " << i;
            fogOnly += a.pixels[i].a == 0.0f && b.pixels[i].a > 0.2f;
        }
        // Rays through the background only: fog with zeros, nothing at all with NaN.
        EXPECT_GT(fogOnly, 300u) << shadingModeName(mode);
    }
}

// Gradient opacity next to no data: a central difference that reaches a no-data voxel sees the stored value
// far below the data, a gradient as large as the table goes, and so the border of the no-data region became
// an opaque shell. Both neighbours are data here, or the difference is one-sided, so a uniform volume with a
// hole stays uniform up to the hole. The hole is a box of NaN, long along y.
VolumeData uniformVolume(bool withHole) {
    glm::ivec3 dims(40);
    return test::makeVolume(dims, test::centredAffine(dims), ScalarType::Float32, [&](glm::dvec3 p) {
        bool inHole = std::abs(p.x) < 6 && std::abs(p.z) < 6 && std::abs(p.y) < 14;
        return withHole && inHole ? std::numeric_limits<double>::quiet_NaN() : 100.0;
    });
}
constexpr std::uint64_t kHoleVoxels = 12 * 12 * 28;

// Opacity at every value (so the twins must leave no-data samples out as the GPU does), and a gradient
// factor of a tenth where the volume is flat, all of it at an edge.
TransferFunction gradientOpacityTf() {
    TransferFunction tf;
    tf.color = {{0, {0.8, 0.6, 0.5}}, {255, {1, 1, 1}}};
    tf.opacity = {{0, 0.1}, {255, 0.1}};
    tf.gradientOpacity = {{0, 0.1}, {20, 1.0}};
    tf.material = {0.25, 0.7, 0.4, 24.0};
    return tf;
}

// Rays along the hole's faces (the view looks along its long axis) must gather no more opacity than through
// the same volume without the hole, and the GPU must match its CPU twin.
TEST(NoData, GradientOpacitySeesNoWallAtTheBorderOfNoData) {
    glContext();
    VolumeData withHole = uniformVolume(true), uniform = uniformVolume(false);
    ASSERT_EQ(withHole.noDataVoxels, kHoleVoxels);
    TransferFunction tf = gradientOpacityTf();
    ASSERT_TRUE(tf.hasGradientOpacity());
    for (ShadingMode mode : {ShadingMode::Solid, ShadingMode::Phong})
        for (double azimuth : {0.0, 25.0}) {
            FrameDescription f = frame(mode, azimuth);
            f.camera.elevationDeg = 0;
            f.size = {64, 64};
            Renderer renderer(glContext(), withHole, tf);
            renderer.render(f);
            Image a = renderer.readImage();
            Image b = render(uniform, tf, f);
            double step = renderer.resolveStepMm(f.raycast);
            float excess = 0, holeDimmed = 0;
            double twinError = 0;
            for (int y = 0; y < f.size.y; ++y)
                for (int x = 0; x < f.size.x; ++x) {
                    glm::vec4 got = a.at(x, y);
                    excess = std::max(excess, got.a - b.at(x, y).a);
                    holeDimmed = std::max(holeDimmed, b.at(x, y).a - got.a);
                    glm::dvec4 expected = reference::raycastPixel(withHole, tf, f, step, {x, y}).rgba;
                    for (int c = 0; c < 4; ++c) twinError = std::max(twinError, std::abs(double(got[c]) - expected[c]));
                }
            std::printf("[ no data ] gradient opacity, %s azimuth %.0f: excess opacity %.3e, twin max error %.2e\n",
                        shadingModeName(mode), azimuth, excess, twinError);
            EXPECT_GT(holeDimmed, 0.1f) << "the view must see the hole";
            // Not bit for bit: only the volume with no data gets the table's transparent lead (the first test).
            EXPECT_LT(excess, 1e-4f) << shadingModeName(mode) << " azimuth " << azimuth;
            EXPECT_LT(twinError, 5e-4) << shadingModeName(mode) << " azimuth " << azimuth;
        }
}

// Step IV's V_o takes the gradient of each voxel (voxel_clip.comp): next to the hole no voxel may be more
// opaque than the flat volume's, the hole's own voxels are transparent, and the GPU matches its twin (V_o is
// stored in R16).
TEST(NoData, StepIvOpacitySeesNoWallAtTheBorderOfNoData) {
    glContext();
    VolumeData volume = uniformVolume(true);
    TransferFunction tf = gradientOpacityTf();
    GpuVolume gpu(glContext().info(), volume);
    TransferFunctionTexture table(tf, volume.valueScale, volume.valueOffset, gpu.hasNoData());
    AmbientOcclusion ao(gpu, LaoSettings{});
    ao.precompute(table);
    std::vector<std::uint16_t> opacity = ao.readOpacity();
    auto nowhere = [](glm::dvec3) { return false; };
    reference::VoxelClipping twin = reference::clipVoxels(volume, tf, nowhere, nowhere, {});
    const double flat = tf.evaluateOpacity(100.0) * tf.evaluateGradientOpacity(0.0);
    double excess = 0, twinError = 0;
    std::size_t holeVoxels = 0;
    for (std::size_t i = 0; i < opacity.size(); ++i) {
        double got = opacity[i] / 65535.0;
        excess = std::max(excess, got - flat);
        twinError = std::max(twinError, std::abs(got - twin.opacity.values[i]));
        if (volume.isNoData(i)) holeVoxels += got == 0.0;
    }
    std::printf("[ no data ] step IV gradient opacity: excess opacity %.3e, twin max error %.2e\n", excess, twinError);
    EXPECT_LT(excess, 1e-4);
    EXPECT_LT(twinError, 1e-4);
    EXPECT_EQ(holeVoxels, kHoleVoxels);
}

TEST(NoData, TheTableIsTransparentFarBelowItsFirstPointAndClampsAsTheTfBetween) {
    glContext();
    TransferFunction tf;
    tf.color = {{100, {1, 0, 0}}, {200, {0, 0, 1}}};
    tf.opacity = {{100, 0.4}, {200, 0.8}};
    // Without no-data voxels the table is the plain one (4096 texels over the domain); with them, the lead.
    EXPECT_EQ(TransferFunctionTexture(tf, 1.0, 0.0).tableSize(), TransferFunctionTexture::domainTexels);
    TransferFunctionTexture texture(tf, 1.0, 0.0, true);
    const std::vector<glm::vec4>& table = texture.table();
    ASSERT_EQ(table.size(), static_cast<std::size_t>(TransferFunctionTexture::noDataTableSize));
    EXPECT_EQ(table[0].a, 0.0f);                      // d0 - 3.0007 (d1 - d0) = -200.07 and below: no data
    EXPECT_FLOAT_EQ(table[1].a, 0.4f);                // then the first point's opacity, as the TF clamps
    EXPECT_FLOAT_EQ(table[TransferFunctionTexture::leadTexels].a, 0.4f);  // d0
    EXPECT_FLOAT_EQ(table.back().a, 0.8f);            // d1
    EXPECT_EQ(glm::vec3(table[0]), glm::vec3(1, 0, 0));  // the first colour, so nothing bleeds in at the edge
    // Where values land: coordinate * size - 0.5 is the texel index.
    auto index = [&](double value) { return (value * texture.texelToTf().x + texture.texelToTf().y) * texture.tableSize() - 0.5; };
    EXPECT_NEAR(index(100), TransferFunctionTexture::leadTexels, 1e-2);
    EXPECT_NEAR(index(200), texture.tableSize() - 1, 1e-2);
    EXPECT_LT(index(100 - 3.001 * 100), 0.0);
    // Empty-space skipping sees the same table: data in the clamped lead have opacity, no data does not.
    EXPECT_FLOAT_EQ(texture.maxOpacity(-150.0f, -150.0f), 0.4f);
    EXPECT_NEAR(texture.maxOpacity(50.0f, 150.0f), 0.6f, 1e-3f);  // with the one-texel margin
    float noData = noDataTexelBelow(100.0, 200.0, 1.0, 0.0);
    EXPECT_LT(noData, -1e10f);
    // A brick holding only no-data voxels reads texel 0 alone: it is skipped.
    EXPECT_EQ(texture.maxOpacity(noData, noData), 0.0f);
}

}  // namespace
}  // namespace curette
