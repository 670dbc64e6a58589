#pragma once
// Where to ask the clip test about a tract bundle: every streamline point plus points in between, so that no
// gap along a streamline exceeds the probe step. The inside flags at these points come from the GPU (a pass
// that evaluates the renderer's own clip test there) or from a CPU InsideTest (insideFlagsCpu, the oracle).
//
// Removed length, defined on the probe points: each sub-segment between consecutive probe points a, b counts
// length(a, b) * (inside(a) + inside(b)) / 2 (the trapezoid rule on the 0/1 inside indicator). Where the clip
// surface crosses a sub-segment this is off by at most half a sub-segment, so a straight chord through a
// clip region is measured within one probe step (at most step / 2 at each of its two ends).

#include "base/tractogram.h"
#include "plan/removal_field.h"

#include <cstdint>
#include <vector>

namespace curette::plan {

constexpr double kDefaultProbeStepMm = 0.25;

// At most this many probe points per bundle: each is a dvec3 here, a flag and a GPU copy, so more would be
// gigabytes for a step far finer than the data; it also keeps the 32-bit streamline offsets from wrapping.
constexpr std::size_t kMaxTractProbePoints = std::size_t(1) << 28;

// Streamline coordinates lie within this many millimetres of the origin: no scan is 100 m across, so a point
// beyond it is corrupt or in the wrong units, and one segment to it would need millions of probe points.
constexpr double kMaxTractCoordinateMm = 1e5;

// The probe points of every streamline, in order; streamline s spans
// [streamlineOffsets[s], streamlineOffsets[s + 1]) (streamlineCount + 1 offsets). Each original point is
// kept; a segment of length L gets ceil(L / stepMm) - 1 evenly spaced points between its ends. Throws
// InputError naming "points[i]" for a point that is not finite or lies beyond kMaxTractCoordinateMm, and
// "report.tract_step_mm" unless stepMm is positive, finite and gives at most kMaxTractProbePoints points.
std::vector<glm::dvec3> tractProbePoints(const Tractogram& tracts, double stepMm, std::vector<std::uint32_t>& streamlineOffsets);

// 1 where `inside` says the point is in the clip region, else 0.
std::vector<std::uint8_t> insideFlagsCpu(const std::vector<glm::dvec3>& points, const InsideTest& inside);

// The probe of one bundle with its inside flags: what the report needs per bundle.
struct TractProbe {
    std::vector<glm::dvec3> points;
    std::vector<std::uint32_t> streamlineOffsets;
    std::vector<std::uint8_t> insideFlags;  // one per point, 0 or 1
    double stepMm = kDefaultProbeStepMm;
};

}  // namespace curette::plan
