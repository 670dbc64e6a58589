// NIfTI-1 reading: every supported type, both endians, gzip, the affine rules, the real MNI head, and
// malformed files (each error names its field).
#include "io/nifti.h"
#include "io/volume_file.h"
#include "base/error.h"
#include "tests/io/io_test_support.h"

#include <gtest/gtest.h>

#include <cmath>

namespace curette {
namespace {

using test::put;
using test::set;

struct NiftiSpec {
    glm::ivec3 dims{3, 4, 5};
    int datatype = 2, bitpix = 8;
    bool bigEndian = false;
    float slope = 0, intercept = 0;
    short qformCode = 0, sformCode = 0;
    float pixdim[4] = {1, 1, 1, 1};
    float quatern[3] = {0, 0, 0}, qoffset[3] = {0, 0, 0};
    float srow[12] = {0};
    float voxOffset = 352;
    const char* magic = "n+1";
    short rank = 3;
    short dim4 = 1;
};

// A NIfTI-1 file whose voxel (i,j,k) holds a function of i + 4 j + 20 k (< 100, so it fits every type).
std::vector<std::uint8_t> makeNifti(const NiftiSpec& s) {
    std::vector<std::uint8_t> b(352, 0);
    bool be = s.bigEndian;
    set<std::int32_t>(b, 0, 348, be);
    set<std::int16_t>(b, 40, s.rank, be);
    set<std::int16_t>(b, 42, static_cast<std::int16_t>(s.dims.x), be);
    set<std::int16_t>(b, 44, static_cast<std::int16_t>(s.dims.y), be);
    set<std::int16_t>(b, 46, static_cast<std::int16_t>(s.dims.z), be);
    set<std::int16_t>(b, 48, s.dim4, be);
    set<std::int16_t>(b, 70, static_cast<std::int16_t>(s.datatype), be);
    set<std::int16_t>(b, 72, static_cast<std::int16_t>(s.bitpix), be);
    for (int i = 0; i < 4; ++i) set<float>(b, static_cast<std::size_t>(76 + 4 * i), s.pixdim[i], be);
    set<float>(b, 108, s.voxOffset, be);
    set<float>(b, 112, s.slope, be);
    set<float>(b, 116, s.intercept, be);
    b[123] = 2;  // millimetres
    set<std::int16_t>(b, 252, s.qformCode, be);
    set<std::int16_t>(b, 254, s.sformCode, be);
    for (int i = 0; i < 3; ++i) set<float>(b, static_cast<std::size_t>(256 + 4 * i), s.quatern[i], be);
    for (int i = 0; i < 3; ++i) set<float>(b, static_cast<std::size_t>(268 + 4 * i), s.qoffset[i], be);
    for (int i = 0; i < 12; ++i) set<float>(b, static_cast<std::size_t>(280 + 4 * i), s.srow[i], be);
    std::memcpy(b.data() + 344, s.magic, 4);
    b.resize(static_cast<std::size_t>(std::max(s.voxOffset, 352.0f)), 0);
    for (int k = 0; k < s.dims.z; ++k)
        for (int j = 0; j < s.dims.y; ++j)
            for (int i = 0; i < s.dims.x; ++i) {
                double v = i + 4 * j + 20 * k;
                switch (s.datatype) {
                    case 2: b.push_back(static_cast<std::uint8_t>(v)); break;
                    case 4: put<std::int16_t>(b, static_cast<std::int16_t>(v - 300), be); break;
                    case 512: put<std::uint16_t>(b, static_cast<std::uint16_t>(v * 100), be); break;
                    case 8: put<std::int32_t>(b, static_cast<std::int32_t>(v * -1000), be); break;
                    case 16: put<float>(b, static_cast<float>(v * 0.5), be); break;
                    case 64: put<double>(b, v * 0.25, be); break;
                }
            }
    return b;
}

double expectedValue(int datatype, int i, int j, int k) {
    double v = i + 4 * j + 20 * k;
    switch (datatype) {
        case 4: return v - 300;
        case 512: return v * 100;
        case 8: return v * -1000;
        case 16: return v * 0.5;
        case 64: return v * 0.25;
    }
    return v;
}

TEST(Nifti, EveryTypeBothEndiansAndGzip) {
    const std::pair<int, int> types[] = {{2, 8}, {4, 16}, {512, 16}, {8, 32}, {16, 32}, {64, 64}};
    for (auto [datatype, bitpix] : types)
        for (bool bigEndian : {false, true})
            for (bool gz : {false, true}) {
                NiftiSpec s;
                s.datatype = datatype, s.bitpix = bitpix, s.bigEndian = bigEndian;
                std::vector<std::uint8_t> bytes = makeNifti(s);
                auto path = test::scratchDirectory() / (std::to_string(datatype) + (bigEndian ? "be" : "le") + (gz ? ".nii.gz" : ".nii"));
                test::writeBytes(path, gz ? test::gzipBytes(bytes) : bytes);
                VolumeData v = io::readVolume(path);
                ASSERT_EQ(v.dims, s.dims);
                for (int k = 0; k < 5; ++k)
                    for (int j = 0; j < 4; ++j)
                        for (int i = 0; i < 3; ++i)
                            ASSERT_NEAR(v.value(i, j, k), expectedValue(datatype, i, j, k), 1e-6 * (1 + std::abs(expectedValue(datatype, i, j, k))))
                                << "datatype " << datatype << (bigEndian ? " BE" : " LE") << (gz ? " gz" : "");
            }
}

TEST(Nifti, ScaleSlopeAndInterceptAreAppliedAndNaNSlopeMeansNone) {
    NiftiSpec s;
    s.slope = 2.0f, s.intercept = -5.0f;
    VolumeData v = io::readNiftiBytes(makeNifti(s), "scaled.nii");
    EXPECT_NEAR(v.value(2, 1, 1), 2.0 * 26 - 5.0, 1e-9);
    s.slope = std::nanf("");
    v = io::readNiftiBytes(makeNifti(s), "nan-slope.nii");
    EXPECT_NEAR(v.value(2, 1, 1), 26, 1e-9);
    s.slope = 0.0f;
    v = io::readNiftiBytes(makeNifti(s), "zero-slope.nii");
    EXPECT_NEAR(v.value(2, 1, 1), 26, 1e-9);
}

TEST(Nifti, AffinePrecedenceSformThenQformThenPixdim) {
    NiftiSpec s;
    s.pixdim[1] = 0.5f, s.pixdim[2] = 2.0f, s.pixdim[3] = 3.0f;
    VolumeData pixdimOnly = io::readNiftiBytes(makeNifti(s), "pixdim.nii");
    EXPECT_EQ(pixdimOnly.indexToWorld, glm::dmat4(glm::dvec4(0.5, 0, 0, 0), glm::dvec4(0, 2, 0, 0), glm::dvec4(0, 0, 3, 0), glm::dvec4(0, 0, 0, 1)));

    // qform: 90 degrees about z (b = c = 0, d = sin 45), qfac -1, offset (1, 2, 3).
    s.qformCode = 1;
    s.pixdim[0] = -1.0f;
    s.quatern[2] = static_cast<float>(std::sqrt(0.5));
    s.qoffset[0] = 1, s.qoffset[1] = 2, s.qoffset[2] = 3;
    VolumeData q = io::readNiftiBytes(makeNifti(s), "qform.nii");
    glm::dvec3 p = glm::dvec3(q.indexToWorld * glm::dvec4(1, 1, 1, 1));
    // R = rotation by 90 degrees about z: (x, y) -> (-y, x); columns scaled by (0.5, 2, -3).
    EXPECT_NEAR(p.x, 1 - 2.0, 1e-6);
    EXPECT_NEAR(p.y, 2 + 0.5, 1e-6);
    EXPECT_NEAR(p.z, 3 - 3.0, 1e-6);
    glm::dmat4 expected = io::niftiQformAffine(0, 0, static_cast<float>(std::sqrt(0.5)), -1, {0.5, 2, 3}, {1, 2, 3});
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) EXPECT_NEAR(expected[c][r], q.indexToWorld[c][r], 1e-12);

    // sform wins over qform: an oblique, anisotropic affine.
    s.sformCode = 2;
    float srow[12] = {0.9f, 0.1f, 0.0f, -10.0f, -0.1f, 1.1f, 0.2f, 20.0f, 0.0f, -0.3f, 1.3f, 5.0f};
    std::memcpy(s.srow, srow, sizeof srow);
    VolumeData sf = io::readNiftiBytes(makeNifti(s), "sform.nii");
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 4; ++col) EXPECT_NEAR(sf.indexToWorld[col][row], srow[4 * row + col], 1e-6);
}

// nifti1_io reads qfac as (pixdim[0] < 0) ? -1 : 1: any negative pixdim[0] mirrors the third axis, zero and
// other positive values do not. Writers that store, say, -0.5 or -2 there mean the mirrored frame.
TEST(Nifti, AnyNegativePixdim0IsQfacMinusOne) {
    auto affineFor = [](float pixdim0) {
        NiftiSpec s;
        s.qformCode = 1;
        s.pixdim[0] = pixdim0, s.pixdim[1] = 0.5f, s.pixdim[2] = 2.0f, s.pixdim[3] = 3.0f;
        s.quatern[0] = 0.1f, s.quatern[1] = 0.2f, s.quatern[2] = 0.3f;
        s.qoffset[0] = 1, s.qoffset[1] = -2, s.qoffset[2] = 3;
        auto path = test::scratchDirectory() / ("pixdim0 " + std::to_string(pixdim0) + ".nii");
        test::writeBytes(path, makeNifti(s));
        return io::readVolume(path).indexToWorld;
    };
    auto thirdColumn = [](const glm::dmat4& m) {
        return "(" + std::to_string(m[2][0]) + ", " + std::to_string(m[2][1]) + ", " + std::to_string(m[2][2]) + ")";
    };
    const glm::dmat4 mirrored = affineFor(-1.0f), unmirrored = affineFor(1.0f);
    ASSERT_NE(mirrored, unmirrored);
    EXPECT_LT(glm::determinant(glm::dmat3(mirrored)), 0.0);
    for (float pixdim0 : {-0.5f, -2.0f, -1e-6f}) {
        const glm::dmat4 m = affineFor(pixdim0);
        EXPECT_TRUE(m == mirrored) << "pixdim[0] = " << pixdim0 << ": third column " << thirdColumn(m) << ", qfac -1 gives "
                                   << thirdColumn(mirrored);
    }
    for (float pixdim0 : {0.0f, 0.5f, 2.0f}) {
        const glm::dmat4 m = affineFor(pixdim0);
        EXPECT_TRUE(m == unmirrored) << "pixdim[0] = " << pixdim0 << ": third column " << thirdColumn(m) << ", qfac +1 gives "
                                     << thirdColumn(unmirrored);
    }
}

TEST(Nifti, VoxOffsetBelow352IsTakenAs352) {
    NiftiSpec s;
    std::vector<std::uint8_t> bytes = makeNifti(s);
    set<float>(bytes, 108, 0.0f, false);
    VolumeData v = io::readNiftiBytes(bytes, "zero-offset.nii");
    EXPECT_NEAR(v.value(2, 3, 4), 94, 1e-9);
}

TEST(Nifti, TheMniColin27Head) {
    VolumeData v = io::readVolume("/usr/share/mricron/templates/ch2.nii.gz");
    EXPECT_EQ(v.dims, glm::ivec3(181, 217, 181));
    EXPECT_EQ(v.sourceType, ScalarType::UInt8);
    EXPECT_EQ(v.format, StorageFormat::UNorm8);
    EXPECT_EQ(glm::dvec3(v.indexToWorld[3]), glm::dvec3(-90, -125, -71));
    EXPECT_EQ(glm::dvec3(v.indexToWorld[0][0], v.indexToWorld[1][1], v.indexToWorld[2][2]), glm::dvec3(1.0));
    EXPECT_EQ(v.minValue, 0.0);
    EXPECT_EQ(v.maxValue, 254.0);
}

void expectError(const std::vector<std::uint8_t>& bytes, const std::string& field) {
    test::expectInputError([&] { io::readNiftiBytes(bytes, "bad.nii"); }, "bad.nii", field);
}

TEST(Nifti, MalformedFilesNameTheirField) {
    NiftiSpec s;
    std::vector<std::uint8_t> good = makeNifti(s);
    expectError(std::vector<std::uint8_t>(good.begin(), good.begin() + 200), "header");
    auto wrongSize = good;
    set<std::int32_t>(wrongSize, 0, 123, false);  // neither 348 (NIfTI-1) nor 540 (NIfTI-2)
    expectError(wrongSize, "sizeof_hdr");
    auto nifti2Sized = good;  // says NIfTI-2, holds fewer than its 540 header bytes
    set<std::int32_t>(nifti2Sized, 0, 540, false);
    expectError(nifti2Sized, "header");
    auto wrongMagic = good;
    std::memcpy(wrongMagic.data() + 344, "abc", 4);
    expectError(wrongMagic, "magic");
    auto complexType = good;  // datatype 32: complex64, not a scalar type curette reads
    set<std::int16_t>(complexType, 70, 32, false);
    expectError(complexType, "datatype");
    auto wrongBitpix = good;
    set<std::int16_t>(wrongBitpix, 72, 16, false);
    expectError(wrongBitpix, "bitpix");
    auto zeroDim = good;
    set<std::int16_t>(zeroDim, 44, 0, false);
    expectError(zeroDim, "dim[2]");
    auto negativeDim = good;
    set<std::int16_t>(negativeDim, 46, -4, false);
    expectError(negativeDim, "dim[3]");
    auto badRank = good;
    set<std::int16_t>(badRank, 40, 9, false);
    expectError(badRank, "dim[0]");
    auto sixD = good;  // 4-D and 5-D files are read volume by volume (tests/io/test_nifti2.cpp); 6-D is not
    set<std::int16_t>(sixD, 40, 6, false);
    set<std::int16_t>(sixD, 50, 1, false);
    set<std::int16_t>(sixD, 52, 2, false);
    expectError(sixD, "dim[6]");
    expectError(std::vector<std::uint8_t>(good.begin(), good.end() - 5), "data");
    NiftiSpec floats = s;
    floats.datatype = 16, floats.bitpix = 32;
    // NaN and Inf are "no data" now, not errors (tests/io/test_nifti2.cpp, tests/render/test_no_data.cpp).
    auto nan = makeNifti(floats);
    set<float>(nan, 352 + 4 * 7, std::nanf(""), false);
    set<float>(nan, 352 + 4 * 9, INFINITY, false);
    EXPECT_EQ(io::readNiftiBytes(nan, "holes.nii").noDataVoxels, 2u);
}

TEST(Nifti, UnreadablePathsAreInputErrors) {
    EXPECT_THROW(io::readVolume("/nonexistent/head.nii.gz"), InputError);
    // A folder without a volume (its own: the shared scratch folder may hold another test's DICOM file).
    const auto empty = test::scratchDirectory() / "nifti-empty-folder";
    std::filesystem::remove_all(empty);
    std::filesystem::create_directories(empty);
    EXPECT_THROW(io::readVolume(empty), InputError);
    auto path = test::scratchDirectory() / "garbage.nii.gz";
    test::writeBytes(path, {0x1f, 0x8b, 8, 0, 1, 2, 3, 4, 5, 6, 7});
    EXPECT_THROW(io::readVolume(path), InputError);
    auto truncated = test::scratchDirectory() / "truncated.nii.gz";
    auto gz = test::gzipBytes(makeNifti(NiftiSpec{}));
    gz.resize(gz.size() / 2);
    test::writeBytes(truncated, gz);
    EXPECT_THROW(io::readVolume(truncated), InputError);
}

}  // namespace
}  // namespace curette
