// Slice placement (io/dicom_geometry.h) on made-up slice records: the order along the normal, the spacing and
// the index-to-world affine of regular stacks, and each refusal with the image and field it names.
#include "io/dicom_geometry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

namespace curette {
namespace {

using io::DicomSlicePlacement;
using io::DicomSliceRecord;

constexpr std::array<double, 6> kAxial{1, 0, 0, 0, 1, 0};

// Slice i is "s<i>.dcm", 64 x 48, at `positions[i]` (LPS mm), PixelSpacing 0.5 (rows) \ 0.8 (columns).
std::vector<DicomSliceRecord> stack(const std::vector<glm::dvec3>& positions, const std::array<double, 6>& orientation = kAxial) {
    std::vector<DicomSliceRecord> records;
    for (std::size_t i = 0; i < positions.size(); ++i) {
        DicomSliceRecord r;
        r.name = "s";
        r.name += std::to_string(i) + ".dcm";  // not `"s" + ...`: g++ 12 warns falsely on it (GCC bug 105329)
        r.columns = 64, r.rows = 48;
        r.position = positions[i];
        r.orientation = orientation;
        r.pixelSpacing = glm::dvec2(0.5, 0.8);
        records.push_back(r);
    }
    return records;
}

std::vector<glm::dvec3> alongZ(const std::vector<double>& z) {
    std::vector<glm::dvec3> positions;
    for (double v : z) positions.emplace_back(-100.0, 50.0, v);
    return positions;
}

std::vector<std::size_t> identity(std::size_t n) {
    std::vector<std::size_t> order(n);
    std::iota(order.begin(), order.end(), std::size_t{0});
    return order;
}

// LPS patient position -> curette's RAS world.
glm::dvec3 ras(const glm::dvec3& lps) { return {-lps.x, -lps.y, lps.z}; }

void expectNear(const glm::dvec4& got, const glm::dvec4& expected) {
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(got[c], expected[c], 1e-9) << "component " << c;
}

TEST(DicomGeometry, ARegularStackIsSortedByPositionAndGivesTheAffine) {
    auto records = stack(alongZ({15.0, 10.0, 17.5, 12.5}));
    DicomSlicePlacement p = io::placeDicomSlices(records);
    ASSERT_TRUE(p.placed()) << p.problem;
    EXPECT_EQ(p.order, (std::vector<std::size_t>{1, 3, 0, 2}));
    EXPECT_EQ(p.dims, glm::ivec3(64, 48, 4));
    EXPECT_EQ(p.spacing, glm::dvec3(0.8, 0.5, 2.5));  // columns step by PixelSpacing[1], rows by PixelSpacing[0]
    expectNear(p.indexToWorld[0], {-0.8, 0, 0, 0});
    expectNear(p.indexToWorld[1], {0, -0.5, 0, 0});
    expectNear(p.indexToWorld[2], {0, 0, 2.5, 0});
    expectNear(p.indexToWorld[3], {100, -50, 10, 1});
}

TEST(DicomGeometry, SlicesAreOrderedAlongTheNormalNotAlongZ) {
    // X = (1,0,0), Y = (0,-1,0): the normal X x Y points to -z, so the highest slice comes first.
    auto records = stack(alongZ({0.0, 2.0, 4.0}), {1, 0, 0, 0, -1, 0});
    DicomSlicePlacement p = io::placeDicomSlices(records);
    ASSERT_TRUE(p.placed()) << p.problem;
    EXPECT_EQ(p.order, (std::vector<std::size_t>{2, 1, 0}));
    EXPECT_DOUBLE_EQ(p.spacing.z, 2.0);
    expectNear(p.indexToWorld[2], {0, 0, -2, 0});
    expectNear(p.indexToWorld[3], {100, -50, 4, 1});
}

TEST(DicomGeometry, AnObliqueAffineMapsEveryPixelToItsPatientPosition) {
    const double c = std::cos(0.3), s = std::sin(0.3);
    const std::array<double, 6> o{c, s, 0, 0, 0, -1};  // X in the axial plane, Y down: a tilted coronal plane
    const glm::dvec3 x(o[0], o[1], o[2]), y(o[3], o[4], o[5]), normal = glm::cross(x, y);
    const glm::dvec3 ipp(12, -30, 40);
    std::vector<glm::dvec3> positions;
    for (int k : {2, 0, 1}) positions.push_back(ipp + 1.25 * k * normal);
    auto records = stack(positions, o);
    DicomSlicePlacement p = io::placeDicomSlices(records);
    ASSERT_TRUE(p.placed()) << p.problem;
    EXPECT_EQ(p.order, (std::vector<std::size_t>{1, 2, 0}));
    EXPECT_NEAR(p.spacing.z, 1.25, 1e-12);
    // P(i,j) = IPP + i PS[1] X + j PS[0] Y (PS3.3 C.7.6.2.1.1), slice k further along the normal.
    for (int k = 0; k < 3; ++k)
        for (auto [i, j] : {std::pair{0, 0}, std::pair{63, 0}, std::pair{0, 47}, std::pair{17, 29}}) {
            glm::dvec3 patient = ipp + i * 0.8 * x + j * 0.5 * y + 1.25 * k * normal;
            expectNear(p.indexToWorld * glm::dvec4(i, j, k, 1), glm::dvec4(ras(patient), 1));
        }
}

TEST(DicomGeometry, OneSliceTakesItsStepFromSpacingBetweenSlicesThenSliceThicknessThenOneMillimetre) {
    auto records = stack(alongZ({3.0}));
    EXPECT_DOUBLE_EQ(io::placeDicomSlices(records).spacing.z, 1.0);
    records[0].sliceThickness = 2.5;
    EXPECT_DOUBLE_EQ(io::placeDicomSlices(records).spacing.z, 2.5);
    records[0].spacingBetweenSlices = 3.0;
    DicomSlicePlacement p = io::placeDicomSlices(records);
    ASSERT_TRUE(p.placed());
    EXPECT_DOUBLE_EQ(p.spacing.z, 3.0);
    EXPECT_EQ(p.dims, glm::ivec3(64, 48, 1));
    expectNear(p.indexToWorld[2], {0, 0, 3, 0});
}

TEST(DicomGeometry, StepsWithinTheToleranceAreUniform) {
    auto records = stack(alongZ({0.0, 2.0, 4.004, 6.0}));
    DicomSlicePlacement p = io::placeDicomSlices(records);
    ASSERT_TRUE(p.placed()) << p.problem;
    EXPECT_DOUBLE_EQ(p.spacing.z, 2.0);  // the mean step, first to last
}

TEST(DicomGeometry, AGantryTiltIsRefusedWithItsAngle) {
    std::vector<glm::dvec3> positions;
    for (int k = 0; k < 4; ++k) positions.emplace_back(0.0, 0.5 * k, 2.0 * k);
    auto records = stack(positions);
    records[0].gantryDetectorTilt = "14";
    DicomSlicePlacement p = io::placeDicomSlices(records);
    EXPECT_EQ(p.problemExpected, "slices stacked along their normal (ImageOrientationPatient row x column)");
    EXPECT_EQ(p.problem, "a gantry tilt of 14.0362 degrees: each step moves 0.5 mm sideways (GantryDetectorTilt (0018,1120) 14); "
                         "a tilted stack needs resampling onto a regular grid, which curette does not do");
    EXPECT_EQ(p.order, identity(4));  // refused after sorting: along the normal
    EXPECT_EQ(p.indexToWorld, glm::dmat4(1.0));
}

TEST(DicomGeometry, PositionsOffsetSidewaysIrregularlyAreRefused) {
    auto records = stack({{0, 0, 0}, {0, 1, 2}, {0, 0, 4}});
    DicomSlicePlacement p = io::placeDicomSlices(records);
    EXPECT_EQ(p.problemExpected, "slice positions on one line along the slice normal");
    EXPECT_EQ(p.problem, "positions offset sideways irregularly, by up to 1 mm");
}

TEST(DicomGeometry, NonUniformStepsAreRefused) {
    auto records = stack(alongZ({5.0, 0.0, 2.0}));
    DicomSlicePlacement p = io::placeDicomSlices(records);
    EXPECT_EQ(p.problemExpected, "uniformly spaced slices (steps within 0.01 mm)");
    EXPECT_EQ(p.problem, "slice steps from 2 to 3 mm; a regular volume needs resampling onto a uniform grid, which curette does not do");
    EXPECT_EQ(p.order, (std::vector<std::size_t>{1, 2, 0}));
    EXPECT_EQ(p.dims, glm::ivec3(64, 48, 3));
}

TEST(DicomGeometry, AMissingSliceIsNamedByItsNeighbours) {
    auto records = stack(alongZ({0.0, 2.0, 4.0, 8.0, 10.0}));
    DicomSlicePlacement p = io::placeDicomSlices(records);
    EXPECT_EQ(p.problemExpected, "every slice of a regularly spaced series");
    EXPECT_EQ(p.problem, "1 slice missing: the slices are 2 mm apart, but 4 mm lie between slice 3 and 4 of 5 (at 4 and 8 mm along "
                         "the normal, s2.dcm and s3.dcm); a regular volume needs the missing images, or resampling, which curette "
                         "does not do");
}

TEST(DicomGeometry, SeveralGapsAreCountedAndTheFirstIsNamed) {
    auto records = stack(alongZ({0.0, 2.0, 8.0, 10.0, 14.0}));
    DicomSlicePlacement p = io::placeDicomSlices(records);
    EXPECT_EQ(p.problem, "3 slices missing: the slices are 2 mm apart, but 6 mm lie between slice 2 and 3 of 5 (at 2 and 8 mm along "
                         "the normal, s1.dcm and s2.dcm) and at 1 more places; a regular volume needs the missing images, or "
                         "resampling, which curette does not do");
}

TEST(DicomGeometry, DuplicatedPositionsAreRefused) {
    auto records = stack(alongZ({0.0, 2.0, 2.005, 4.0}));
    DicomSlicePlacement p = io::placeDicomSlices(records);
    EXPECT_EQ(p.problemExpected, "one image per slice position");
    EXPECT_EQ(p.problem, "4 images at 3 positions (several echoes, phases or acquisitions in one series?)");
}

TEST(DicomGeometry, TwoOrientationsAreRefusedNamingAnImageOfEach) {
    auto records = stack(alongZ({0.0, 2.0, 4.0}));
    records[2].orientation = std::array<double, 6>{1, 0, 0, 0, 0, -1};
    DicomSlicePlacement p = io::placeDicomSlices(records);
    EXPECT_EQ(p.problemExpected, "one ImageOrientationPatient (0020,0037) for every slice");
    EXPECT_EQ(p.problem, "2 different orientations among 3 images (1\\0\\0\\0\\1\\0 in s0.dcm, 1\\0\\0\\0\\0\\-1 in s2.dcm): a localizer "
                         "or several stacks in one series");
    EXPECT_EQ(p.order, identity(3));  // refused before sorting
}

TEST(DicomGeometry, OrientationsWithinTheirWrittenPrecisionAreOne) {
    auto records = stack(alongZ({0.0, 2.0, 4.0}));
    records[1].orientation = std::array<double, 6>{1, 0.00005, 0, 0, 1, 0};
    EXPECT_TRUE(io::placeDicomSlices(records).placed());
}

TEST(DicomGeometry, AnOrientationThatIsNotTwoOrthogonalUnitVectorsIsRefused) {
    auto records = stack(alongZ({0.0, 2.0}), {1, 0, 0, 0.5, 0.5, 0});
    DicomSlicePlacement p = io::placeDicomSlices(records);
    EXPECT_EQ(p.problemExpected, "ImageOrientationPatient (0020,0037): two orthogonal unit vectors");
    EXPECT_EQ(p.problem, "ImageOrientationPatient 1\\0\\0\\0.5\\0.5\\0 in s0.dcm");
}

TEST(DicomGeometry, TwoPixelSpacingsAreRefused) {
    auto records = stack(alongZ({0.0, 2.0}));
    records[1].pixelSpacing = glm::dvec2(0.5, 0.7);
    DicomSlicePlacement p = io::placeDicomSlices(records);
    EXPECT_EQ(p.problemExpected, "one PixelSpacing (0028,0030) for every slice");
    EXPECT_EQ(p.problem, "PixelSpacing 0.5\\0.8 in s0.dcm and 0.5\\0.7 in s1.dcm");
}

TEST(DicomGeometry, EachImageNeedsItsSizePositionOrientationAndSpacing) {
    auto records = stack(alongZ({0.0, 2.0, 4.0}));
    records[1].columns = 32;
    DicomSlicePlacement p = io::placeDicomSlices(records);
    EXPECT_EQ(p.problemExpected, "images of one size (Columns x Rows)");
    EXPECT_EQ(p.problem, "images of 64 x 48 (s0.dcm) and 32 x 48 (s1.dcm)");
    EXPECT_EQ(p.dims, glm::ivec3(64, 48, 3));

    records = stack(alongZ({0.0, 2.0, 4.0}));
    records[2].position.reset();
    p = io::placeDicomSlices(records);
    EXPECT_EQ(p.problem, "no ImagePositionPatient or ImageOrientationPatient in s2.dcm (a projection or secondary-capture image?)");
    EXPECT_EQ(p.order, identity(3));

    records = stack(alongZ({0.0, 2.0, 4.0}));
    records[1].pixelSpacing.reset();
    p = io::placeDicomSlices(records);
    EXPECT_EQ(p.problemExpected, "PixelSpacing (0028,0030) in every image (two positive numbers)");
    EXPECT_EQ(p.problem, "no PixelSpacing in s1.dcm");
}

TEST(DicomGeometry, WhatTheScanFoundWrongComesFirstImageByImage) {
    auto records = stack(alongZ({0.0, 2.0, 4.0}));
    records[1].pixelProblem = "SamplesPerPixel 3";
    records[2].truncation = "PixelData ends early";
    records[2].position.reset();
    DicomSlicePlacement p = io::placeDicomSlices(records);
    EXPECT_EQ(p.problem, "SamplesPerPixel 3 in s1.dcm");  // image 1 is checked before image 2

    records[1].pixelProblem.clear();
    p = io::placeDicomSlices(records);
    EXPECT_EQ(p.problemExpected, "image files that hold all their pixel data");
    EXPECT_EQ(p.problem, "s2.dcm is truncated: PixelData ends early");

    records[2].truncation.clear();
    records[2].geometryProblem = "NumberOfFrames 4 in s2.dcm without per-frame positions";
    p = io::placeDicomSlices(records);
    EXPECT_EQ(p.problemExpected, "the position of every frame of a multi-frame image");
    EXPECT_EQ(p.problem, "NumberOfFrames 4 in s2.dcm without per-frame positions");
}

TEST(DicomGeometry, NoRecordsAreRefused) {
    DicomSlicePlacement p = io::placeDicomSlices({});
    EXPECT_FALSE(p.placed());
    EXPECT_TRUE(p.order.empty());
}

}  // namespace
}  // namespace curette
