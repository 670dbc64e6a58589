#pragma once
// Margins: how close the carve comes to a structure, boundary to boundary, in mm.
//
// The removed region and a structure are both unions of voxel cells: a labelled structure is its voxels'
// cells (the label volume is nearest-neighbour), and the carve is taken as the cells of the voxels it
// touches (tissue with removed fraction > 0). The gap between two cells of an axis-aligned lattice is the
// distance between their nearest corners, so one exact distance transform on the lattice of cell corners
// (dims + 1 per axis) gives every cell's gap to the removed cells, and the minimum over a label's cells is
// its margin: 0 when a cell of it abuts a removed cell (touching without removing anything of it).
//
// Accuracy: a cell the carve covers only in part counts whole, so a cell gap is never larger than the gap to
// what is removed, and smaller by at most the uncovered part of the nearest touched cell (under a cell
// diagonal; exact when the carve's faces lie on cell faces). refinedMargin closes that: it probes the partly
// covered cells nearest the structure at a lattice of sub-points with the clip test itself, then along a ray
// from the nearest inside one towards the structure, and measures from the inside points: for a face flat over
// a sub-point the margin is then within a quarter of a sub-point diagonal (Margin::uncertaintyMm) of the true
// gap, and never smaller than the cell gap. Grids with an oblique affine use the column norms as
// spacings (plan/distance_transform.h).

#include "plan/removal_field.h"

#include <cstdint>
#include <functional>
#include <vector>

namespace curette::plan {

// The touched cells of a carve over the grid: 0 untouched, 1 covered in part, 2 covered whole (every one of
// the 9 + N samples inside).
enum class Touch : std::uint8_t { None = 0, Part = 1, Whole = 2 };

struct CellGaps {
    glm::ivec3 dims{0};                    // the scan grid; the corner lattice is dims + 1
    glm::dvec3 spacingMm{0.0};
    glm::dmat4 worldToIndex{1.0}, indexToWorld{1.0};
    std::vector<double> cornerDistance2;   // mm^2 from each cell corner to the nearest removed cell; empty: nothing removed
    std::vector<double> cellGap2;          // mm^2 from each voxel's cell to the nearest removed cell

    bool empty() const { return cornerDistance2.empty(); }
    // The distance in mm from a world point to the removed cells: trilinear in the corner distances, exact on
    // the corners and along straight stretches of the region's faces. +infinity when nothing is removed.
    double distanceMm(glm::dvec3 world) const;
    // Bounds on that distance by the triangle inequality from the corners of the point's cell (the distance
    // is 1-Lipschitz): lower = max over corners of d(c) - |p - c|, never below 0; upper = min of d(c) + |p - c|.
    struct Bounds {
        double lower = 0, upper = 0;
    };
    Bounds distanceBoundsMm(glm::dvec3 world) const;
};

// `touch` marks, on the whole grid (x fastest), the touched cells.
CellGaps cellGapsTo(glm::ivec3 dims, const glm::dmat4& indexToWorld, const std::vector<Touch>& touch);

// The uncertainty of an unrefined cell gap in mm (how much smaller than the gap to what is removed it can
// be): the cell diagonal, the most a partly covered cell can add.
double marginUncertaintyMm(glm::dvec3 spacingMm);

// Which of a list of world points lie inside the clip region: the renderer's clip test on the GPU
// (RemovalProbe::insideFlags) or a CPU twin.
using PointsInside = std::function<std::vector<std::uint8_t>(const std::vector<glm::dvec3>& world)>;

// The sub-point spacing refinedMargin aims for, per axis (2 to 8 sub-points per cell axis).
inline constexpr double kRefineStepMm = 0.125;

struct Margin {
    double mm = 0;
    double uncertaintyMm = 0;   // refined: the gap to a face flat over a sub-point lies within this of mm;
                                // cells only: the gap lies in [mm, mm + this]
    bool contact = false;       // a probe point inside the carve lies in the structure (between the field's samples)
};

// The gap from what the carve removes to the cells `inStructure` marks (both on the whole grid, x fastest),
// refined through `inside` where the nearest touched cells are covered in part, probing each such cell at
// its own clip samples (`sampleOffsets`: step IV's N offsets, clip::antiAliasingOffsets) and a sub-point
// lattice. The structure must not hold a touched cell (its margin is then 0). A probe point inside the carve
// within the structure is contact (margin 0). +infinity when nothing is touched.
Margin refinedMargin(glm::ivec3 dims, const glm::dmat4& indexToWorld, const std::vector<Touch>& touch,
                     const std::vector<std::uint8_t>& inStructure, const std::vector<glm::dvec3>& sampleOffsets,
                     const PointsInside& inside);

// The same to a set of world points (a bundle's probe points near the carve): the distance from what the
// carve removes to the nearest point, over the touched cells within `reachMm` of the points. Exact to the
// points; to the streamlines through them, larger by at most half the probe step where the nearest approach
// falls between points.
Margin refinedMarginToPoints(glm::ivec3 dims, const glm::dmat4& indexToWorld, const std::vector<Touch>& touch,
                             const std::vector<glm::dvec3>& points, double reachMm, const std::vector<glm::dvec3>& sampleOffsets,
                             const PointsInside& inside);

// Bundles farther than this from the touched cells keep their cell gap (and its uncertainty, a cell diagonal):
// refining costs a search per cell that grows with the distance, and a millimetre matters less there.
inline constexpr double kRefineBundlesWithinMm = 10.0;

}  // namespace curette::plan
