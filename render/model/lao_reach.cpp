#include "render/model/lao_reach.h"

#include "render/model/brick_set.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace curette {

LaoReachBricks::LaoReachBricks(const VolumeGeometry& g, double reachMm) : limitMm_(reachMm + g.cellDiagonalMm()) {
    const glm::dmat3 a(g.indexToWorld), inverse = glm::inverse(a);
    const double cell = g.cellDiagonalMm();
    const double limit = limitMm_ * (1.0 + 1e-9) + 1e-9;   // rounding: keep an offset right at the limit
    const int half = kVisitBrickSize - 1;                   // voxel offsets within a brick pair: 4 d +- 3
    // The offsets can only reach as far along index axis i as a world ball of the limit does: limit * |row i
    // of A^-1|, plus the 3 voxels inside a brick.
    glm::ivec3 most;
    for (int i = 0; i < 3; ++i) {
        double extent = limitMm_ * glm::length(glm::dvec3(inverse[0][i], inverse[1][i], inverse[2][i]));
        most[i] = static_cast<int>(std::floor((extent + half) / kVisitBrickSize)) + 1;
    }
    std::map<std::pair<int, int>, std::pair<int, int>> ranges;
    for (int dz = -most.z; dz <= most.z; ++dz)
        for (int dy = -most.y; dy <= most.y; ++dy)
            for (int dx = -most.x; dx <= most.x; ++dx) {
                glm::dvec3 centre = double(kVisitBrickSize) * glm::dvec3(dx, dy, dz);
                double d = glm::length(a * centre);
                // |A x| lies within |A c| +- 3 cell diagonals for x within 3 voxels of c along every axis.
                if (d - half * cell > limit) continue;
                bool offset = d + half * cell <= limit;
                for (int z = -half; z <= half && !offset; ++z)
                    for (int y = -half; y <= half && !offset; ++y)
                        for (int x = -half; x <= half && !offset; ++x)
                            offset = glm::length(a * (centre + glm::dvec3(x, y, z))) <= limit;
                if (!offset) continue;
                auto [it, fresh] = ranges.try_emplace({dy, dz}, dx, dx);
                if (!fresh) {
                    it->second.first = std::min(it->second.first, dx);
                    it->second.second = std::max(it->second.second, dx);
                }
            }
    for (const auto& [yz, x] : ranges) rows_.push_back({yz.first, yz.second, x.first, x.second});
}

bool LaoReachBricks::isOffset(glm::ivec3 d) const {
    for (const Row& r : rows_)
        if (r.dy == d.y && r.dz == d.z) return d.x >= r.dxMin && d.x <= r.dxMax;
    return false;
}

void LaoReachBricks::setChanged(glm::ivec3 grid, const std::vector<std::uint8_t>& changed) {
    grid_ = grid;
    const std::size_t width = static_cast<std::size_t>(grid.x) + 1;
    rowPrefix_.assign(width * static_cast<std::size_t>(grid.y) * static_cast<std::size_t>(grid.z), 0);
    for (std::size_t row = 0; row < static_cast<std::size_t>(grid.y) * static_cast<std::size_t>(grid.z); ++row) {
        std::uint32_t* prefix = &rowPrefix_[row * width];
        const std::uint8_t* flags = &changed[row * static_cast<std::size_t>(grid.x)];
        for (int x = 0; x < grid.x; ++x) prefix[x + 1] = prefix[x] + (flags[x] ? 1u : 0u);
    }
}

bool LaoReachBricks::canChange(glm::ivec3 b) const {
    const std::size_t width = static_cast<std::size_t>(grid_.x) + 1;
    for (const Row& r : rows_) {
        int y = b.y + r.dy, z = b.z + r.dz;
        if (y < 0 || z < 0 || y >= grid_.y || z >= grid_.z) continue;
        int x0 = std::max(b.x + r.dxMin, 0), x1 = std::min(b.x + r.dxMax, grid_.x - 1);
        if (x0 > x1) continue;
        const std::uint32_t* prefix = &rowPrefix_[(static_cast<std::size_t>(z) * static_cast<std::size_t>(grid_.y) + static_cast<std::size_t>(y)) * width];
        if (prefix[x1 + 1] != prefix[x0]) return true;
    }
    return false;
}

}  // namespace curette
