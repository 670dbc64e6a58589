#include "plan/tract_probe.h"

#include "base/error.h"

#include <cmath>
#include <string>

namespace curette::plan {

std::vector<glm::dvec3> tractProbePoints(const Tractogram& tracts, double stepMm, std::vector<std::uint32_t>& streamlineOffsets) {
    if (!(stepMm > 0.0) || !std::isfinite(stepMm))
        throw InputError(tracts.source, "probe_step_mm", "a positive length", std::to_string(stepMm));
    std::vector<glm::dvec3> points;
    points.reserve(tracts.points.size());
    streamlineOffsets.assign(1, 0);
    for (std::size_t s = 0; s < tracts.streamlineCount(); ++s) {
        const std::uint32_t first = tracts.offsets[s], end = tracts.offsets[s + 1];
        for (std::uint32_t p = first; p < end; ++p) {
            glm::dvec3 b(tracts.points[p]);
            if (p > first) {
                glm::dvec3 a(tracts.points[p - 1]);
                const double length = glm::length(b - a);
                const int pieces = static_cast<int>(std::ceil(length / stepMm));
                for (int m = 1; m < pieces; ++m) points.push_back(a + (b - a) * (double(m) / double(pieces)));
            }
            points.push_back(b);
        }
        streamlineOffsets.push_back(static_cast<std::uint32_t>(points.size()));
    }
    return points;
}

std::vector<std::uint8_t> insideFlagsCpu(const std::vector<glm::dvec3>& points, const InsideTest& inside) {
    std::vector<std::uint8_t> flags(points.size(), 0);
    for (std::size_t i = 0; i < points.size(); ++i) flags[i] = inside(points[i]) ? 1 : 0;
    return flags;
}

}  // namespace curette::plan
