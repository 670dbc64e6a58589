// The report against analytic values: per-label volumes and shares on a two-label volume, the tissue rules,
// intrusion depth and margins of a sphere carve beside a slab label, bundles of straight streamlines
// through and past a sphere, and a head-sized run (181 x 217 x 181, AAL-like labels, three bundles).
#include "base/error.h"
#include "mesh/coverage.h"
#include "plan/removal_report.h"
#include "plan_test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>

namespace curette::plan {
namespace {

using namespace testing;

struct Scene {
    glm::ivec3 dims;
    glm::dmat4 affine;
    VolumeData volume;
    RemovalField field;
};

Scene carve(glm::dvec3 spacing, double halfExtent, const InsideTest& inside) {
    Scene s;
    s.dims = dimsFor(spacing, halfExtent);
    s.affine = gridAffine(spacing, s.dims);
    s.volume = uniformVolume(s.dims, s.affine, 200);
    s.field = removalFieldCpu(s.dims, s.affine, glm::ivec3(0), s.dims, inside, clip::antiAliasingOffsets(32));
    return s;
}

// A label map on the scene's grid from a function of the voxel centre.
template <typename F>
LabelMap labelsFrom(const Scene& s, F idAt) {
    LabelMap m;
    m.dims = s.dims;
    m.indexToWorld = s.affine;
    m.ids.resize(m.voxelCount());
    m.source = "<synthetic labels>";
    for (int k = 0; k < s.dims.z; ++k)
        for (int j = 0; j < s.dims.y; ++j)
            for (int i = 0; i < s.dims.x; ++i)
                m.ids[m.linearIndex(i, j, k)] = static_cast<std::uint16_t>(idAt(glm::dvec3(s.affine * glm::dvec4(i, j, k, 1.0))));
    return m;
}

const StructureRow* row(const Report& r, int id) {
    for (const StructureRow& s : r.structures)
        if (s.id == id) return &s;
    return nullptr;
}

TEST(RemovalReport, PerLabelVolumesAndSharesOnATwoLabelVolume) {
    const glm::dvec3 c(0.37, -0.21, 0.55);
    const double radius = 8.0, ball = 4.0 / 3.0 * kPi * radius * radius * radius;
    Scene s = carve({0.6, 0.9, 1.5}, 16.0, sphere(c, radius));
    // Label 1 where world x < c.x (half the ball), label 2 where x >= c.x, both inside |z| < 12; 0 elsewhere.
    LabelMap labels = labelsFrom(s, [&](glm::dvec3 p) { return std::abs(p.z) >= 12.0 ? 0 : p.x < c.x ? 1 : 2; });
    LabelTable table;
    table.entries = {{1, "Left, \"lobe\"", glm::dvec4(1.0)}, {2, "Right lobe", glm::dvec4(1.0)}, {7, "Far away", glm::dvec4(1.0)}};
    LabelSet set{"synthetic", &labels, &table, {7}};
    Report r = computeReport(s.volume, stepTf(), ReportSettings{}, s.field, {set}, {});
    const double voxelMl = 0.6 * 0.9 * 1.5 / 1000.0;
    EXPECT_NEAR(r.voxelVolumeMl, voxelMl, 1e-15);
    ASSERT_EQ(r.structures.size(), 3u) << "two touched, one protected";
    const StructureRow* left = row(r, 1);
    const StructureRow* right = row(r, 2);
    const StructureRow* far = row(r, 7);
    ASSERT_TRUE(left && right && far);
    EXPECT_EQ(left->name, "Left, \"lobe\"");
    EXPECT_TRUE(left->touched && right->touched);
    EXPECT_FALSE(far->touched);
    EXPECT_TRUE(far->isProtected);
    EXPECT_EQ(far->voxels, 0u);
    EXPECT_TRUE(std::isinf(far->marginMm)) << "a label with no voxels is infinitely far";
    // The labels partition the touched voxels: their removed volumes add up to the total exactly.
    EXPECT_NEAR(left->removedMl + right->removedMl, r.removedMl, 1e-12);
    // Each holds half the ball; the cut plane x = c.x lies between voxel centres, so the split is within one
    // voxel layer of the plane's cross-section (pi r^2 * 0.6 mm).
    EXPECT_NEAR(left->removedMl * 1000.0, ball / 2, kPi * radius * radius * 0.6);
    EXPECT_NEAR(right->removedMl * 1000.0, ball / 2, kPi * radius * radius * 0.6);
    // Label volumes: voxel counts; shares: removed / volume.
    std::uint64_t count1 = std::count(labels.ids.begin(), labels.ids.end(), 1);
    EXPECT_EQ(left->voxels, count1);
    EXPECT_NEAR(left->volumeMl, double(count1) * voxelMl, 1e-12);
    EXPECT_NEAR(left->share, left->removedMl / left->volumeMl, 1e-15);
    EXPECT_EQ(left->marginMm, 0.0);
    EXPECT_TRUE(r.warnings().empty());

    // Tissue by labels: only label 2 counts, so only the right half is removed.
    ReportSettings byLabel;
    byLabel.tissue = TissueRule::Labels;
    byLabel.tissueLabelIds = {2};
    Report r2 = computeReport(s.volume, stepTf(), byLabel, s.field, {set}, {});
    EXPECT_NEAR(r2.removedMl, right->removedMl, 1e-12);
    EXPECT_EQ(row(r2, 1), nullptr);
    // Tissue by opacity: an air volume (value 0, transparent under the TF) loses nothing.
    VolumeData air = uniformVolume(s.dims, s.affine, 0);
    EXPECT_EQ(computeReport(air, stepTf(), ReportSettings{}, s.field, {}, {}).removedMl, 0.0);
    ReportSettings all;
    all.tissue = TissueRule::All;
    EXPECT_EQ(computeReport(air, stepTf(), all, s.field, {}, {}).removedMl, r.removedMl);
    // A label map on another grid is an input error.
    LabelMap wrong = labels;
    wrong.dims.x += 1;
    EXPECT_THROW(computeReport(s.volume, stepTf(), ReportSettings{}, s.field, {{"w", &wrong, &table, {}}}, {}), InputError);
}

// A protected label counts as tissue whatever the tissue rule and the TF: a carve into a protected structure the
// TF hides (air values, transparent under the TF, as a glass TF leaves a gyrus the labels draw) removes it and
// warns, with the same figures as where its voxels are opaque. An unprotected label there removes nothing.
TEST(RemovalReport, AProtectedLabelIsTissueWhateverTheTransferFunction) {
    const glm::dvec3 c(0.31, 0.12, -0.27);
    const double radius = 7.0;
    Scene s = carve({1.0, 1.0, 1.0}, 14.0, sphere(c, radius));
    LabelMap labels = labelsFrom(s, [&](glm::dvec3 p) { return p.x < c.x ? 4 : 5; });
    LabelTable table;
    table.entries = {{4, "protected gyrus", glm::dvec4(1.0)}, {5, "other", glm::dvec4(1.0)}};
    LabelSet set{"atlas", &labels, &table, {4}};
    VolumeData air = uniformVolume(s.dims, s.affine, 0);   // transparent under stepTf()
    Report hidden = computeReport(air, stepTf(), ReportSettings{}, s.field, {set}, {});
    Report opaque = computeReport(s.volume, stepTf(), ReportSettings{}, s.field, {set}, {});
    const StructureRow* gyrus = row(hidden, 4);
    const StructureRow* visible = row(opaque, 4);
    ASSERT_TRUE(gyrus && visible);
    EXPECT_TRUE(gyrus->touched);
    EXPECT_GT(gyrus->removedMl, 0.0);
    EXPECT_EQ(gyrus->removedMl, visible->removedMl);
    EXPECT_EQ(gyrus->marginMm, 0.0);
    ASSERT_EQ(hidden.warnings().size(), 1u);
    EXPECT_NE(hidden.warnings()[0].find("protected structure atlas/protected gyrus"), std::string::npos);
    EXPECT_EQ(row(hidden, 5), nullptr) << "the unprotected label in transparent voxels is not tissue";
    EXPECT_EQ(hidden.removedMl, gyrus->removedMl);
    // The same under the label tissue rule naming only the other label.
    ReportSettings byLabel;
    byLabel.tissue = TissueRule::Labels;
    byLabel.tissueLabelIds = {5};
    Report r = computeReport(air, stepTf(), byLabel, s.field, {set}, {});
    ASSERT_NE(row(r, 4), nullptr);
    EXPECT_EQ(row(r, 4)->removedMl, visible->removedMl);
    EXPECT_EQ(r.warnings().size(), 1u);
}

// A shown label is drawn with its own opacity over a TF that hides the tissue (the renderer classifies
// max(TF, label)), so the report counts it as tissue too; a label not shown stays air. And the exports take
// their tissue from the same rule (reportTissue), protected labels included.
TEST(RemovalReport, AShownLabelIsTissueAsTheRendererDrawsIt) {
    const glm::dvec3 c(0.31, 0.12, -0.27);
    const double radius = 7.0;
    Scene s = carve({1.0, 1.0, 1.0}, 14.0, sphere(c, radius));
    LabelMap labels = labelsFrom(s, [&](glm::dvec3 p) { return p.x < c.x ? 4 : p.y < c.y ? 5 : 6; });
    LabelTable table;
    table.entries = {{4, "protected gyrus", glm::dvec4(1.0)}, {5, "shown", glm::dvec4(1.0)}, {6, "hidden", glm::dvec4(1.0)}};
    LabelSet set{"atlas", &labels, &table, {4}};
    set.shownOpacity.assign(7, 0.0);
    set.shownOpacity[5] = 0.6;   // drawn at 0.6 per unit length; 4 and 6 not shown
    VolumeData air = uniformVolume(s.dims, s.affine, 0);   // transparent under stepTf()
    Report glass = computeReport(air, stepTf(), ReportSettings{}, s.field, {set}, {});
    Report opaque = computeReport(s.volume, stepTf(), ReportSettings{}, s.field, {set}, {});
    const StructureRow* shown = row(glass, 5);
    ASSERT_NE(shown, nullptr) << "the shown label is tissue, so the carve touches it";
    EXPECT_EQ(shown->removedMl, row(opaque, 5)->removedMl);
    EXPECT_EQ(row(glass, 6), nullptr) << "a label not shown, in transparent voxels, is not tissue";
    EXPECT_NEAR(glass.removedMl, row(opaque, 4)->removedMl + row(opaque, 5)->removedMl, 1e-12);
    // Above the label's opacity it is air again.
    ReportSettings strict;
    strict.opacityThreshold = 0.7;
    EXPECT_EQ(row(computeReport(air, stepTf(), strict, s.field, {set}, {}), 5), nullptr);
    // The exports' tissue is the report's: protected and shown labels in, the hidden one out.
    const std::vector<std::uint8_t> tissue = reportTissue(air, stepTf(), ReportSettings{}, {set}, s.field.box());
    std::size_t at = 0, protectedIn = 0, shownIn = 0, hiddenIn = 0;
    for (int k = 0; k < s.field.size.z; ++k)
        for (int j = 0; j < s.field.size.y; ++j)
            for (int i = 0; i < s.field.size.x; ++i, ++at) {
                const int id = labels.id(s.field.origin.x + i, s.field.origin.y + j, s.field.origin.z + k);
                (id == 4 ? protectedIn : id == 5 ? shownIn : hiddenIn) += tissue[at];
            }
    EXPECT_GT(protectedIn, 0u);
    EXPECT_GT(shownIn, 0u);
    EXPECT_EQ(hiddenIn, 0u);
}

// A sphere of radius 8 at c carves; a slab label occupies the voxel centres with z >= zc. With the top of the
// sphere at t = c.z + 8 and s the z spacing (R's top centre lies in (t - s, t]):
//   zc < t (intrusion): depth = (top centre of R in the slab) - (zc - s), within s/2 of t - zc + s/2,
//                       the depth past the slab's face halfway between centres;
//   zc > t (margin):    the gap from the sphere to the slab's cells, zc - s/2 - t (checked below).
void checkSlab(glm::dvec3 spacing, double zFirst, bool intrudes) {
    const glm::dvec3 c(0.23, -0.41, 0.17);
    const double radius = 8.0, top = c.z + radius;
    Scene s = carve(spacing, 18.0, sphere(c, radius));
    // The first slab centre at or above zFirst.
    const double z0 = s.affine[3].z, sz = spacing.z;
    const double zc = z0 + std::ceil((zFirst - z0) / sz - 1e-9) * sz;
    LabelMap labels = labelsFrom(s, [&](glm::dvec3 p) { return p.z >= zc - 1e-9 ? 3 : 0; });
    LabelTable table;
    table.entries = {{3, "slab", glm::dvec4(1.0)}};
    Report r = computeReport(s.volume, stepTf(), ReportSettings{}, s.field, {{"t", &labels, &table, {3}}}, {});
    const StructureRow* slab = row(r, 3);
    ASSERT_NE(slab, nullptr);
    const double eps = 1e-9;
    if (intrudes) {
        ASSERT_TRUE(slab->touched);
        EXPECT_EQ(slab->marginMm, 0.0);
        EXPECT_NEAR(slab->intrusionDepthMm, top - zc + sz / 2, sz / 2 + eps) << "spacing z " << sz;
        ASSERT_EQ(r.warnings().size(), 1u);
        EXPECT_NE(r.warnings()[0].find("protected structure t/slab"), std::string::npos);
    } else {
        EXPECT_FALSE(slab->touched);
        EXPECT_EQ(slab->intrusionDepthMm, 0.0);
        // The slab's cells begin half a voxel below its first centre; the margin is the gap to them, never
        // larger, and smaller by at most the cell diagonal (the sphere's top cells are covered in part).
        const double gap = zc - sz / 2 - top;
        EXPECT_LE(slab->marginMm, gap + eps) << "spacing z " << sz;
        EXPECT_GE(slab->marginMm, gap - glm::length(spacing) - eps) << "spacing z " << sz;
        EXPECT_TRUE(r.warnings().empty());
    }
}

TEST(RemovalReport, IntrusionDepthAndMarginOfASphereBesideASlab) {
    for (glm::dvec3 spacing : {glm::dvec3(1.0), glm::dvec3(0.6, 0.9, 1.5)}) {
        checkSlab(spacing, 4.6, true);    // 3.6 mm into the slab
        checkSlab(spacing, 1.0, true);    // deep: the sub-box grows until the depth is exact
        checkSlab(spacing, 11.3, false);  // 3.1 mm away
        checkSlab(spacing, 14.0, false);
    }
}

TEST(RemovalReport, IntrusionDepthOfACarveDeepInsideALabelIsExactBeyondTheFirstPad) {
    // A cube label of centres [-15, 15]^3 mm holds the whole sphere (r 8): the nearest centre not of the
    // label is 7 mm or more beyond the sphere's box, farther than the first pad, so the sub-box must grow.
    // The deepest removed voxel is the one at the origin: 16 mm from the centres at +-16 outside the cube.
    const glm::dvec3 c(0.23, -0.41, 0.17);
    Scene s = carve(glm::dvec3(1.0), 18.0, sphere(c, 8.0));
    LabelMap labels = labelsFrom(s, [&](glm::dvec3 p) {
        return std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}) <= 15.0 + 1e-9 ? 4 : 0;
    });
    Report r = computeReport(s.volume, stepTf(), ReportSettings{}, s.field, {{"cube", &labels, nullptr, {}}}, {});
    const StructureRow* cube = row(r, 4);
    ASSERT_NE(cube, nullptr);
    EXPECT_EQ(cube->name, "label 4") << "no table: the id names it";
    EXPECT_NEAR(cube->intrusionDepthMm, 16.0, 1e-9);
    // The label filling the whole grid: only the grid's outside is "not of it"; the origin is 19 mm from it.
    LabelMap everywhere = labelsFrom(s, [](glm::dvec3) { return 5; });
    Report all = computeReport(s.volume, stepTf(), ReportSettings{}, s.field, {{"all", &everywhere, nullptr, {}}}, {});
    ASSERT_NE(row(all, 5), nullptr);
    EXPECT_NEAR(row(all, 5)->intrusionDepthMm, 19.0, 1e-9);
}

// Straight streamlines along x at distance rho from the sphere's centre: cut exactly when rho < r, removed
// length the chord 2 sqrt(r^2 - rho^2) within 2 probe steps, margins rho - r within one voxel diagonal.
TEST(RemovalReport, BundlesThroughAndPastASphere) {
    const glm::dvec3 c(0.23, -0.41, 0.17);
    const double radius = 6.0;
    InsideTest inside = sphere(c, radius);
    Scene s = carve(glm::dvec3(1.0), 16.0, inside);
    Tractogram tracts;
    tracts.source = "<lines>";
    tracts.scalarNames = {"fa"};
    tracts.propertyNames = {"index"};
    const std::vector<double> rhos{0.0, 2.5, 4.9, 5.5, 6.5, 7.7, 9.0, 11.0};
    for (std::size_t l = 0; l < rhos.size(); ++l) {
        const double angle = 0.7 * double(l);
        const glm::dvec3 offset(0.0, rhos[l] * std::cos(angle), rhos[l] * std::sin(angle));
        for (int p = 0; p <= 28; ++p) {
            tracts.points.emplace_back(glm::dvec3(c.x - 14.0 + p, c.y, c.z) + offset);
            tracts.scalars.push_back(float(l));
        }
        tracts.offsets.push_back(static_cast<std::uint32_t>(tracts.points.size()));
        tracts.properties.push_back(float(l));
    }
    BundleInput bundle{"lines", &tracts, true, {}};
    bundle.probe.stepMm = 0.25;
    bundle.probe.points = tractProbePoints(tracts, bundle.probe.stepMm, bundle.probe.streamlineOffsets);
    bundle.probe.insideFlags = insideFlagsCpu(bundle.probe.points, inside);
    BundleInput passing{"passing", &tracts, false, bundle.probe};
    Report r = computeReport(s.volume, stepTf(), ReportSettings{}, s.field, {}, {bundle, passing});
    ASSERT_EQ(r.bundles.size(), 2u);
    const BundleRow& b = r.bundles[0];
    EXPECT_EQ(b.streamlines, rhos.size());
    EXPECT_EQ(b.cut, 4u);
    EXPECT_NEAR(b.share, 0.5, 1e-15);
    EXPECT_NEAR(b.totalLengthMm, 28.0 * double(rhos.size()), 1e-6);
    double chords = 0;
    for (double rho : rhos)
        if (rho < radius) chords += 2.0 * std::sqrt(radius * radius - rho * rho);
    EXPECT_NEAR(b.removedLengthMm, chords, 2 * 0.25 * 4) << "within 2 steps per cut streamline";
    EXPECT_EQ(b.marginMm, 0.0);
    // Per streamline: the removed length of each alone.
    for (std::size_t l = 0; l < rhos.size(); ++l) {
        Tractogram one;
        one.points.assign(tracts.points.begin() + std::ptrdiff_t(29 * l), tracts.points.begin() + std::ptrdiff_t(29 * (l + 1)));
        one.offsets = {0, 29};
        BundleInput single{"one", &one, false, {}};
        single.probe.points = tractProbePoints(one, 0.25, single.probe.streamlineOffsets);
        single.probe.insideFlags = insideFlagsCpu(single.probe.points, inside);
        const BundleRow& o = computeReport(s.volume, stepTf(), ReportSettings{}, s.field, {}, {single}).bundles[0];
        const double chord = rhos[l] < radius ? 2.0 * std::sqrt(radius * radius - rhos[l] * rhos[l]) : 0.0;
        EXPECT_NEAR(o.removedLengthMm, chord, 2 * 0.25) << "rho " << rhos[l];
        EXPECT_EQ(o.cut, rhos[l] < radius ? 1u : 0u) << "rho " << rhos[l];
        if (rhos[l] > radius) {
            EXPECT_NEAR(o.marginMm, rhos[l] - radius, std::sqrt(3.0)) << "rho " << rhos[l];
            EXPECT_LE(o.marginMm, rhos[l] - radius + 1e-9) << "rho " << rhos[l] << ": the cells' margin is never larger";
            // Refined through the clip test: within a quarter millimetre and the stated uncertainty.
            PointsInside probe = [&](const std::vector<glm::dvec3>& points) { return insideFlagsCpu(points, inside); };
            const BundleRow& refined = computeReport(s.volume, stepTf(), ReportSettings{}, s.field, {}, {single}, probe).bundles[0];
            EXPECT_NEAR(refined.marginMm, rhos[l] - radius, 0.25) << "rho " << rhos[l];
            EXPECT_NEAR(refined.marginMm, rhos[l] - radius, refined.marginUncertaintyMm) << "rho " << rhos[l];
        }
    }
    // Cut and spared partition the input, with their scalars and properties.
    EXPECT_EQ(b.cutTracts.streamlineCount() + b.sparedTracts.streamlineCount(), tracts.streamlineCount());
    EXPECT_EQ(b.cutTracts.points.size() + b.sparedTracts.points.size(), tracts.points.size());
    EXPECT_EQ(b.cutTracts.properties, (std::vector<float>{0, 1, 2, 3}));
    EXPECT_EQ(b.sparedTracts.properties, (std::vector<float>{4, 5, 6, 7}));
    EXPECT_EQ(b.sparedTracts.scalars.size(), b.sparedTracts.points.size());
    EXPECT_EQ(b.sparedTracts.points.front(), tracts.points[4 * 29]);
    // The protected bundle is cut: a warning; the other is not protected.
    ASSERT_EQ(r.warnings().size(), 1u);
    EXPECT_NE(r.warnings()[0].find("protected bundle lines"), std::string::npos);
    // A probe that does not belong to the tractogram is an input error.
    BundleInput broken = bundle;
    broken.probe.insideFlags.pop_back();
    EXPECT_THROW(computeReport(s.volume, stepTf(), ReportSettings{}, s.field, {}, {broken}), InputError);
}

TEST(RemovalReport, RemovedLengthIsUnbiasedOverManyChords) {
    // The trapezoid rule errs by (1/2 - u) step where the surface crosses a sub-segment at fraction u: within
    // step / 2 per crossing, zero on average. Over 300 random chords (600 crossings) the mean error per
    // crossing is within 0.03 mm of zero (its standard deviation is 0.25 / sqrt(12 * 600) = 0.003 mm); counting
    // a sub-segment whole when either end is inside would be +step / 2 = +0.125 mm.
    const glm::dvec3 c(0.23, -0.41, 0.17);
    const double radius = 6.0;
    InsideTest inside = sphere(c, radius);
    Scene s = carve(glm::dvec3(1.0), 10.0, inside);
    std::mt19937 random(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    Tractogram tracts;
    double chords = 0;
    while (tracts.streamlineCount() < 300) {
        glm::dvec3 d = glm::normalize(glm::dvec3(u(random), u(random), u(random)));
        glm::dvec3 o(u(random) * 5.0, u(random) * 5.0, u(random) * 5.0);
        o -= d * glm::dot(o, d);  // o: the closest point to the centre's line
        if (glm::length(o) > radius - 0.5) continue;
        for (int p = 0; p <= 9; ++p) tracts.points.emplace_back(c + o + d * (-9.0 + 2.0 * p));
        tracts.offsets.push_back(static_cast<std::uint32_t>(tracts.points.size()));
        chords += 2.0 * std::sqrt(radius * radius - glm::dot(o, o));
    }
    BundleInput bundle{"chords", &tracts, false, {}};
    bundle.probe.points = tractProbePoints(tracts, 0.25, bundle.probe.streamlineOffsets);
    bundle.probe.insideFlags = insideFlagsCpu(bundle.probe.points, inside);
    const BundleRow& b = computeReport(s.volume, stepTf(), ReportSettings{}, s.field, {}, {bundle}).bundles[0];
    EXPECT_EQ(b.cut, 300u);
    EXPECT_NEAR((b.removedLengthMm - chords) / 600.0, 0.0, 0.03);
}

TEST(TractProbe, NoGapExceedsTheStepAndOriginalPointsAreKept) {
    Tractogram t;
    t.points = {{0, 0, 0}, {1.0, 0, 0}, {1.0, 0.1, 0}, {1.0, 0.1, 0}, {4.0, 4.1, 0}};
    t.offsets = {0, 3, 5};
    std::vector<std::uint32_t> offsets;
    std::vector<glm::dvec3> points = tractProbePoints(t, 0.3, offsets);
    ASSERT_EQ(offsets.size(), 3u);
    EXPECT_EQ(offsets.back(), points.size());
    for (std::size_t s = 0; s + 1 < offsets.size(); ++s)
        for (std::uint32_t p = offsets[s] + 1; p < offsets[s + 1]; ++p) EXPECT_LE(glm::length(points[p] - points[p - 1]), 0.3 + 1e-12);
    EXPECT_EQ(points[offsets[1] - 1], glm::dvec3(t.points[2]));
    EXPECT_EQ(points[offsets[1]], glm::dvec3(t.points[3]));
    EXPECT_EQ(offsets[1], 4u + 1u + 1u) << "1 mm: 3 between; 0.1 mm: none";
    EXPECT_THROW(tractProbePoints(t, 0.0, offsets), InputError);
}

// Runs tractProbePoints and expects an InputError naming `field`.
void expectProbeInputError(const Tractogram& t, double stepMm, const std::string& field) {
    std::vector<std::uint32_t> offsets;
    try {
        tractProbePoints(t, stepMm, offsets);
        ADD_FAILURE() << "expected an InputError naming " << field;
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), field) << e.what();
        EXPECT_EQ(e.file(), t.source);
    }
}

Tractogram oneSegment(glm::vec3 a, glm::vec3 b) {
    Tractogram t;
    t.points = {a, b};
    t.offsets = {0, 2};
    t.source = "bundle.tck";
    return t;
}

TEST(TractProbe, ATinyStepIsAnInputErrorNamingTheStep) {
    const Tractogram t = oneSegment({0, 0, 0}, {1, 0, 0});
    expectProbeInputError(t, 1e-9, "report.tract_step_mm");   // 1e9 points on one millimetre
    expectProbeInputError(t, 1e-12, "report.tract_step_mm");  // more points than an int counts
    expectProbeInputError(t, 1e-300, "report.tract_step_mm");
}

TEST(TractProbe, TheTotalOverAllStreamlinesIsCapped) {
    // 60 streamlines of 5e6 probe points each: each alone is within the cap of 2^28, all together are not.
    Tractogram t;
    t.source = "bundle.tck";
    for (int s = 0; s < 60; ++s) {
        t.points.emplace_back(0.0f, float(s), 0.0f);
        t.points.emplace_back(5e4f, float(s), 0.0f);
        t.offsets.push_back(static_cast<std::uint32_t>(t.points.size()));
    }
    expectProbeInputError(t, 0.01, "report.tract_step_mm");
}

TEST(TractProbe, AFarPointIsAnInputErrorNamingThePoint) {
    Tractogram t;
    t.source = "bundle.tck";
    t.points = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}, {1e30f, 0, 0}, {4, 0, 0}};
    t.offsets = {0, 3, 6};
    expectProbeInputError(t, 0.25, "points[4]");  // streamline 1, its second point
    t.points[4] = {4, -1e30f, 0};
    expectProbeInputError(t, 0.25, "points[4]");
    t.points = {{1e30f, 1e30f, 1e30f}};  // a lone point has no segment, but is no tract point either
    t.offsets = {0, 1};
    expectProbeInputError(t, 0.25, "points[0]");
}

TEST(TractProbe, ANonFinitePointIsAnInputErrorNamingThePoint) {
    for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
        Tractogram t = oneSegment({0, 0, 0}, {1, 0, 0});
        t.points.insert(t.points.begin() + 1, glm::vec3(0.5f, bad, 0));
        t.offsets = {0, 3};
        expectProbeInputError(t, 0.25, "points[1]");
    }
}

}  // namespace
}  // namespace curette::plan
