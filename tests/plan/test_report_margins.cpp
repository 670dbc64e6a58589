// The report's margins boundary to boundary and contact only when something is removed: a protected wall of
// voxels i >= 32 beside an axis-aligned box that ends at x = c (1 mm voxels, centres on integers), so the
// true gap is 31.5 - c.
#include "mesh/coverage.h"
#include "plan/removal_report.h"
#include "plan/tract_probe.h"
#include "plan_test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace curette::plan {
namespace {

using namespace testing;

constexpr glm::ivec3 kDims{48, 24, 24};

struct WallScene {
    VolumeData volume;
    LabelMap labels;
    LabelTable table;
    RemovalField field;
};

// Voxel centres on integer world coordinates; label 1 ("Wall", protected) where i >= 32.
WallScene wallScene(const InsideTest& carve) {
    WallScene s;
    s.volume = uniformVolume(kDims, glm::dmat4(1.0), 200);
    s.labels.dims = kDims;
    s.labels.indexToWorld = glm::dmat4(1.0);
    s.labels.source = "<wall labels>";
    s.labels.ids.resize(s.labels.voxelCount());
    for (int k = 0; k < kDims.z; ++k)
        for (int j = 0; j < kDims.y; ++j)
            for (int i = 0; i < kDims.x; ++i) s.labels.ids[s.labels.linearIndex(i, j, k)] = i >= 32 ? 1 : 0;
    s.table.entries = {{1, "Wall", glm::dvec4(1.0)}};
    s.field = removalFieldCpu(kDims, glm::dmat4(1.0), glm::ivec3(0), kDims, carve, clip::antiAliasingOffsets(32));
    return s;
}

// With `refineWith`, the margins are refined through that clip test (as the GPU's is passed in `report`).
Report wallReport(const WallScene& s, const InsideTest& refineWith = {}) {
    LabelSet set{"walls", &s.labels, &s.table, {1}};
    PointsInside inside;
    if (refineWith)
        inside = [refineWith](const std::vector<glm::dvec3>& points) { return insideFlagsCpu(points, refineWith); };
    return computeReport(s.volume, stepTf(), ReportSettings{}, s.field, {set}, {}, inside);
}

// The box 9.5 <= x < c, 5.5 <= y, z < 17.5 (its other faces on cell faces).
InsideTest boxEndingAt(double c) {
    return [c](glm::dvec3 p) { return p.x >= 9.5 && p.x < c && p.y >= 5.5 && p.y < 17.5 && p.z >= 5.5 && p.z < 17.5; };
}

TEST(ReportMargins, ABoxThatStopsAtTheWallTouchesNothingOfIt) {
    WallScene s = wallScene(boxEndingAt(31.5));
    Report r = wallReport(s);
    ASSERT_EQ(r.structures.size(), 1u);
    const StructureRow& wall = r.structures.front();
    EXPECT_FALSE(wall.touched) << "the box ends on the wall's face: nothing of it is removed";
    EXPECT_EQ(wall.removedMl, 0.0);
    EXPECT_EQ(wall.marginMm, 0.0) << "abutting: no gap";
    EXPECT_TRUE(r.warnings().empty()) << r.warnings().front();
    // The carve itself: 22 x 12 x 12 mm, every face on cell faces.
    EXPECT_NEAR(r.removedMl, 22.0 * 12 * 12 / 1000.0, 1e-9);
}

TEST(ReportMargins, GapsToAWallAreBoundaryToBoundary) {
    for (double gap : {1.0, 2.0, 4.0}) {
        WallScene s = wallScene(boxEndingAt(31.5 - gap));
        Report r = wallReport(s);
        ASSERT_EQ(r.structures.size(), 1u);
        const StructureRow& wall = r.structures.front();
        EXPECT_FALSE(wall.touched);
        EXPECT_TRUE(r.warnings().empty());
        EXPECT_NEAR(wall.marginMm, gap, 0.25) << "box ending at x = " << 31.5 - gap;
        EXPECT_LE(wall.marginMm, gap + 1e-9) << "never larger than the gap";
    }
}

// Faces between cell faces: the cell gap alone is up to a cell smaller; refined, within 0.25 mm and never
// more than that above the gap. Axis-aligned, turned boxes and a sphere, on the wall.
TEST(ReportMargins, GapsFromFacesInsideACellAreRefinedToAQuarterMillimetre) {
    struct Case {
        const char* name;
        InsideTest carve;
        double gap;
    };
    const double r = 7.0;
    std::vector<Case> cases = {
        {"box to x = 30.9", boxEndingAt(30.9), 0.6},
        {"box to x = 29.3", boxEndingAt(29.3), 2.2},
        {"box to x = 27.75", boxEndingAt(27.75), 3.75},
        // Turned 30 degrees about z: its nearest edge is at centre.x + half.x cos + half.y sin.
        {"turned box", rotatedBox({18.0, 12.0, 12.0}, {5.0, 3.0, 4.0}, {0, 0, 1}, 30.0),
         31.5 - (18.0 + 5.0 * std::cos(kPi / 6) + 3.0 * std::sin(kPi / 6))},
        {"sphere", sphere({31.5 - r - 1.37, 11.8, 12.3}, r), 1.37},
    };
    for (const Case& c : cases) {
        WallScene s = wallScene(c.carve);
        const StructureRow& wall = wallReport(s, c.carve).structures.front();
        ASSERT_FALSE(wall.touched) << c.name;
        EXPECT_NEAR(wall.marginMm, c.gap, 0.25) << c.name;
        EXPECT_NEAR(wall.marginMm, c.gap, wall.marginUncertaintyMm) << c.name << ": within its stated uncertainty";
        EXPECT_GT(wall.marginUncertaintyMm, 0.0) << c.name;
        EXPECT_LE(wall.marginUncertaintyMm, 0.25) << c.name;
        std::printf("[ margin ] %-16s gap %.4f mm, reported %.4f +- %.3f mm\n", c.name, c.gap, wall.marginMm, wall.marginUncertaintyMm);
    }
}

}  // namespace
}  // namespace curette::plan
