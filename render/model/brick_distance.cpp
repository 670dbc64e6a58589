#include "render/model/brick_distance.h"

#include <glm/vector_relational.hpp>

#include <algorithm>
#include <stdexcept>

namespace curette {

std::vector<std::uint8_t> chebyshevBrickDistance(const std::vector<bool>& occupied, glm::ivec3 grid, int cap) {
    const std::size_t count = static_cast<std::size_t>(grid.x) * grid.y * grid.z;
    if (occupied.size() != count) throw std::logic_error("chebyshevBrickDistance: one flag per brick expected");
    cap = std::clamp(cap, 1, 255);
    std::vector<std::uint8_t> distance(count, static_cast<std::uint8_t>(cap));
    auto index = [&](glm::ivec3 b) { return (static_cast<std::size_t>(b.z) * grid.y + b.y) * grid.x + b.x; };
    // Breadth-first from every occupied brick at once; each ring of the search is one more step in the
    // Chebyshev metric (a step to any of the 26 neighbours changes every coordinate by at most 1).
    std::vector<glm::ivec3> front, next;
    for (int z = 0; z < grid.z; ++z)
        for (int y = 0; y < grid.y; ++y)
            for (int x = 0; x < grid.x; ++x)
                if (occupied[index({x, y, z})]) {
                    distance[index({x, y, z})] = 0;
                    front.push_back({x, y, z});
                }
    for (int d = 1; d < cap && !front.empty(); ++d) {
        next.clear();
        for (glm::ivec3 b : front)
            for (int dz = -1; dz <= 1; ++dz)
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        glm::ivec3 n = b + glm::ivec3(dx, dy, dz);
                        if (glm::any(glm::lessThan(n, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(n, grid))) continue;
                        std::uint8_t& at = distance[index(n)];
                        if (at <= d) continue;
                        at = static_cast<std::uint8_t>(d);
                        next.push_back(n);
                    }
        std::swap(front, next);
    }
    return distance;
}

}  // namespace curette
