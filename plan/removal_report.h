#pragma once
// The carve as a plan: what it removes, in total, per labelled structure and per tract bundle, and how close
// it comes to what must be spared. Inputs are the scan, its TF, the removal field (step IV's inside-sample
// counts, plan/removal_field.h), label sets resampled to the scan grid and bundles with their probe flags.
//
// Definitions (voxel v, removed fraction r(v) = count / (9 + N), tissue t(v) in {0, 1}, plan/tissue_mask.h):
//   removed mL       sum_v t(v) r(v) |det A| / 1000, A the 3x3 part of indexToWorld (voxel volume in mm^3).
//                    The AA samples make r a 9 + N point quadrature of the voxel's covered fraction, so the
//                    total is good to a fraction of one voxel per voxel of surface crossed, and the errors
//                    of neighbouring voxels largely cancel (tests/plan: well under 1 % for r >= 8 voxels).
//   touched          t(v) r(v) > 0.
//   uncertainty      of a removed volume: over its partly covered voxels (0 < r < 1), voxel volume times
//                    1 / (9 + N) (the quadrature's step) plus h / s (a face the clip test places up to h =
//                    facePlacementMm from the mesh's moves r by up to h over the smallest spacing s): a bound
//                    for errors of one sign, which the analytic tests stay well inside.
//   removed region   R = { v : t(v) = 1 and r(v) >= 0.5 }: the voxels the carve takes (margins start there).
//   per label L      volume mL (its voxels * voxel volume), removed mL (the sum above over L's voxels),
//                    share = removed / volume, touched (any voxel of L touched),
//                    intrusion depth mm: max over v in R and L of the distance from v's centre to the
//                    nearest centre of a voxel not of L (outside the grid counts as not of L): how deep
//                    the carve reaches into L; 0 when R misses L.
//                    margin mm: the gap from the touched cells to L's cells, boundary to boundary
//                    (plan/margin.h); 0 when touched or abutting, +infinity when nothing is touched.
//   per bundle       streamlines, cut (a streamline is cut when any of its probe points is inside), share =
//                    cut / streamlines, total length, removed length (plan/tract_probe.h), margin mm (min over
//                    its probe points of the distance to the touched cells, plan/margin.h; 0 if cut).
// Accuracy: margins are never larger than the gap to what is removed and smaller by at most one cell
// diagonal (a partly covered cell counts whole; exact where the carve's faces lie on cell faces). The
// intrusion depth is between voxel centres (exact EDT, plan/distance_transform.h) and exceeds the
// continuous one by up to one voxel.

#include "base/label_map.h"
#include "base/tractogram.h"
#include "base/transfer_function.h"
#include "base/volume.h"
#include "plan/margin.h"
#include "plan/removal_field.h"
#include "plan/tissue_mask.h"
#include "plan/tract_probe.h"

#include <cstdint>
#include <string>
#include <vector>

namespace curette::plan {

// A label volume on the scan grid (resampleNearest first) with its table; `labels` and `table` must outlive
// the call. Label id 0 is "no label" and never reported.
struct LabelSet {
    std::string name;                // e.g. "aal"; names the rows
    const LabelMap* labels = nullptr;
    const LabelTable* table = nullptr;
    std::vector<int> protectedIds;   // always reported; a touch is a warning
    std::vector<double> shownOpacity;  // by id: the opacity per unit length it is drawn with, 0 when not shown
};

// The tissue over `box` (x fastest) as the report counts it: the tissue rule (plan/tissue_mask.h), shown
// labels with the opacity they are drawn with under the opacity rule, and protected labels always. The
// exports (removed region, cavity) take it too.
std::vector<std::uint8_t> reportTissue(const VolumeData& volume, const TransferFunction& tf, const ReportSettings& settings,
                                       const std::vector<LabelSet>& labelSets, const VoxelBox& box);

// A bundle and its probe (tractProbePoints with inside flags from the GPU or insideFlagsCpu); `tracts` must
// outlive the call.
struct BundleInput {
    std::string name;
    const Tractogram* tracts = nullptr;
    bool isProtected = false;
    TractProbe probe;
};

struct StructureRow {
    std::string labelSet;
    int id = 0;
    std::string name;
    bool isProtected = false;
    std::uint64_t voxels = 0;          // of this label in the grid
    std::uint64_t touchedVoxels = 0, partialVoxels = 0;
    double volumeMl = 0, removedMl = 0, share = 0;
    double removedUncertaintyMl = 0;
    bool touched = false;
    double intrusionDepthMm = 0;
    double intrusionUncertaintyMm = 0; // a cell diagonal (between voxel centres)
    double marginMm = 0;               // +infinity when nothing is removed
    double marginUncertaintyMm = 0;    // plan/margin.h
};

struct BundleRow {
    std::string name;
    bool isProtected = false;
    std::uint64_t streamlines = 0, cut = 0;
    double share = 0;
    double totalLengthMm = 0, removedLengthMm = 0;
    double marginMm = 0;               // +infinity when nothing is removed
    double marginUncertaintyMm = 0;    // a cell diagonal: the gap can be larger by up to this (plan/margin.h)
    Tractogram cutTracts, sparedTracts;  // the input's streamlines partitioned, scalars and properties kept
};

struct ReportTimings {
    double tissueMs = 0, distanceMs = 0, structuresMs = 0, intrusionMs = 0, bundlesMs = 0, totalMs = 0;
};

struct Report {
    std::string volumeSource;
    TissueRule tissue = TissueRule::Opacity;
    double opacityThreshold = 0;
    glm::ivec3 dims{0};
    glm::dvec3 spacingMm{0.0};
    double voxelVolumeMl = 0;
    int samplesPerVoxel = 0;           // 9 + N
    VoxelBox fieldBox;
    double removedMl = 0, removedUncertaintyMl = 0;
    double facePlacementMm = 0;             // the field's
    std::uint64_t touchedVoxels = 0, partialVoxels = 0;
    std::uint64_t removedRegionVoxels = 0;  // |R|
    std::vector<StructureRow> structures;   // per label set, by removed mL (largest first), then id
    std::vector<BundleRow> bundles;         // in input order
    ReportTimings timings;

    // One line per protected structure or bundle the carve touches (empty when none).
    std::vector<std::string> warnings() const;
};

// The removed region R on the field's whole grid (1 where tissue and count / (9 + N) >= 0.5; the definition
// above), from the tissue over the field's box (reportTissue; empty: every voxel is tissue).
// The report's margins and the exported labelmap both start from it.
std::vector<std::uint8_t> removedRegionOnGrid(const RemovalField& field, const std::vector<std::uint8_t>& tissueInFieldBox);

// `inside` (the clip test at world points, plan/margin.h) refines the margins of untouched labels; without it
// they are cell gaps. Throws InputError when a label map or the field is not on the volume's grid, or a probe
// does not match its tractogram.
Report computeReport(const VolumeData& volume, const TransferFunction& tf, const ReportSettings& settings,
                     const RemovalField& field, const std::vector<LabelSet>& labelSets,
                     const std::vector<BundleInput>& bundles, const PointsInside& inside = {});

}  // namespace curette::plan
