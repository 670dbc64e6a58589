#include "render/model/brick_set.h"

#include <algorithm>

namespace curette {

double clipSampleReachMm(const VolumeGeometry& g) { return g.cellDiagonalMm() * 1.001; }

BrickSet BrickSet::none(glm::ivec3 dims) {
    BrickSet s;
    s.dims = dims;
    s.grid = visitBrickGrid(dims);
    s.visited.assign(std::size_t(s.grid.x) * std::size_t(s.grid.y) * std::size_t(s.grid.z), 0);
    return s;
}

BrickSet BrickSet::all(glm::ivec3 dims) {
    BrickSet s = none(dims);
    std::fill(s.visited.begin(), s.visited.end(), std::uint8_t(1));
    return s;
}

std::size_t BrickSet::visitedCount() const { return static_cast<std::size_t>(std::count(visited.begin(), visited.end(), std::uint8_t(1))); }

std::uint64_t BrickSet::visitedVoxels() const {
    std::uint64_t voxels = 0;
    std::size_t b = 0;
    for (int z = 0; z < grid.z; ++z)
        for (int y = 0; y < grid.y; ++y)
            for (int x = 0; x < grid.x; ++x, ++b) {
                if (!visited[b]) continue;
                glm::ivec3 size = glm::min(glm::ivec3(kVisitBrickSize), dims - kVisitBrickSize * glm::ivec3(x, y, z));
                voxels += std::uint64_t(size.x) * std::uint64_t(size.y) * std::uint64_t(size.z);
            }
    return voxels;
}

bool BrickSet::visits(glm::ivec3 v) const {
    glm::ivec3 b = v / kVisitBrickSize;
    return visited[std::size_t(b.x) + std::size_t(grid.x) * (std::size_t(b.y) + std::size_t(grid.y) * std::size_t(b.z))] != 0;
}

void BrickSet::unite(const BrickSet& other) {
    for (std::size_t b = 0; b < visited.size(); ++b) visited[b] |= other.visited[b];
}

std::vector<std::uint32_t> BrickSet::visitedIndices() const {
    std::vector<std::uint32_t> list;
    list.reserve(visitedCount());
    for (std::size_t b = 0; b < visited.size(); ++b)
        if (visited[b]) list.push_back(static_cast<std::uint32_t>(b));
    return list;
}

}  // namespace curette
