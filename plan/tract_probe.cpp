#include "plan/tract_probe.h"

#include "base/error.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace curette::plan {

namespace {

std::string number(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
}

// The probe points strictly between a and b, in double: a tiny step or a far point must not overflow the count.
double pointsBetween(glm::dvec3 a, glm::dvec3 b, double stepMm) {
    return std::max(std::ceil(glm::length(b - a) / stepMm) - 1.0, 0.0);
}

// Every point finite and within kMaxTractCoordinateMm, so that the counts below measure the step alone.
void checkPoints(const Tractogram& tracts) {
    for (std::size_t s = 0; s < tracts.streamlineCount(); ++s)
        for (std::uint32_t p = tracts.offsets[s]; p < tracts.offsets[s + 1]; ++p) {
            const glm::dvec3 q(tracts.points[p]);
            bool ok = true;
            for (int a = 0; a < 3; ++a) ok = ok && std::isfinite(q[a]) && std::abs(q[a]) <= kMaxTractCoordinateMm;
            if (!ok)
                throw InputError(tracts.source, "points[" + std::to_string(p) + "]",
                                 "a finite point with every coordinate within +-" + number(kMaxTractCoordinateMm) + " mm",
                                 "(" + number(q.x) + ", " + number(q.y) + ", " + number(q.z) + ") in streamline " + std::to_string(s));
        }
}

}  // namespace

std::vector<glm::dvec3> tractProbePoints(const Tractogram& tracts, double stepMm, std::vector<std::uint32_t>& streamlineOffsets) {
    if (!(stepMm > 0.0) || !std::isfinite(stepMm))
        throw InputError(tracts.source, "report.tract_step_mm", "a positive length", number(stepMm));
    checkPoints(tracts);
    double total = 0;
    for (std::size_t s = 0; s < tracts.streamlineCount(); ++s)
        for (std::uint32_t p = tracts.offsets[s]; p < tracts.offsets[s + 1]; ++p)
            total += 1.0 + (p > tracts.offsets[s] ? pointsBetween(glm::dvec3(tracts.points[p - 1]), glm::dvec3(tracts.points[p]), stepMm) : 0.0);
    if (total > double(kMaxTractProbePoints))
        throw InputError(tracts.source, "report.tract_step_mm",
                         "a step giving at most " + std::to_string(kMaxTractProbePoints) +
                             " probe points (segment length / step, summed over the streamlines)",
                         number(stepMm) + " mm, which gives " + number(total) + " points");
    std::vector<glm::dvec3> points;
    points.reserve(static_cast<std::size_t>(total));
    streamlineOffsets.assign(1, 0);
    for (std::size_t s = 0; s < tracts.streamlineCount(); ++s) {
        const std::uint32_t first = tracts.offsets[s], end = tracts.offsets[s + 1];
        for (std::uint32_t p = first; p < end; ++p) {
            glm::dvec3 b(tracts.points[p]);
            if (p > first) {
                glm::dvec3 a(tracts.points[p - 1]);
                const auto between = static_cast<std::size_t>(pointsBetween(a, b, stepMm));
                const double pieces = double(between + 1);
                for (std::size_t m = 1; m <= between; ++m) points.push_back(a + (b - a) * (double(m) / pieces));
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
