// Which bricks' LAO a clipped opacity can change (render/model/lao_reach.h) against brute force over voxel pairs:
// every pair of voxels within the LAO reach plus a cell diagonal (the trilinear footprint) lies at a listed
// brick offset, every listed offset holds such a pair, and the row queries agree with scattering the
// offsets from every changed brick. On isotropic, anisotropic and oblique grids.
#include "render/model/lao_reach.h"
#include "render/mesh_voxel_box.h"
#include "tests/render/gl_test_support.h"

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace curette {
namespace {

struct Grid {
    const char* name;
    VolumeGeometry geometry;
    double reachMm;
};

std::vector<Grid> grids() {
    glm::ivec3 dims(40, 36, 30);
    glm::dmat4 turn = glm::mat4_cast(glm::angleAxis(glm::radians(35.0), glm::normalize(glm::dvec3(1.0, -2.0, 2.0))));
    glm::dmat4 shear(1.0);
    shear[1][0] = 0.4;   // index y leans along world x: a sheared (non-orthogonal) cell
    return {{"isotropic 1 mm, reach 6", {dims, test::centredAffine(dims)}, 6.0},
            {"anisotropic 0.6 x 0.9 x 2.5, reach 5.6", {dims, test::centredAffine(dims, {0.6, 0.9, 2.5})}, 5.6},
            {"oblique sheared 0.8 x 1.1 x 1.3, reach 7", {dims, turn * shear * test::centredAffine(dims, {0.8, 1.1, 1.3})}, 7.0}};
}

glm::ivec3 brickOf(glm::ivec3 v) { return v / kVisitBrickSize; }

TEST(LaoReach, OffsetsHoldEveryVoxelPairWithinReachAndNoOther) {
    for (const Grid& grid : grids()) {
        const VolumeGeometry& g = grid.geometry;
        LaoReachBricks reach(g, grid.reachMm);
        const double limit = grid.reachMm + g.cellDiagonalMm();   // reach plus the trilinear footprint
        EXPECT_DOUBLE_EQ(reach.limitMm(), limit);
        const glm::dmat3 a(g.indexToWorld);
        // Conservative: voxels v in a 4^3 corner block (every position inside a brick), u anywhere within the
        // index box holding the world ball of the limit.
        const int span = 16;
        int pairs = 0;
        for (int vz = 0; vz < 4; ++vz)
            for (int vy = 0; vy < 4; ++vy)
                for (int vx = 0; vx < 4; ++vx) {
                    glm::ivec3 v(vx + 20, vy + 20, vz + 20);
                    for (int z = -span; z <= span; ++z)
                        for (int y = -span; y <= span; ++y)
                            for (int x = -span; x <= span; ++x) {
                                glm::ivec3 u = v + glm::ivec3(x, y, z);
                                if (glm::length(a * glm::dvec3(x, y, z)) > limit) continue;
                                ++pairs;
                                ASSERT_TRUE(reach.isOffset(brickOf(u) - brickOf(v)))
                                    << grid.name << ": voxels " << x << "," << y << "," << z << " apart are within reach but their bricks are not";
                            }
                }
        ASSERT_GT(pairs, 1000) << grid.name;
        // Tight: every offset in the rows has a voxel pair within the limit (plus rounding).
        std::size_t offsets = 0;
        for (const LaoReachBricks::Row& r : reach.rows())
            for (int dx = r.dxMin; dx <= r.dxMax; ++dx, ++offsets) {
                double least = 1e300;
                glm::dvec3 centre = double(kVisitBrickSize) * glm::dvec3(dx, r.dy, r.dz);
                for (int z = -3; z <= 3; ++z)
                    for (int y = -3; y <= 3; ++y)
                        for (int x = -3; x <= 3; ++x) least = std::min(least, glm::length(a * (centre + glm::dvec3(x, y, z))));
                ASSERT_LE(least, limit * (1.0 + 1e-6)) << grid.name << ": offset " << dx << "," << r.dy << "," << r.dz << " holds no pair within reach";
            }
        std::printf("[ lao reach ] %s: %zu brick offsets, %d voxel pairs checked\n", grid.name, offsets, pairs);
    }
}

TEST(LaoReach, RowQueriesAgreeWithScatteringTheOffsets) {
    for (const Grid& grid : grids()) {
        LaoReachBricks reach(grid.geometry, grid.reachMm);
        glm::ivec3 bricks = visitBrickGrid(grid.geometry.dims);
        std::mt19937 random(5);
        std::vector<std::uint8_t> changed(std::size_t(bricks.x) * std::size_t(bricks.y) * std::size_t(bricks.z), 0);
        for (int i = 0; i < 6; ++i) changed[random() % changed.size()] = 1;
        reach.setChanged(bricks, changed);
        std::vector<std::uint8_t> scattered(changed.size(), 0);
        auto at = [&](glm::ivec3 b) { return std::size_t(b.x) + std::size_t(bricks.x) * (std::size_t(b.y) + std::size_t(bricks.y) * std::size_t(b.z)); };
        for (int z = 0; z < bricks.z; ++z)
            for (int y = 0; y < bricks.y; ++y)
                for (int x = 0; x < bricks.x; ++x) {
                    if (!changed[at({x, y, z})]) continue;
                    // Brick B can change where B + d is changed: scatter -d from each changed brick.
                    for (const LaoReachBricks::Row& r : reach.rows())
                        for (int dx = r.dxMin; dx <= r.dxMax; ++dx) {
                            glm::ivec3 b = glm::ivec3(x, y, z) - glm::ivec3(dx, r.dy, r.dz);
                            if (glm::all(glm::greaterThanEqual(b, glm::ivec3(0))) && glm::all(glm::lessThan(b, bricks))) scattered[at(b)] = 1;
                        }
                }
        int reached = 0;
        for (int z = 0; z < bricks.z; ++z)
            for (int y = 0; y < bricks.y; ++y)
                for (int x = 0; x < bricks.x; ++x) {
                    ASSERT_EQ(reach.canChange({x, y, z}), scattered[at({x, y, z})] != 0) << grid.name << ": brick " << x << "," << y << "," << z;
                    reached += scattered[at({x, y, z})];
                }
        EXPECT_GT(reached, 6) << grid.name;
        EXPECT_LT(reached, static_cast<int>(changed.size())) << grid.name << ": some bricks must be out of reach";
    }
}

}  // namespace
}  // namespace curette
