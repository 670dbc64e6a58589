#include "render/model/depth_interval_pyramid.h"

#include <algorithm>
#include <stdexcept>

namespace curette {

DepthIntervalPyramid::DepthIntervalPyramid(int resolution, const std::vector<std::vector<float>>& fronts,
                                           const std::vector<std::vector<float>>& backs)
    : resolution_(resolution) {
    const std::size_t pixels = std::size_t(resolution) * std::size_t(resolution);
    if (resolution < 1 || fronts.size() != backs.size()) throw std::logic_error("DepthIntervalPyramid: a front and a back per interval");
    for (std::size_t j = 0; j < fronts.size(); ++j) {
        if (fronts[j].size() != pixels || backs[j].size() != pixels) throw std::logic_error("DepthIntervalPyramid: resolution^2 pixels a layer");
        std::vector<Level> levels{{resolution, fronts[j], backs[j]}};
        while (levels.back().side > 1) {
            const Level& fine = levels.back();
            Level coarse;
            coarse.side = (fine.side + 1) / 2;
            coarse.maxFront.assign(std::size_t(coarse.side) * std::size_t(coarse.side), -1e30f);
            coarse.minBack.assign(coarse.maxFront.size(), 1e30f);
            for (int y = 0; y < fine.side; ++y)
                for (int x = 0; x < fine.side; ++x) {
                    std::size_t from = std::size_t(y) * std::size_t(fine.side) + std::size_t(x);
                    std::size_t to = std::size_t(y / 2) * std::size_t(coarse.side) + std::size_t(x / 2);
                    coarse.maxFront[to] = std::max(coarse.maxFront[to], fine.maxFront[from]);
                    coarse.minBack[to] = std::min(coarse.minBack[to], fine.minBack[from]);
                }
            levels.push_back(std::move(coarse));
        }
        intervals_.push_back(std::move(levels));
    }
}

bool DepthIntervalPyramid::intervalHolds(glm::ivec2 lo, glm::ivec2 hi, double zLo, double zHi) const {
    if (glm::any(glm::lessThan(lo, glm::ivec2(0))) || glm::any(glm::greaterThanEqual(hi, glm::ivec2(resolution_))) ||
        glm::any(glm::lessThan(hi, lo)))
        return false;
    // The finest level whose blocks cover the rectangle in at most eight per axis (they reach at most a
    // seventh of its side beyond it).
    int k = 0;
    while (((hi.x >> k) - (lo.x >> k) > 7 || (hi.y >> k) - (lo.y >> k) > 7)) ++k;
    for (const std::vector<Level>& levels : intervals_) {
        const Level& level = levels[std::size_t(k)];
        bool holds = true;
        for (int y = lo.y >> k; y <= (hi.y >> k) && holds; ++y)
            for (int x = lo.x >> k; x <= (hi.x >> k) && holds; ++x) {
                std::size_t b = std::size_t(y) * std::size_t(level.side) + std::size_t(x);
                holds = double(level.maxFront[b]) < zLo && zHi < double(level.minBack[b]);
            }
        if (holds) return true;
    }
    return false;
}

}  // namespace curette
