// The exact EDT against brute force on random masks (several seeds, densities and anisotropic spacings).
#include "plan/distance_transform.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace curette::plan {
namespace {

std::vector<double> bruteForce(glm::ivec3 dims, glm::dvec3 spacing, const std::vector<std::uint8_t>& feature) {
    std::vector<glm::dvec3> features;
    auto at = [&](int i, int j, int k) {
        return (std::size_t(k) * std::size_t(dims.y) + std::size_t(j)) * std::size_t(dims.x) + std::size_t(i);
    };
    for (int k = 0; k < dims.z; ++k)
        for (int j = 0; j < dims.y; ++j)
            for (int i = 0; i < dims.x; ++i)
                if (feature[at(i, j, k)]) features.push_back(glm::dvec3(i, j, k) * spacing);
    std::vector<double> d(feature.size(), std::numeric_limits<double>::infinity());
    for (int k = 0; k < dims.z; ++k)
        for (int j = 0; j < dims.y; ++j)
            for (int i = 0; i < dims.x; ++i)
                for (const glm::dvec3& f : features)
                    d[at(i, j, k)] = std::min(d[at(i, j, k)], glm::length(glm::dvec3(i, j, k) * spacing - f));
    return d;
}

TEST(DistanceTransform, MatchesBruteForceOnRandomMasks) {
    const std::vector<glm::dvec3> spacings{{1.0, 1.0, 1.0}, {0.6, 0.9, 1.5}, {2.0, 0.5, 0.7}, {0.3, 1.7, 1.0}};
    for (unsigned seed = 1; seed <= 12; ++seed) {
        std::mt19937 random(seed);
        glm::ivec3 dims(int(random() % 12) + 1, int(random() % 12) + 1, int(random() % 12) + 1);
        const double density = std::vector<double>{0.002, 0.02, 0.2, 0.7}[seed % 4];
        std::bernoulli_distribution isFeature(density);
        std::vector<std::uint8_t> mask(std::size_t(dims.x) * std::size_t(dims.y) * std::size_t(dims.z));
        for (auto& m : mask) m = isFeature(random) ? 1 : 0;
        if (seed == 5) mask.assign(mask.size(), 0);           // no feature: infinite everywhere
        if (seed == 6) mask.assign(mask.size(), 0), mask[mask.size() / 2] = 1;  // one feature
        const glm::dvec3 spacing = spacings[seed % spacings.size()];
        const std::vector<double> fast = distanceTransformMm(dims, spacing, mask);
        const std::vector<double> slow = bruteForce(dims, spacing, mask);
        ASSERT_EQ(fast.size(), slow.size());
        for (std::size_t i = 0; i < fast.size(); ++i) {
            if (std::isinf(slow[i])) {
                ASSERT_TRUE(std::isinf(fast[i])) << "seed " << seed << " voxel " << i;
            } else {
                ASSERT_NEAR(fast[i], slow[i], 1e-9 * (1.0 + slow[i])) << "seed " << seed << " voxel " << i << " dims " << dims.x
                                                                      << "x" << dims.y << "x" << dims.z;
            }
        }
    }
}

TEST(DistanceTransform, SpacingIsTheAffineColumnNorm) {
    glm::dmat4 a(1.0);
    a[0] = glm::dvec4(0.0, 0.6, 0.8, 0.0);  // 1.0 mm along a rotated axis
    a[1] = glm::dvec4(0.0, 0.0, 0.0, 0.0) + glm::dvec4(2.0, 0.0, 0.0, 0.0);
    a[2] = glm::dvec4(0.0, -1.2, 0.9, 0.0);  // 1.5 mm
    glm::dvec3 s = gridSpacingMm(a);
    EXPECT_NEAR(s.x, 1.0, 1e-12);
    EXPECT_NEAR(s.y, 2.0, 1e-12);
    EXPECT_NEAR(s.z, 1.5, 1e-12);
}

}  // namespace
}  // namespace curette::plan
