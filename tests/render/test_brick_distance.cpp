// The empty-space distance map (render/model/brick_distance.h) against the definition, brute force, over random
// occupancy grids.
#include "render/model/brick_distance.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <random>

namespace curette {
namespace {

// The definition: min over occupied bricks q of max(|p - q|) per axis, capped.
int bruteForce(const std::vector<bool>& occupied, glm::ivec3 grid, glm::ivec3 p, int cap) {
    int best = cap;
    for (int z = 0; z < grid.z; ++z)
        for (int y = 0; y < grid.y; ++y)
            for (int x = 0; x < grid.x; ++x)
                if (occupied[(static_cast<std::size_t>(z) * grid.y + y) * grid.x + x])
                    best = std::min(best, std::max({std::abs(x - p.x), std::abs(y - p.y), std::abs(z - p.z)}));
    return best;
}

TEST(BrickDistance, EqualsTheChebyshevDistanceToTheNearestOccupiedBrick) {
    std::mt19937 random(3);
    for (int trial = 0; trial < 40; ++trial) {
        glm::ivec3 grid(1 + random() % 9, 1 + random() % 7, 1 + random() % 8);
        double density = std::uniform_real_distribution<double>(0.0, 0.15)(random);
        std::vector<bool> occupied(static_cast<std::size_t>(grid.x) * grid.y * grid.z);
        for (std::size_t i = 0; i < occupied.size(); ++i) occupied[i] = std::bernoulli_distribution(density)(random);
        int cap = trial % 3 == 0 ? 3 : 255;
        std::vector<std::uint8_t> d = chebyshevBrickDistance(occupied, grid, cap);
        for (int z = 0; z < grid.z; ++z)
            for (int y = 0; y < grid.y; ++y)
                for (int x = 0; x < grid.x; ++x)
                    ASSERT_EQ(d[(static_cast<std::size_t>(z) * grid.y + y) * grid.x + x], bruteForce(occupied, grid, {x, y, z}, cap))
                        << "trial " << trial << " brick " << x << "," << y << "," << z;
    }
}

TEST(BrickDistance, AnEmptyGridIsEverywhereAtTheCap) {
    std::vector<std::uint8_t> d = chebyshevBrickDistance(std::vector<bool>(24, false), {2, 3, 4}, 255);
    EXPECT_TRUE(std::all_of(d.begin(), d.end(), [](std::uint8_t v) { return v == 255; }));
}

}  // namespace
}  // namespace curette
