// The gradient volume (render/gradient_volume.h): phong on an 8-bit scan reads
// its gradients from one texture instead of six reads of the scan, and the image stays the CPU reference's,
// at the volume's faces too, where the texture's pad stands for the clamped samples outside the cells.
#include "render/reference/raycast_reference.h"
#include "render/renderer.h"
#include "tests/render/gl_test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace curette {
namespace {

using test::glContext;

// Tissue up to every face of the box, varying along every axis, so rays read the pad and every gradient axis.
double slopedField(glm::dvec3 p) {
    return std::clamp(110.0 + 2.5 * p.x - 1.5 * p.y + 20.0 * std::sin(0.35 * p.z) + 0.4 * test::blobField(p), 0.0, 255.0);
}

// Faint everywhere (rays cross the whole box, as through the glass brain), so every sample is shaded.
TransferFunction faintEverywhere() {
    TransferFunction tf;
    tf.color = {{0, {0.2, 0.3, 0.7}}, {128, {0.9, 0.5, 0.3}}, {255, {1, 1, 0.9}}};
    tf.opacity = {{0, 0.01}, {128, 0.03}, {255, 0.08}};
    tf.material = {0.25, 0.7, 0.4, 24.0};
    return tf;
}

struct Rendered {
    Image image;
    bool built = false;             // the first frame's plan ran the gradient volume pass
    bool builtAgain = false;        // ... and the second's
    std::size_t bytes = 0;          // the gradient volume's in the memory report
};

Rendered renderTwice(const VolumeData& volume, const FrameDescription& frame, bool gradientVolume) {
    Renderer renderer(glContext(), volume, faintEverywhere());
    renderer.setGradientVolume(gradientVolume);
    Rendered out;
    renderer.render(frame);
    out.built = renderer.lastPlan().runs(Pass::GradientVolume);
    renderer.render(frame);
    out.builtAgain = renderer.lastPlan().runs(Pass::GradientVolume);
    out.image = renderer.readImage();
    for (const GpuAllocation& a : renderer.gpuAllocations())
        if (a.resource == Resource::GradientVolume) out.bytes += a.bytes;
    return out;
}

double largestDifference(const Image& a, const Image& b) {
    double worst = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i)
        for (int c = 0; c < 4; ++c) worst = std::max(worst, double(std::abs(a.pixels[i][c] - b.pixels[i][c])));
    return worst;
}

// The largest channel error of `image` against the CPU double reference (the six central differences of
// trilinear samples, clamped at the faces) over every pixel of the rows `rows` apart.
double referenceError(const VolumeData& volume, const FrameDescription& frame, double stepMm, const Image& image, int rows) {
    double worst = 0;
    for (int y = 0; y < frame.size.y; y += rows)
        for (int x = 0; x < frame.size.x; ++x) {
            glm::dvec4 expected = reference::raycastPixel(volume, faintEverywhere(), frame, stepMm, {x, y}).rgba;
            for (int c = 0; c < 4; ++c) worst = std::max(worst, std::abs(double(image.at(x, y)[c]) - expected[c]));
        }
    return worst;
}

// The stored differences are exact (128 k of 32767) and the texture interpolates them with the weights of the
// six reads, so against the CPU reference the texture is as close as the six reads are: closer, measured, since
// llvmpipe filters the 8-bit scan in fixed point and the 16-bit differences in float (six reads 1.5e-2, the
// texture 3e-3 on the uint8 reference test). The rays cross the faces, where the pad is read.
TEST(GradientVolume, PhongImageMatchesTheReferenceAtTheFacesToo) {
    glContext();
    glm::ivec3 dims(24, 28, 20);
    VolumeData volume = test::makeVolume(dims, test::centredAffine(dims), ScalarType::UInt8, slopedField);
    for (double azimuth : {35.0, 180.0}) {
        FrameDescription frame = test::frameLookingAt(glm::dvec3(0), 80, azimuth, 25, {64, 64}, ShadingMode::Phong);
        Rendered sixReads = renderTwice(volume, frame, false), texture = renderTwice(volume, frame, true);
        EXPECT_FALSE(sixReads.built);
        EXPECT_TRUE(texture.built) << "phong on an 8-bit scan builds it";
        EXPECT_FALSE(texture.builtAgain) << "once per volume";
        EXPECT_EQ(texture.bytes, std::size_t(26 * 30 * 22 * 8)) << "RGBA16_SNORM with one texel of padding";
        double step = Renderer(glContext(), volume, faintEverywhere()).resolveStepMm(frame.raycast);
        double textureError = referenceError(volume, frame, step, texture.image, 3);
        double sixReadsError = referenceError(volume, frame, step, sixReads.image, 3);
        std::printf("[ gradient volume ] azimuth %.0f: largest error against the reference %.2e (six reads %.2e)\n", azimuth,
                    textureError, sixReadsError);
        EXPECT_LT(textureError, 5e-3);
        EXPECT_LE(textureError, sixReadsError);
        // It must be the gradient that lights the picture: flat shading would differ by far more.
        Renderer flat(glContext(), volume, faintEverywhere());
        FrameDescription solid = frame;
        solid.shading = ShadingMode::Solid;
        flat.render(solid);
        EXPECT_GT(largestDifference(flat.readImage(), texture.image), 0.05);
    }
}

// Only a phong ray cast on an 8-bit scan without no-data voxels builds it: other modes, and 16-bit and float
// scans (whose differences 16 bits would not hold exactly), keep the six reads and allocate nothing.
TEST(GradientVolume, OnlyPhongOnAnEightBitScanBuildsIt) {
    glContext();
    glm::ivec3 dims(16);
    for (ScalarType type : {ScalarType::UInt8, ScalarType::UInt16, ScalarType::Float32}) {
        VolumeData volume = test::makeVolume(dims, test::centredAffine(dims), type, slopedField);
        for (ShadingMode mode : {ShadingMode::Solid, ShadingMode::Phong, ShadingMode::Dos}) {
            FrameDescription frame = test::frameLookingAt(glm::dvec3(0), 60, 30, 20, {32, 32}, mode);
            Rendered r = renderTwice(volume, frame, true);
            bool expected = type == ScalarType::UInt8 && mode == ShadingMode::Phong;
            EXPECT_EQ(r.built, expected) << shadingModeName(mode) << " " << scalarTypeName(type);
            EXPECT_EQ(r.bytes > 0, expected) << shadingModeName(mode) << " " << scalarTypeName(type);
        }
    }
}

}  // namespace
}  // namespace curette
