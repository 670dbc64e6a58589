// A head-sized report: 181 x 217 x 181 at 1 mm (the MNI grid), an ellipsoid head in air, 116 AAL-like labels
// in the brain, two carves (a sphere and a rotated box) and three bundles of 3000 curved streamlines. Checks
// the figures agree with each other and with direct counts; the timings land in the test's XML properties
// (speed is measured by benches, not asserted here).
#include "mesh/coverage.h"
#include "plan/cavity_surface.h"
#include "plan/removal_report.h"
#include "plan/report_output.h"
#include "plan_test_support.h"

#include <gtest/gtest.h>

#include <random>

namespace curette::plan {
namespace {

using namespace testing;

TEST(HeadReport, AHeadSizedReportIsConsistent) {
    const glm::ivec3 dims(181, 217, 181);
    glm::dmat4 affine(1.0);
    affine[3] = glm::dvec4(-90.0, -126.0, -72.0, 1.0);
    VolumeData volume = uniformVolume(dims, affine, 0);
    LabelMap labels;
    labels.dims = dims;
    labels.indexToWorld = affine;
    labels.ids.assign(volume.voxelCount(), 0);
    labels.source = "<aal-like>";
    const glm::dvec3 headCentre(0.0, -18.0, 18.0);
    for (int k = 0; k < dims.z; ++k)
        for (int j = 0; j < dims.y; ++j)
            for (int i = 0; i < dims.x; ++i) {
                glm::dvec3 p = glm::dvec3(affine * glm::dvec4(i, j, k, 1.0)) - headCentre;
                glm::dvec3 q = p / glm::dvec3(80.0, 100.0, 80.0);
                if (glm::dot(q, q) >= 1.0) continue;
                volume.voxels[volume.linearIndex(i, j, k)] = 200;
                if (glm::dot(q, q) < 0.85 * 0.85)  // the brain: 116 blocks of labels
                    labels.ids[labels.linearIndex(i, j, k)] = static_cast<std::uint16_t>(1 + (i / 18 + 7 * (j / 20) + 13 * (k / 18)) % 116);
            }
    LabelTable table;
    for (int id = 1; id <= 116; ++id) table.entries.push_back({id, "region " + std::to_string(id), glm::dvec4(1.0)});

    const InsideTest ball = sphere({20.3, 10.1, 50.7}, 14.0);
    const InsideTest slot = rotatedBox({-30.2, -40.4, 40.3}, {6.0, 12.0, 20.0}, {1.0, 1.0, 0.0}, 30.0);
    const InsideTest either = [&](glm::dvec3 p) { return ball(p) || slot(p); };
    // The field box: around both carves (what the GPU pass would cover), from their world bounds.
    const glm::ivec3 lo = glm::ivec3(glm::floor(glm::dvec3(glm::inverse(affine) * glm::dvec4(-60.0, -80.0, 10.0, 1.0))));
    const glm::ivec3 hi = glm::ivec3(glm::ceil(glm::dvec3(glm::inverse(affine) * glm::dvec4(40.0, 30.0, 70.0, 1.0))));
    RemovalField field = removalFieldCpu(dims, affine, lo, hi - lo, either, clip::antiAliasingOffsets(32));

    std::mt19937 random(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<Tractogram> tracts(3);
    std::vector<BundleInput> bundles;
    const std::vector<glm::dvec3> through{{20.0, 10.0, 50.0}, {-30.0, -40.0, 40.0}, {0.0, -20.0, 0.0}};
    for (std::size_t b = 0; b < 3; ++b) {
        tracts[b].source = "<bundle " + std::to_string(b) + ">";
        for (int s = 0; s < 3000; ++s) {
            glm::dvec3 start = through[b] + glm::dvec3(-50.0, 10.0 * u(random), 10.0 * u(random));
            const double bend = 8.0 * u(random), phase = u(random);
            for (int p = 0; p <= 100; ++p)
                tracts[b].points.emplace_back(start + glm::dvec3(p, bend * std::sin(0.05 * p + phase), 0.3 * bend * std::cos(0.04 * p)));
            tracts[b].offsets.push_back(static_cast<std::uint32_t>(tracts[b].points.size()));
        }
        BundleInput in{"bundle " + std::to_string(b), &tracts[b], b == 2, {}};
        in.probe.points = tractProbePoints(tracts[b], kDefaultProbeStepMm, in.probe.streamlineOffsets);
        in.probe.insideFlags = insideFlagsCpu(in.probe.points, either);
        bundles.push_back(std::move(in));
    }
    LabelSet set{"aal", &labels, &table, {1, 50, 116}};
    const TransferFunction tf = stepTf();
    Report report = computeReport(volume, tf, ReportSettings{}, field, {set}, bundles);

    RecordProperty("report_total_ms", std::to_string(report.timings.totalMs));
    RecordProperty("report_distance_ms", std::to_string(report.timings.distanceMs));
    RecordProperty("report_structures_ms", std::to_string(report.timings.structuresMs));
    RecordProperty("report_intrusion_ms", std::to_string(report.timings.intrusionMs));
    RecordProperty("report_bundles_ms", std::to_string(report.timings.bundlesMs));
    RecordProperty("report_tissue_ms", std::to_string(report.timings.tissueMs));

    // The carves lie inside the head: the removed volume is the two shapes' (they do not overlap).
    const double shapes = 4.0 / 3.0 * kPi * 14.0 * 14.0 * 14.0 + 8.0 * 6.0 * 12.0 * 20.0;
    EXPECT_NEAR(report.removedMl * 1000.0, shapes, 0.01 * shapes);
    // Per label: the touched labels' removals add up to what was removed inside the brain.
    double labelled = 0, direct = 0;
    for (const StructureRow& s : report.structures) labelled += s.removedMl;
    for (int k = field.origin.z; k < field.origin.z + field.size.z; ++k)
        for (int j = field.origin.y; j < field.origin.y + field.size.y; ++j)
            for (int i = field.origin.x; i < field.origin.x + field.size.x; ++i)
                if (labels.id(i, j, k) != 0 && volume.voxels[volume.linearIndex(i, j, k)] != 0)
                    direct += field.removedFraction({i, j, k}) / 1000.0;
    EXPECT_NEAR(labelled, direct, 1e-9);
    EXPECT_GT(report.structures.size(), 3u);
    for (const StructureRow& s : report.structures) {
        EXPECT_EQ(s.touched, s.marginMm == 0.0) << s.name;
        EXPECT_GE(s.intrusionDepthMm, 0.0) << s.name;  // 0 when only fractions below 0.5 touch it
    }
    EXPECT_GT(report.structures.front().intrusionDepthMm, 3.0) << "the most removed label is carved deeply";
    // Bundles: cut counts against the flags directly; the third (protected) bundle passes below the carves.
    for (std::size_t b = 0; b < 3; ++b) {
        std::uint64_t cut = 0;
        const TractProbe& probe = bundles[b].probe;
        for (std::size_t s = 0; s + 1 < probe.streamlineOffsets.size(); ++s)
            cut += std::any_of(probe.insideFlags.begin() + probe.streamlineOffsets[s],
                               probe.insideFlags.begin() + probe.streamlineOffsets[s + 1], [](std::uint8_t f) { return f != 0; })
                       ? 1 : 0;
        EXPECT_EQ(report.bundles[b].cut, cut);
        EXPECT_EQ(report.bundles[b].cutTracts.streamlineCount() + report.bundles[b].sparedTracts.streamlineCount(), 3000u);
    }
    EXPECT_GT(report.bundles[0].cut, 100u);
    EXPECT_EQ(report.bundles[2].cut, 0u);
    EXPECT_GT(report.bundles[2].marginMm, 5.0);

    // The cavity surface of the same field is closed.
    clip::TriangleMesh cavity = cavitySurface(field, tissueInBox(volume, tf, ReportSettings{}, &labels, field.box()));
    EXPECT_NO_THROW(clip::validateClosed(cavity));
    EXPECT_NEAR(cavity.signedVolume(), shapes, 0.04 * shapes);
    EXPECT_FALSE(reportSummary(report).empty());
}

}  // namespace
}  // namespace curette::plan
