// LAO (steps I and V) against its CPU double twin, and the direction sets of CAO eq. 3.
#include "render/passes/ambient_occlusion.h"
#include "render/reference/lao_reference.h"
#include "render/renderer.h"
#include "tests/render/gl_test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

namespace curette {
namespace {

using test::glContext;

double blobs(glm::dvec3 p) {
    const glm::dvec4 centres[] = {{-5, -3, 2, 6}, {6, 4, -3, 5}, {1, -7, -5, 4}};
    double v = 0;
    for (const glm::dvec4& c : centres) v += 240.0 * std::exp(-glm::dot(p - glm::dvec3(c), p - glm::dvec3(c)) / (2 * c.w * c.w));
    return std::min(v, 255.0);
}

TEST(LaoDirections, PatternsHaveTheirCountsUnitLengthAndMeanWeightOne) {
    for (auto [text, count] : {std::pair{"6", 6}, {"14", 14}, {"26", 26}, {"54", 54}, {"fibonacci:512", 512}, {"fib7", 7}}) {
        LaoDirectionSet set;
        ASSERT_TRUE(parseLaoPattern(text, set)) << text;
        std::vector<LaoDirection> list = set.build();
        ASSERT_EQ(static_cast<int>(list.size()), count) << text;
        double weights = 0;
        glm::dvec3 mean(0);
        for (const LaoDirection& d : list) {
            EXPECT_NEAR(glm::length(d.direction), 1.0, 1e-12);
            weights += d.weight;
            mean += d.direction;
        }
        EXPECT_NEAR(weights / count, 1.0, 1e-12) << text;
        // The neighbourhood patterns and a dense Fibonacci set are balanced over the sphere (jitter moves the
        // mean by at most about the jitter); a 7-point Fibonacci set is not, so it is not checked.
        if (count != 7) {
            EXPECT_LT(glm::length(mean / double(count)), 0.03) << text;
        }
    }
    LaoDirectionSet six;
    parseLaoPattern("6", six);
    six.jitter = 0;
    for (const LaoDirection& d : six.build()) EXPECT_NEAR(std::abs(d.direction.x) + std::abs(d.direction.y) + std::abs(d.direction.z), 1.0, 1e-12);
    LaoDirectionSet bad;
    EXPECT_FALSE(parseLaoPattern("7", bad));
    EXPECT_FALSE(parseLaoPattern("fibonacci:0", bad));
    EXPECT_FALSE(parseLaoPattern("fibonacci:x", bad));
}

struct AoFixture {
    VolumeData volume;
    TransferFunction tf;
    std::unique_ptr<GpuVolume> gpu;
    std::unique_ptr<TransferFunctionTexture> tfTexture;
    AoFixture(glm::ivec3 dims, const glm::dmat4& affine) {
        glContext();
        volume = test::makeVolume(dims, affine, ScalarType::UInt8, blobs);
        tf = test::rampTransferFunction(30, 180, 0.35);
        gpu = std::make_unique<GpuVolume>(glContext().info(), volume);
        tfTexture = std::make_unique<TransferFunctionTexture>(tf, volume.valueScale, volume.valueOffset);
    }
};

// GPU LAO against the CPU double twin, fed the GPU's own V_o (so only the ray differs). V_AO is stored in
// R16: the storage alone allows 0.5 / 65535 = 7.6e-6. The float arithmetic over K * (M - 1) = 26 * 11
// samples adds relative errors of a few 1e-7 per operation: bound 2e-5 (measured: max 7.9e-6, i.e. the
// storage quantum; rms 4.5e-6), far under the 8-bit display step (3.9e-3). Two steps: the TF's unit length
// (lao_ray.glsl's LAO_UNIT_STEP variant, no pow) and 0.7 mm (the corrected opacity (1 - a)^0.7; the unit
// step's variant there is off by 9.8e-2).
void expectLaoMatchesTwinOnAnisotropicObliqueVolume(double stepMm, const LaoDirectionSet& directions = {}) {
    glm::dmat3 rz(std::cos(0.4), std::sin(0.4), 0, -std::sin(0.4), std::cos(0.4), 0, 0, 0, 1);
    glm::dmat3 linear = rz * glm::dmat3(glm::dvec3(0.9, 0, 0), glm::dvec3(0, 1.1, 0), glm::dvec3(0, 0, 1.3));
    glm::ivec3 dims(30, 28, 24);
    glm::dmat4 affine(linear);
    affine[3] = glm::dvec4(-linear * (0.5 * glm::dvec3(dims - 1)), 1.0);
    AoFixture f(dims, affine);
    LaoSettings settings;
    settings.samples = 12;
    settings.stepMm = stepMm;
    settings.directions = directions;
    AmbientOcclusion ao(*f.gpu, settings);
    ao.precompute(*f.tfTexture);
    std::vector<std::uint16_t> gpuOpacity = ao.readOpacity();
    std::vector<std::uint16_t> gpuAmbient = ao.readPrecomputed();

    reference::Grid opacity;
    opacity.dims = dims;
    for (std::uint16_t v : gpuOpacity) opacity.values.push_back(v / 65535.0);
    reference::LaoParameters p{settings.directions.build(), settings.samples, settings.stepMm, f.tf.unitLengthMm};
    glm::dmat4 worldToTexture = f.gpu->geometry().worldToTexture();
    std::mt19937 random(5);
    double maxError = 0, sumSquares = 0;
    int n = 400;
    double minAmbient = 1;
    for (int i = 0; i < n; ++i) {
        glm::ivec3 v(random() % dims.x, random() % dims.y, random() % dims.z);
        double expected = reference::localAmbientOcclusion(opacity, worldToTexture, affine, v, p);
        double got = gpuAmbient[f.volume.linearIndex(v.x, v.y, v.z)] / 65535.0;
        maxError = std::max(maxError, std::abs(got - expected));
        sumSquares += (got - expected) * (got - expected);
        minAmbient = std::min(minAmbient, expected);
    }
    std::printf("[ lao twin ] step %.2f mm, K = %zu: max %.2e rms %.2e over %d voxels (darkest %.3f)\n", stepMm,
                p.directions.size(), maxError, std::sqrt(sumSquares / n), n, minAmbient);
    EXPECT_LT(maxError, 2e-5);
    EXPECT_LT(minAmbient, 0.8) << "the volume must occlude something";
}

TEST(Lao, GpuMatchesCpuTwinOnAnisotropicObliqueVolume) {
    ASSERT_EQ(test::rampTransferFunction(30, 180, 0.35).unitLengthMm, 1.0);
    expectLaoMatchesTwinOnAnisotropicObliqueVolume(1.0);
}

TEST(Lao, GpuMatchesCpuTwinWithAStepUnlikeTheUnitLength) { expectLaoMatchesTwinOnAnisotropicObliqueVolume(0.7); }

// K is what the built list holds: a pattern whose length is not the set's `count` (here left at its default
// of 26) still casts every one of its directions, no more, with weights over its own length.
TEST(Lao, TheCompiledInDirectionCountIsTheListsLength) {
    for (LaoPattern pattern : {LaoPattern::Rubik54, LaoPattern::Neighbourhood6, LaoPattern::Neighbourhood14}) {
        LaoDirectionSet directions;
        directions.pattern = pattern;
        ASSERT_EQ(directions.count, 26);
        const std::size_t length = directions.build().size();
        ASSERT_NE(length, 26u);
        EXPECT_EQ(directions.describe().substr(0, directions.describe().find(' ')), std::to_string(length));
        SCOPED_TRACE(directions.describe());
        expectLaoMatchesTwinOnAnisotropicObliqueVolume(1.0, directions);
        // A K past the list's end reads beyond the direction buffer, which llvmpipe returns as zeros, so the
        // image alone cannot tell; the direction buffer's reported size is K entries of 16 bytes.
        glm::ivec3 dims(8, 8, 8);
        AoFixture f(dims, test::centredAffine(dims));
        LaoSettings settings;
        settings.directions = directions;
        AmbientOcclusion ao(*f.gpu, settings);
        std::size_t bytes = 0;
        for (const GpuAllocation& a : ao.allocations())
            if (a.resource == Resource::LaoDirections) bytes = a.bytes;
        EXPECT_EQ(bytes, 16u * length);
    }
}

// Without clip meshes, step IV stores each voxel's TF opacity: the GPU reads the 4096-texel baked table
// (error <= slope * range / 4095 / 2 = 0.35/150 * 255/8190 = 7e-5) and stores R16 (7.6e-6).
TEST(Lao, UnclippedOpacityIsTheTransferFunction) {
    glm::ivec3 dims(20, 18, 16);
    AoFixture f(dims, test::centredAffine(dims));
    AmbientOcclusion ao(*f.gpu, LaoSettings{});
    ao.precompute(*f.tfTexture);
    std::vector<std::uint16_t> gpuOpacity = ao.readOpacity();
    std::vector<std::uint8_t> mask = ao.readMask();
    double maxError = 0;
    for (std::size_t i = 0; i < gpuOpacity.size(); ++i) {
        double expected = f.tf.evaluateOpacity(f.volume.valueScale * f.volume.normalized(i) + f.volume.valueOffset);
        maxError = std::max(maxError, std::abs(gpuOpacity[i] / 65535.0 - expected));
        EXPECT_EQ(mask[i], 1u) << "step I marks every voxel b";
    }
    EXPECT_LT(maxError, 1e-4);
    EXPECT_EQ(ao.lastStats().recomputed, f.volume.voxelCount());
}

// A TF with gradient opacity compiles step IV's GRADIENT_OPACITY variant: V_o is then the TF opacity times
// the gradient factor of the voxel's central differences, as the CPU twin computes it. The gradient table
// (256 entries, linear between them) is exact for this ramp, whose only kink is its last point; float
// differences of 8-bit texels are exact, so the bound stays the TF table's 1e-4.
TEST(Lao, UnclippedOpacityWithGradientOpacityMatchesTheTwin) {
    glm::ivec3 dims(20, 18, 16);
    AoFixture f(dims, test::centredAffine(dims, {0.9, 1.1, 1.3}));
    f.tf.gradientOpacity = {{0, 0.2}, {25, 1.0}};
    f.tfTexture = std::make_unique<TransferFunctionTexture>(f.tf, f.volume.valueScale, f.volume.valueOffset);
    AmbientOcclusion ao(*f.gpu, LaoSettings{});
    ao.precompute(*f.tfTexture);
    std::vector<std::uint16_t> gpuOpacity = ao.readOpacity();
    auto nowhere = [](glm::dvec3) { return false; };
    reference::VoxelClipping twin = reference::clipVoxels(f.volume, f.tf, nowhere, nowhere, {});
    double maxError = 0, largestEffect = 0;
    for (std::size_t i = 0; i < gpuOpacity.size(); ++i) {
        maxError = std::max(maxError, std::abs(gpuOpacity[i] / 65535.0 - twin.opacity.values[i]));
        double plain = f.tf.evaluateOpacity(f.volume.valueScale * f.volume.normalized(i) + f.volume.valueOffset);
        largestEffect = std::max(largestEffect, plain - twin.opacity.values[i]);
    }
    std::printf("[ gradient opacity ] max %.2e, largest effect %.3f\n", maxError, largestEffect);
    EXPECT_LT(maxError, 1e-4);
    EXPECT_GT(largestEffect, 0.05) << "the gradient factor must matter here";
}

}  // namespace
}  // namespace curette
