#include "plan/tool_clearance.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace curette::plan {

namespace {

std::vector<Touch> cellsOf(const std::vector<std::uint8_t>& marked) {
    std::vector<Touch> touch(marked.size(), Touch::None);
    for (std::size_t i = 0; i < marked.size(); ++i)
        if (marked[i]) touch[i] = Touch::Whole;
    return touch;
}

}  // namespace

ToolClearance::ToolClearance(glm::ivec3 dims, const glm::dmat4& indexToWorld, const std::vector<std::uint8_t>& protectedCells)
    : gaps_(cellGapsTo(dims, indexToWorld, cellsOf(protectedCells))) {}

std::optional<Clearance> ToolClearance::of(const PosedMesh& tool) const {
    if (empty() || !tool.geometry) return std::nullopt;
    const std::vector<glm::dvec3> world = tool.worldVertices();
    double lower = std::numeric_limits<double>::infinity(), upper = lower;
    Clearance c;
    // Each triangle on a barycentric grid of n steps per edge: every point of it lies within a sub-triangle's
    // longest edge / sqrt(3) of a grid point (the circumradius of an acute triangle, half the longest edge of
    // an obtuse one), at most kClearanceSampleMm.
    for (const glm::uvec3& t : tool.geometry->triangles) {
        const glm::dvec3 a = world[t.x], b = world[t.y], d = world[t.z];
        const double longest = std::max({glm::length(b - a), glm::length(d - b), glm::length(a - d)});
        const int n = std::max(1, static_cast<int>(std::ceil(longest / (kClearanceSampleMm * std::sqrt(3.0)))));
        for (int i = 0; i <= n; ++i)
            for (int j = 0; i + j <= n; ++j) {
                const glm::dvec3 p = a + (b - a) * (static_cast<double>(i) / n) + (d - a) * (static_cast<double>(j) / n);
                const CellGaps::Bounds bounds = gaps_.distanceBoundsMm(p);
                if (bounds.lower < lower) lower = bounds.lower, c.nearestOnTool = p;
                upper = std::min(upper, bounds.upper);
            }
    }
    // Any surface point q lies within kClearanceSampleMm of a sample s, and the distance is 1-Lipschitz.
    c.mm = std::max(0.0, lower - kClearanceSampleMm);
    c.uncertaintyMm = std::max(0.0, upper - c.mm);
    return c;
}

}  // namespace curette::plan
