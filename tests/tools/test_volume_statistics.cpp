// `curette info`'s statistics: percentiles are data values. They were bin centres of a 4096-bin histogram, so
// the AAL label map (integers, mostly 0) showed "1%: 0.01416" where the value is 0.
#include "scene/volume_statistics.h"

#include <gtest/gtest.h>

#include <numeric>

namespace curette {
namespace {

TEST(VolumeStatistics, PercentilesOfAnIntegerVolumeAreItsValues) {
    glm::ivec3 dims(10, 10, 10);
    std::vector<std::uint8_t> samples(1000, 0);
    for (std::size_t i = 900; i < 1000; ++i) samples[i] = static_cast<std::uint8_t>(100 + (i % 7));  // labels 100..106
    VolumeData v = buildVolume("labels", dims, ScalarType::UInt8, samples.data(), false, 1.0, 0.0, glm::dmat4(1.0));
    VolumeStatistics s = computeStatistics(v);
    EXPECT_EQ(s.percentiles[0], 0.0);   // 1 %
    EXPECT_EQ(s.percentiles[2], 0.0);   // median
    for (double p : s.percentiles) EXPECT_EQ(p, std::round(p)) << "a percentile of integers is an integer";
    EXPECT_GE(s.percentiles[4], 100.0);  // 99 %: inside the labels
    EXPECT_LE(s.percentiles[4], 106.0);
}

TEST(VolumeStatistics, PercentilesAreNearestRankOfTheSortedValues) {
    glm::ivec3 dims(100, 1, 1);
    std::vector<float> samples(100);
    std::iota(samples.begin(), samples.end(), 1.0f);  // 1..100, shuffled below
    for (std::size_t i = 0; i < 100; i += 3) std::swap(samples[i], samples[99 - i]);
    VolumeData v = buildVolume("ramp", dims, ScalarType::Float32, reinterpret_cast<const std::uint8_t*>(samples.data()), false, 2.0, 1.0,
                               glm::dmat4(1.0));
    VolumeStatistics s = computeStatistics(v);
    // Physical values 2 x + 1 for x = 1..100; nearest rank: 1 % -> x = 1, 25 % -> 25, 50 % -> 50, 75 % -> 75, 99 % -> 99.
    EXPECT_DOUBLE_EQ(s.percentiles[0], 3.0);
    EXPECT_DOUBLE_EQ(s.percentiles[1], 51.0);
    EXPECT_DOUBLE_EQ(s.percentiles[2], 101.0);
    EXPECT_DOUBLE_EQ(s.percentiles[3], 151.0);
    EXPECT_DOUBLE_EQ(s.percentiles[4], 199.0);
}

// The TF editor's gradient-opacity range: the largest central difference in value per mm, through the affine
// (here 2 mm voxels along x, 1 mm along y and z), as the ray caster computes the gradient at a voxel centre.
TEST(VolumeStatistics, TheLargestGradientMagnitudeIsTheRayCastersCentralDifference) {
    glm::ivec3 dims(6, 3, 3);
    std::vector<float> samples(54);
    for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 6; ++i) samples[static_cast<std::size_t>((k * 3 + j) * 6 + i)] = static_cast<float>(i * i);   // x^2 along x
    glm::dmat4 affine(1.0);
    affine[0][0] = 2.0;
    VolumeData v = buildVolume("ramp", dims, ScalarType::Float32, reinterpret_cast<const std::uint8_t*>(samples.data()), false, 3.0, 1.0, affine);
    // Physical 3 i^2 + 1; the largest central difference is at i = 4: 3 (25 - 9) / 2 = 24 per voxel, 12 per mm
    // (at i = 5 the edge clamps: 3 (25 - 16) / 2 = 13.5 per voxel).
    EXPECT_DOUBLE_EQ(maxGradientMagnitude(v), 12.0);
    std::vector<float> flat(54, 7.0f);
    VolumeData constant = buildVolume("flat", dims, ScalarType::Float32, reinterpret_cast<const std::uint8_t*>(flat.data()), false, 1.0, 0.0, affine);
    EXPECT_EQ(maxGradientMagnitude(constant), 0.0);
}

}  // namespace
}  // namespace curette
