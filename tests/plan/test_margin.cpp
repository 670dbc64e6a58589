// Cell gaps (plan/margin.h) against brute force over the cells, on isotropic and anisotropic grids, and the
// distance to the touched cells in front of a face.
#include "plan/margin.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace curette::plan {
namespace {

constexpr glm::ivec3 kDims{48, 24, 24};

// Brute force: the gap from every touched cell to every cell of a set, on a small grid.
double bruteForceGap(glm::ivec3 dims, const std::vector<Touch>& touched, const std::vector<std::uint8_t>& structure) {
    double best2 = INFINITY;
    auto at = [&](int i, int j, int k) { return (std::size_t(k) * dims.y + j) * dims.x + i; };
    for (int k = 0; k < dims.z; ++k)
        for (int j = 0; j < dims.y; ++j)
            for (int i = 0; i < dims.x; ++i) {
                if (touched[at(i, j, k)] == Touch::None) continue;
                for (int c = 0; c < dims.z; ++c)
                    for (int b = 0; b < dims.y; ++b)
                        for (int a = 0; a < dims.x; ++a) {
                            if (!structure[at(a, b, c)]) continue;
                            glm::dvec3 gap = glm::max(glm::abs(glm::dvec3(a - i, b - j, c - k)) - 1.0, 0.0);
                            best2 = std::min(best2, glm::dot(gap, gap));
                        }
            }
    return std::sqrt(best2);
}

TEST(Margin, CellGapsEqualBruteForceOverCells) {
    const glm::ivec3 dims{14, 11, 9};
    std::vector<Touch> touched(std::size_t(dims.x) * dims.y * dims.z, Touch::None);
    std::vector<std::uint8_t> structure(touched.size(), 0);
    auto at = [&](int i, int j, int k) { return (std::size_t(k) * dims.y + j) * dims.x + i; };
    // A ball of touched cells and an oblique slab of structure cells.
    for (int k = 0; k < dims.z; ++k)
        for (int j = 0; j < dims.y; ++j)
            for (int i = 0; i < dims.x; ++i) {
                if ((i - 3) * (i - 3) + (j - 4) * (j - 4) + (k - 4) * (k - 4) <= 5) touched[at(i, j, k)] = Touch::Part;
                if (i + 0.6 * j - 0.3 * k > 11.5) structure[at(i, j, k)] = 1;
            }
    CellGaps gaps = cellGapsTo(dims, glm::dmat4(1.0), touched);
    double best2 = INFINITY;
    for (std::size_t v = 0; v < structure.size(); ++v)
        if (structure[v]) best2 = std::min(best2, gaps.cellGap2[v]);
    EXPECT_NEAR(std::sqrt(best2), bruteForceGap(dims, touched, structure), 1e-9);
    // And on an anisotropic grid the same cells are spacing-scaled.
    glm::dmat4 aniso(1.0);
    aniso[0][0] = 0.5, aniso[1][1] = 0.5, aniso[2][2] = 3.0;
    CellGaps scaled = cellGapsTo(dims, aniso, touched);
    double bestScaled2 = INFINITY, brute2 = INFINITY;
    for (std::size_t v = 0; v < structure.size(); ++v)
        if (structure[v]) bestScaled2 = std::min(bestScaled2, scaled.cellGap2[v]);
    for (int k = 0; k < dims.z; ++k)
        for (int j = 0; j < dims.y; ++j)
            for (int i = 0; i < dims.x; ++i) {
                if (touched[at(i, j, k)] == Touch::None) continue;
                for (std::size_t w = 0; w < structure.size(); ++w) {
                    if (!structure[w]) continue;
                    glm::ivec3 u(int(w % dims.x), int(w / dims.x % dims.y), int(w / dims.x / dims.y));
                    glm::dvec3 gap = glm::max(glm::abs(glm::dvec3(u - glm::ivec3(i, j, k))) - 1.0, 0.0) * glm::dvec3(0.5, 0.5, 3.0);
                    brute2 = std::min(brute2, glm::dot(gap, gap));
                }
            }
    EXPECT_NEAR(std::sqrt(bestScaled2), std::sqrt(brute2), 1e-9);
}

TEST(Margin, ADistanceToTheTouchedCellsIsExactInFrontOfAFace) {
    std::vector<Touch> touched(std::size_t(kDims.x) * kDims.y * kDims.z, Touch::None);
    for (int k = 0; k < kDims.z; ++k)
        for (int j = 0; j < kDims.y; ++j)
            for (int i = 0; i < 20; ++i) touched[(std::size_t(k) * kDims.y + j) * kDims.x + i] = Touch::Whole;
    CellGaps gaps = cellGapsTo(kDims, glm::dmat4(1.0), touched);
    // The touched cells end at x = 19.5.
    for (double x : {19.5, 20.0, 23.3, 30.75}) EXPECT_NEAR(gaps.distanceMm({x, 11.2, 7.9}), x - 19.5, 1e-9) << x;
}

}  // namespace
}  // namespace curette::plan
