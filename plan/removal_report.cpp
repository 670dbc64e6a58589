#include "plan/removal_report.h"

#include "base/error.h"
#include "mesh/coverage.h"
#include "plan/distance_transform.h"
#include "plan/margin.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

namespace curette::plan {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) { return std::chrono::duration<double, std::milli>(Clock::now() - start).count(); }

std::string labelName(const LabelTable* table, int id) {
    if (table)
        if (const LabelEntry* e = table->find(id)) return e->name;
    return "label " + std::to_string(id);
}

Tractogram subsetStreamlines(const Tractogram& in, const std::vector<std::uint8_t>& keep) {
    Tractogram out;
    out.source = in.source;
    out.scalarNames = in.scalarNames;
    out.propertyNames = in.propertyNames;
    const std::size_t scalarsPerPoint = in.scalarNames.size(), propertiesPerStreamline = in.propertyNames.size();
    for (std::size_t s = 0; s < in.streamlineCount(); ++s) {
        if (!keep[s]) continue;
        const std::size_t first = in.offsets[s], end = in.offsets[s + 1];
        out.points.insert(out.points.end(), in.points.begin() + static_cast<std::ptrdiff_t>(first),
                          in.points.begin() + static_cast<std::ptrdiff_t>(end));
        if (scalarsPerPoint && in.scalars.size() == in.points.size() * scalarsPerPoint)
            out.scalars.insert(out.scalars.end(), in.scalars.begin() + static_cast<std::ptrdiff_t>(first * scalarsPerPoint),
                               in.scalars.begin() + static_cast<std::ptrdiff_t>(end * scalarsPerPoint));
        if (propertiesPerStreamline && in.properties.size() == in.streamlineCount() * propertiesPerStreamline)
            out.properties.insert(out.properties.end(),
                                  in.properties.begin() + static_cast<std::ptrdiff_t>(s * propertiesPerStreamline),
                                  in.properties.begin() + static_cast<std::ptrdiff_t>((s + 1) * propertiesPerStreamline));
        out.offsets.push_back(static_cast<std::uint32_t>(out.points.size()));
    }
    return out;
}

// The intrusion depth of label `id`: max over voxels of R and the label of the distance to the nearest centre
// not of the label. The transform runs on the bounding box of those voxels grown by a pad, with everything
// outside the grid counting as "not of the label". A value is exact when it does not exceed the distance to
// the nearest centre beyond the sub-box (a nearer feature cannot lie out there); otherwise the pad doubles.
double intrusionDepthMm(const LabelMap& labels, std::uint16_t id, const std::vector<std::uint8_t>& removedRegion,
                        glm::ivec3 lo, glm::ivec3 hi, glm::dvec3 spacing) {
    const glm::ivec3 dims = labels.dims;
    for (int pad = 4;; pad *= 2) {
        const glm::ivec3 origin = lo - pad, size = hi - lo + 1 + 2 * pad;
        const VoxelBox box{origin, size};
        std::vector<std::uint8_t> notLabel(box.voxelCount(), 1);
        std::size_t at = 0;
        for (int k = origin.z; k < origin.z + size.z; ++k)
            for (int j = origin.y; j < origin.y + size.y; ++j)
                for (int i = origin.x; i < origin.x + size.x; ++i, ++at)
                    if (i >= 0 && j >= 0 && k >= 0 && i < dims.x && j < dims.y && k < dims.z)
                        notLabel[at] = labels.id(i, j, k) != id ? 1 : 0;
        const std::vector<double> d2 = squaredDistanceTransformMm(size, spacing, notLabel);
        // The sub-box reaches past the grid on every side: everything beyond it is "not of the label" but
        // farther than the ring just outside the grid, so every value is exact.
        const bool coversGrid = glm::all(glm::lessThan(origin, glm::ivec3(0))) && glm::all(glm::greaterThan(origin + size, dims));
        double deepest2 = 0;
        bool exact = true;
        for (int k = lo.z; k <= hi.z; ++k)
            for (int j = lo.y; j <= hi.y; ++j)
                for (int i = lo.x; i <= hi.x; ++i) {
                    const std::size_t index = labels.linearIndex(i, j, k);
                    if (!removedRegion[index] || labels.ids[index] != id) continue;
                    const glm::ivec3 local = glm::ivec3(i, j, k) - origin;
                    const double value = d2[(static_cast<std::size_t>(local.z) * static_cast<std::size_t>(size.y) +
                                             static_cast<std::size_t>(local.y)) * static_cast<std::size_t>(size.x) +
                                            static_cast<std::size_t>(local.x)];
                    deepest2 = std::max(deepest2, value);
                    glm::dvec3 beyond = glm::min(glm::dvec3(local + 1), glm::dvec3(size - local)) * spacing;
                    const double reach = std::min({beyond.x, beyond.y, beyond.z});
                    if (value > reach * reach) exact = false;
                }
        if (exact || coversGrid) return std::sqrt(deepest2);
    }
}

void checkSameGrid(const std::string& what, glm::ivec3 dims, const glm::dmat4& a, const VolumeData& volume) {
    if (dims != volume.dims) throw InputError(what, "dims", "the scan's grid (resample onto it first)");
    double worst = 0;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 3; ++r) worst = std::max(worst, std::abs(a[c][r] - volume.indexToWorld[c][r]));
    if (worst > 1e-6) throw InputError(what, "index_to_world", "the scan's affine (resample onto it first)");
}

}  // namespace

std::vector<std::string> Report::warnings() const {
    std::vector<std::string> out;
    char line[512];
    for (const StructureRow& s : structures)
        if (s.isProtected && s.touched) {
            std::snprintf(line, sizeof line, "WARNING: protected structure %s/%s (id %d) touched: %.3f mL removed, %.1f mm deep",
                          s.labelSet.c_str(), s.name.c_str(), s.id, s.removedMl, s.intrusionDepthMm);
            out.emplace_back(line);
        }
    for (const BundleRow& b : bundles)
        if (b.isProtected && b.cut > 0) {
            std::snprintf(line, sizeof line, "WARNING: protected bundle %s cut: %llu of %llu streamlines, %.1f mm removed",
                          b.name.c_str(), static_cast<unsigned long long>(b.cut), static_cast<unsigned long long>(b.streamlines),
                          b.removedLengthMm);
            out.emplace_back(line);
        }
    return out;
}

std::vector<std::uint8_t> reportTissue(const VolumeData& volume, const TransferFunction& tf, const ReportSettings& settings,
                                       const std::vector<LabelSet>& labelSets, const VoxelBox& box) {
    std::vector<std::uint8_t> tissue = tissueInBox(volume, tf, settings, labelSets.empty() ? nullptr : labelSets.front().labels, box);
    if (settings.tissue == TissueRule::Opacity) {
        std::vector<ShownLabels> shown;
        for (const LabelSet& set : labelSets)
            if (!set.shownOpacity.empty()) shown.push_back({set.labels, &set.shownOpacity});
        addShownLabels(tissue, box, shown, settings.opacityThreshold);
    }
    for (const LabelSet& set : labelSets) addProtectedLabels(tissue, box, *set.labels, set.protectedIds);
    return tissue;
}

std::vector<std::uint8_t> removedRegionOnGrid(const RemovalField& field, const std::vector<std::uint8_t>& tissueInFieldBox) {
    const glm::ivec3 dims = field.gridDims;
    std::vector<std::uint8_t> region(std::size_t(dims.x) * std::size_t(dims.y) * std::size_t(dims.z), 0);
    std::size_t at = 0;
    for (int k = field.origin.z; k < field.origin.z + field.size.z; ++k)
        for (int j = field.origin.y; j < field.origin.y + field.size.y; ++j)
            for (int i = field.origin.x; i < field.origin.x + field.size.x; ++i, ++at) {
                bool tissue = tissueInFieldBox.empty() || tissueInFieldBox[at];
                if (tissue && 2 * int(field.insideSamples[at]) >= field.samplesPerVoxel)
                    region[(std::size_t(k) * std::size_t(dims.y) + std::size_t(j)) * std::size_t(dims.x) + std::size_t(i)] = 1;
            }
    return region;
}

namespace {

void checkInputs(const VolumeData& volume, const RemovalField& field, const std::vector<LabelSet>& labelSets) {
    field.validate();
    checkSameGrid("<removal field>", field.gridDims, field.indexToWorld, volume);
    for (const LabelSet& set : labelSets) {
        if (!set.labels) throw InputError("<label set " + set.name + ">", "labels", "a label map");
        checkSameGrid(set.labels->source, set.labels->dims, set.labels->indexToWorld, volume);
    }
}

// The grid and the settings the report is computed on.
Report reportOf(const VolumeData& volume, const ReportSettings& settings, const RemovalField& field) {
    Report report;
    report.volumeSource = volume.source;
    report.tissue = settings.tissue;
    report.opacityThreshold = settings.opacityThreshold;
    report.dims = volume.dims;
    report.spacingMm = gridSpacingMm(volume.indexToWorld);
    report.voxelVolumeMl = std::abs(glm::determinant(glm::dmat3(volume.indexToWorld))) / 1000.0;
    report.samplesPerVoxel = field.samplesPerVoxel;
    report.facePlacementMm = field.facePlacementMm;
    report.fieldBox = field.box();
    return report;
}

// What every later stage reads: the tissue over the field box and the removed region R on the whole grid.
struct Removal {
    glm::dmat4 indexToWorld{1.0};             // the scan's
    VoxelBox box;
    std::vector<std::uint8_t> tissue;         // over the field box
    std::vector<std::uint8_t> removedRegion;  // R, on the grid
    std::vector<Touch> touch;                 // t(v) r(v) > 0 (whole: r = 1), on the grid: margins are measured to these
    CellGaps gaps;                            // to the touched cells (plan/margin.h); empty when nothing needs it
};

// The bound of plan/removal_report.h "uncertainty" for a volume with `partialVoxels` partly covered voxels.
double removedUncertaintyMl(const Report& report, std::uint64_t partialVoxels) {
    const double smallest = std::min({report.spacingMm.x, report.spacingMm.y, report.spacingMm.z});
    return double(partialVoxels) * report.voxelVolumeMl * (1.0 / report.samplesPerVoxel + report.facePlacementMm / smallest);
}

// Tissue and the removed fraction over the field box (nothing is removed outside it).
Removal measureTissue(Report& report, const VolumeData& volume, const TransferFunction& tf, const ReportSettings& settings,
                      const RemovalField& field, const std::vector<LabelSet>& labelSets) {
    Removal removal;
    removal.indexToWorld = volume.indexToWorld;
    removal.box = field.box();
    const VoxelBox& box = removal.box;
    removal.tissue = reportTissue(volume, tf, settings, labelSets, box);
    removal.removedRegion = removedRegionOnGrid(field, removal.tissue);
    removal.touch.assign(volume.voxelCount(), Touch::None);
    std::uint64_t removedSamples = 0;  // sum of t(v) * count(v): the total in units of voxel / (9 + N)
    std::size_t at = 0;
    for (int k = box.origin.z; k < box.origin.z + box.size.z; ++k)
        for (int j = box.origin.y; j < box.origin.y + box.size.y; ++j)
            for (int i = box.origin.x; i < box.origin.x + box.size.x; ++i, ++at) {
                if (!removal.tissue[at] || field.insideSamples[at] == 0) continue;
                removedSamples += field.insideSamples[at];
                ++report.touchedVoxels;
                report.partialVoxels += field.insideSamples[at] < field.samplesPerVoxel ? 1 : 0;
                removal.touch[volume.linearIndex(i, j, k)] = field.insideSamples[at] == field.samplesPerVoxel ? Touch::Whole : Touch::Part;
                report.removedRegionVoxels += removal.removedRegion[volume.linearIndex(i, j, k)];
            }
    report.removedMl = double(removedSamples) / double(field.samplesPerVoxel) * report.voxelVolumeMl;
    report.removedUncertaintyMl = removedUncertaintyMl(report, report.partialVoxels);
    return removal;
}

// Per label of one set: counts and closest approach over the grid, removal sums and R's bounding box over the
// field box.
struct LabelSums {
    std::size_t ids = 0;
    std::vector<std::uint64_t> voxels, touched, partial, removedSamples;
    std::vector<double> closest2;
    std::vector<glm::ivec3> regionLo, regionHi;  // regionHi.x < 0: no voxel of the label in R
};

LabelSums sumLabels(const LabelSet& set, const RemovalField& field, const Removal& removal) {
    const LabelMap& labels = *set.labels;
    int maxId = 0;
    for (std::uint16_t id : labels.ids) maxId = std::max(maxId, int(id));
    for (int id : set.protectedIds) maxId = std::max(maxId, id);
    LabelSums sums;
    const std::size_t ids = sums.ids = static_cast<std::size_t>(maxId) + 1;
    sums.voxels.assign(ids, 0), sums.touched.assign(ids, 0), sums.partial.assign(ids, 0), sums.removedSamples.assign(ids, 0);
    sums.closest2.assign(ids, kInfinity);
    sums.regionLo.assign(ids, glm::ivec3(std::numeric_limits<int>::max())), sums.regionHi.assign(ids, glm::ivec3(-1));
    if (removal.gaps.empty()) {
        for (std::uint16_t id : labels.ids) ++sums.voxels[id];
    } else {
        for (std::size_t v = 0; v < labels.ids.size(); ++v) {
            const std::uint16_t id = labels.ids[v];
            ++sums.voxels[id];
            sums.closest2[id] = std::min(sums.closest2[id], removal.gaps.cellGap2[v]);
        }
    }
    const VoxelBox& box = removal.box;
    std::size_t at = 0;
    for (int k = box.origin.z; k < box.origin.z + box.size.z; ++k)
        for (int j = box.origin.y; j < box.origin.y + box.size.y; ++j)
            for (int i = box.origin.x; i < box.origin.x + box.size.x; ++i, ++at) {
                if (!removal.tissue[at] || field.insideSamples[at] == 0) continue;
                const std::size_t index = labels.linearIndex(i, j, k);
                const std::uint16_t id = labels.ids[index];
                sums.removedSamples[id] += field.insideSamples[at];
                ++sums.touched[id];
                sums.partial[id] += field.insideSamples[at] < field.samplesPerVoxel ? 1 : 0;
                if (removal.removedRegion[index]) {
                    sums.regionLo[id] = glm::min(sums.regionLo[id], glm::ivec3(i, j, k));
                    sums.regionHi[id] = glm::max(sums.regionHi[id], glm::ivec3(i, j, k));
                }
            }
    return sums;
}

// One row per touched or protected label; its margin is the closest approach of an untouched one.
std::vector<StructureRow> structureRows(const LabelSet& set, const LabelSums& sums, const Report& report) {
    std::vector<StructureRow> rows;
    std::vector<bool> isProtected(sums.ids, false);
    for (int id : set.protectedIds)
        if (id > 0) isProtected[static_cast<std::size_t>(id)] = true;
    for (std::size_t id = 1; id < sums.ids; ++id) {
        if (!sums.touched[id] && !isProtected[id]) continue;
        StructureRow row;
        row.labelSet = set.name;
        row.id = int(id);
        row.name = labelName(set.table, row.id);
        row.isProtected = isProtected[id];
        row.voxels = sums.voxels[id];
        row.touchedVoxels = sums.touched[id];
        row.partialVoxels = sums.partial[id];
        row.removedUncertaintyMl = removedUncertaintyMl(report, row.partialVoxels);
        row.intrusionUncertaintyMm = glm::length(report.spacingMm);
        row.volumeMl = double(sums.voxels[id]) * report.voxelVolumeMl;
        row.removedMl = double(sums.removedSamples[id]) / double(report.samplesPerVoxel) * report.voxelVolumeMl;
        row.share = row.volumeMl > 0 ? row.removedMl / row.volumeMl : 0.0;
        row.touched = sums.touched[id] > 0;
        row.marginMm = row.touched ? 0.0 : std::sqrt(sums.closest2[id]);
        rows.push_back(std::move(row));
    }
    return rows;
}

// The margins of untouched labels, boundary to boundary: refined through the clip test where the nearest
// touched cells are covered in part (plan/margin.h), else the cell gap and its uncertainty.
void refineMargins(std::vector<StructureRow>& rows, const LabelMap& labels, const Removal& removal, const Report& report,
                   const PointsInside& inside) {
    for (StructureRow& row : rows) {
        if (row.touched) continue;
        if (std::isinf(row.marginMm)) continue;
        std::vector<std::uint8_t> inLabel(labels.ids.size());
        for (std::size_t v = 0; v < labels.ids.size(); ++v) inLabel[v] = labels.ids[v] == row.id ? 1 : 0;
        const Margin m = refinedMargin(report.dims, labels.indexToWorld, removal.touch, inLabel,
                                       clip::antiAliasingOffsets(report.samplesPerVoxel - 9), inside);
        row.marginMm = m.mm;
        row.marginUncertaintyMm = m.uncertaintyMm;
        // The carve reaches into the structure between the field's samples: contact, though no sample counted it.
        row.touched = m.contact;
    }
}

// The intrusion depth of every label with voxels in R, then the rows by removed mL (largest first), then id.
void addIntrusionDepths(std::vector<StructureRow>& rows, const LabelMap& labels, const LabelSums& sums, const Removal& removal,
                        glm::dvec3 spacingMm) {
    for (StructureRow& row : rows) {
        const std::size_t id = static_cast<std::size_t>(row.id);
        if (sums.regionHi[id].x >= 0)
            row.intrusionDepthMm = intrusionDepthMm(labels, static_cast<std::uint16_t>(row.id), removal.removedRegion, sums.regionLo[id],
                                                    sums.regionHi[id], spacingMm);
    }
    std::stable_sort(rows.begin(), rows.end(), [](const StructureRow& a, const StructureRow& b) {
        return a.removedMl != b.removedMl ? a.removedMl > b.removedMl : a.id < b.id;
    });
}

// One bundle: cut flags, lengths (trapezoid rule on the inside flags, plan/tract_probe.h) and its margin.
BundleRow bundleRow(const BundleInput& in, const Removal& removal, const Report& report, const PointsInside& inside) {
    if (!in.tracts) throw InputError("<bundle " + in.name + ">", "tracts", "a tractogram");
    const Tractogram& tracts = *in.tracts;
    const TractProbe& probe = in.probe;
    if (probe.streamlineOffsets.size() != tracts.streamlineCount() + 1 || probe.insideFlags.size() != probe.points.size() ||
        (!probe.streamlineOffsets.empty() && probe.streamlineOffsets.back() != probe.points.size()))
        throw InputError(tracts.source, "probe", "tractProbePoints of this tractogram with one inside flag per point");
    // The trilinear interpolant of a 1-Lipschitz function sampled on an orthogonal grid changes by at most
    // sqrt(3) per mm: after a probe at distance d, the next (d - best) / sqrt(3) mm of the streamline cannot
    // come closer than the best so far, so they are skipped (the result is the same as probing every point).
    const double lipschitz = std::sqrt(3.0);
    BundleRow row;
    row.name = in.name;
    row.isProtected = in.isProtected;
    row.streamlines = tracts.streamlineCount();
    row.marginMm = kInfinity;
    row.marginUncertaintyMm = marginUncertaintyMm(removal.gaps.spacingMm);
    std::vector<std::uint8_t> cut(tracts.streamlineCount(), 0);
    for (std::size_t s = 0; s < tracts.streamlineCount(); ++s) {
        const std::uint32_t first = probe.streamlineOffsets[s], end = probe.streamlineOffsets[s + 1];
        for (std::uint32_t p = first; p < end; ++p) {
            if (probe.insideFlags[p]) cut[s] = 1;
            if (p > first) {
                const double length = glm::length(probe.points[p] - probe.points[p - 1]);
                row.totalLengthMm += length;
                row.removedLengthMm += length * 0.5 * double(probe.insideFlags[p] + probe.insideFlags[p - 1]);
            }
        }
        if (cut[s]) {
            ++row.cut;
            row.marginMm = 0;
        } else if (!removal.gaps.empty() && row.marginMm > 0) {
            double skip = 0;
            for (std::uint32_t p = first; p < end; ++p) {
                if (p > first) skip -= glm::length(probe.points[p] - probe.points[p - 1]);
                if (skip > 0) continue;
                const double d = removal.gaps.distanceMm(probe.points[p]);
                row.marginMm = std::min(row.marginMm, d);
                skip = (d - row.marginMm) / lipschitz;
            }
        }
    }
    // Refined through the clip test when it is at hand and the bundle is near (plan/margin.h): the gap to the
    // nearest probe point, within half a probe step of the gap to the streamlines. The cell gap is never larger
    // than the true one and smaller by at most a cell diagonal, so the nearest approach lies at the points
    // whose cell gap is within a diagonal of the smallest, and within that reach of them (half a diagonal more
    // for the trilinear interpolation of the gaps between cell corners).
    if (inside && row.cut == 0 && row.marginMm <= kRefineBundlesWithinMm) {
        const double reach = row.marginMm + 1.5 * row.marginUncertaintyMm;
        std::vector<glm::dvec3> near;
        for (const glm::dvec3& p : probe.points)
            if (removal.gaps.distanceMm(p) <= reach) near.push_back(p);
        const Margin m = refinedMarginToPoints(report.dims, removal.indexToWorld, removal.touch, near, reach,
                                               clip::antiAliasingOffsets(report.samplesPerVoxel - 9), inside);
        row.marginMm = m.mm;
        row.marginUncertaintyMm = m.uncertaintyMm + 0.5 * probe.stepMm;
    }
    row.share = row.streamlines ? double(row.cut) / double(row.streamlines) : 0.0;
    row.cutTracts = subsetStreamlines(tracts, cut);
    for (std::uint8_t& c : cut) c = c ? 0 : 1;
    row.sparedTracts = subsetStreamlines(tracts, cut);
    return row;
}

}  // namespace

Report computeReport(const VolumeData& volume, const TransferFunction& tf, const ReportSettings& settings,
                     const RemovalField& field, const std::vector<LabelSet>& labelSets,
                     const std::vector<BundleInput>& bundles, const PointsInside& inside) {
    const Clock::time_point start = Clock::now();
    checkInputs(volume, field, labelSets);
    Report report = reportOf(volume, settings, field);

    Clock::time_point phase = Clock::now();
    Removal removal = measureTissue(report, volume, tf, settings, field, labelSets);
    report.timings.tissueMs = msSince(phase);

    // One distance transform to the touched cells serves every margin.
    phase = Clock::now();
    if (report.touchedVoxels > 0 && (!labelSets.empty() || !bundles.empty()))
        removal.gaps = cellGapsTo(volume.dims, volume.indexToWorld, removal.touch);
    report.timings.distanceMs = msSince(phase);

    for (const LabelSet& set : labelSets) {
        phase = Clock::now();
        const LabelSums sums = sumLabels(set, field, removal);
        std::vector<StructureRow> rows = structureRows(set, sums, report);
        refineMargins(rows, *set.labels, removal, report, inside);
        report.timings.structuresMs += msSince(phase);

        phase = Clock::now();
        addIntrusionDepths(rows, *set.labels, sums, removal, report.spacingMm);
        report.structures.insert(report.structures.end(), rows.begin(), rows.end());
        report.timings.intrusionMs += msSince(phase);
    }

    phase = Clock::now();
    for (const BundleInput& in : bundles) report.bundles.push_back(bundleRow(in, removal, report, inside));
    report.timings.bundlesMs = msSince(phase);
    report.timings.totalMs = msSince(start);
    return report;
}

}  // namespace curette::plan
