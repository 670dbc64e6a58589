#pragma once
// Tool clearance: how close a clip mesh (the tool a planner holds) comes to the nearest protected structure,
// cheap enough to show live while the tool moves. The removal report's margins (plan/margin.h) start from
// what the carve removes and follow 0.2 s after the motion stops; this is the tool's own surface, every frame.
//
// The same machinery as the margins: the protected structures are unions of voxel cells, one exact distance
// transform on the lattice of cell corners (cellGapsTo) gives every corner's distance to them, and a point's
// distance is bounded from the corners of its cell by the triangle inequality. The tool's surface is sampled
// at points no farther than kClearanceSampleMm apart on every triangle. The figure shown is a lower bound:
// the true gap from the surface to the structures is never smaller than `mm`, and exceeds it by at most
// `uncertaintyMm` (a sample's corner bound plus the sample spacing). A structure wholly inside the tool is
// not seen from its surface: the report, once current, says it is touched.

#include "plan/margin.h"
#include "plan/removal_field.h"

#include <optional>

namespace curette::plan {

// Surface samples are at most this far from every point of the tool's surface.
inline constexpr double kClearanceSampleMm = 0.25;

struct Clearance {
    double mm = 0;              // lower bound of the gap (0: contact or overlap)
    double uncertaintyMm = 0;   // the gap lies in [mm, mm + uncertaintyMm]
    glm::dvec3 nearestOnTool{0.0};   // the surface sample the bound was found at (world RAS mm)
};

class ToolClearance {
public:
    // `protectedCells` marks, on the scan grid (x fastest), the voxels of every protected structure.
    ToolClearance(glm::ivec3 dims, const glm::dmat4& indexToWorld, const std::vector<std::uint8_t>& protectedCells);
    bool empty() const { return gaps_.empty(); }
    // The clearance of `tool` (nullopt when there is no protected structure).
    std::optional<Clearance> of(const PosedMesh& tool) const;

private:
    CellGaps gaps_;
};

}  // namespace curette::plan
