// NIfTI-2 reading (nifti2.h layout: 540-byte header, 64-bit dims, double pixdim/quatern/srow), and what both
// versions share: 4-D and 5-D files read one 3-D volume by index, and NaN/Inf voxels are "no data".
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

struct Nifti2Spec {
    glm::ivec3 dims{3, 4, 5};
    std::int64_t dim4 = 1, dim5 = 1;
    std::int64_t rank = 3;
    int datatype = 4, bitpix = 16;
    bool bigEndian = false;
    double slope = 0, intercept = 0;
    int qformCode = 0, sformCode = 0;
    double pixdim[4] = {1, 1, 1, 1};
    double quatern[3] = {0, 0, 0}, qoffset[3] = {0, 0, 0};
    double srow[12] = {0};
    std::int64_t voxOffset = 544;
    bool pair = false;
    int intentCode = 0;
};

// Voxel (i, j, k) of volume t (dim[4] fastest, then dim[5]) holds i + 4 j + 20 k + 100 t, through the type's map.
double rawValue(int i, int j, int k, int t) { return i + 4 * j + 20 * k + 100 * t; }

double expectedValue(int datatype, double v) {
    switch (datatype) {
        case 4: return v - 300;
        case 512: return v * 100;
        case 8: return v * -1000;
        case 16: return v * 0.5;
        case 64: return v * 0.25;
    }
    return v;
}

void putVoxel(std::vector<std::uint8_t>& b, int datatype, double v, bool be) {
    switch (datatype) {
        case 2: b.push_back(static_cast<std::uint8_t>(v)); break;
        case 4: put<std::int16_t>(b, static_cast<std::int16_t>(v - 300), be); break;
        case 512: put<std::uint16_t>(b, static_cast<std::uint16_t>(v * 100), be); break;
        case 8: put<std::int32_t>(b, static_cast<std::int32_t>(v * -1000), be); break;
        case 16: put<float>(b, static_cast<float>(v * 0.5), be); break;
        case 64: put<double>(b, v * 0.25, be); break;
    }
}

// The 540-byte header at the offsets of nifti2.h, the 4-byte extension flag, then the voxels (unless a pair).
std::vector<std::uint8_t> header2(const Nifti2Spec& s) {
    std::vector<std::uint8_t> b(544, 0);
    bool be = s.bigEndian;
    set<std::int32_t>(b, 0, 540, be);
    std::memcpy(b.data() + 4, s.pair ? "ni2\0\r\n\032\n" : "n+2\0\r\n\032\n", 8);
    set<std::int16_t>(b, 12, static_cast<std::int16_t>(s.datatype), be);
    set<std::int16_t>(b, 14, static_cast<std::int16_t>(s.bitpix), be);
    const std::int64_t dim[8] = {s.rank, s.dims.x, s.dims.y, s.dims.z, s.dim4, s.dim5, 1, 1};
    for (int i = 0; i < 8; ++i) set<std::int64_t>(b, static_cast<std::size_t>(16 + 8 * i), dim[i], be);
    for (int i = 0; i < 4; ++i) set<double>(b, static_cast<std::size_t>(104 + 8 * i), s.pixdim[i], be);
    set<std::int64_t>(b, 168, s.voxOffset, be);
    set<double>(b, 176, s.slope, be);
    set<double>(b, 184, s.intercept, be);
    set<std::int32_t>(b, 344, s.qformCode, be);
    set<std::int32_t>(b, 348, s.sformCode, be);
    for (int i = 0; i < 3; ++i) set<double>(b, static_cast<std::size_t>(352 + 8 * i), s.quatern[i], be);
    for (int i = 0; i < 3; ++i) set<double>(b, static_cast<std::size_t>(376 + 8 * i), s.qoffset[i], be);
    for (int i = 0; i < 12; ++i) set<double>(b, static_cast<std::size_t>(400 + 8 * i), s.srow[i], be);
    set<std::int32_t>(b, 500, 2, be);  // xyzt_units: millimetres
    set<std::int32_t>(b, 504, s.intentCode, be);
    return b;
}

std::vector<std::uint8_t> voxels(const Nifti2Spec& s) {
    std::vector<std::uint8_t> b;
    for (std::int64_t t = 0; t < s.dim4 * s.dim5; ++t)
        for (int k = 0; k < s.dims.z; ++k)
            for (int j = 0; j < s.dims.y; ++j)
                for (int i = 0; i < s.dims.x; ++i) putVoxel(b, s.datatype, rawValue(i, j, k, static_cast<int>(t)), s.bigEndian);
    return b;
}

std::vector<std::uint8_t> makeNifti2(const Nifti2Spec& s) {
    std::vector<std::uint8_t> b = header2(s);
    b.resize(static_cast<std::size_t>(s.voxOffset), 0);
    std::vector<std::uint8_t> v = voxels(s);
    b.insert(b.end(), v.begin(), v.end());
    return b;
}

void expectVolume(const VolumeData& v, const Nifti2Spec& s, int t, const std::string& what) {
    ASSERT_EQ(v.dims, s.dims) << what;
    for (int k = 0; k < s.dims.z; ++k)
        for (int j = 0; j < s.dims.y; ++j)
            for (int i = 0; i < s.dims.x; ++i) {
                double e = expectedValue(s.datatype, rawValue(i, j, k, t));
                ASSERT_NEAR(v.value(i, j, k), e, 1e-9 * (1 + std::abs(e))) << what << " at " << i << "," << j << "," << k;
            }
}

TEST(Nifti2, EveryTypeBothEndiansAndGzip) {
    const std::pair<int, int> types[] = {{2, 8}, {4, 16}, {512, 16}, {8, 32}, {16, 32}, {64, 64}};
    for (auto [datatype, bitpix] : types)
        for (bool bigEndian : {false, true})
            for (bool gz : {false, true}) {
                Nifti2Spec s;
                s.datatype = datatype, s.bitpix = bitpix, s.bigEndian = bigEndian;
                std::string what = std::to_string(datatype) + (bigEndian ? "be" : "le") + (gz ? ".nii.gz" : ".nii");
                auto path = test::scratchDirectory() / ("n2-" + what);
                std::vector<std::uint8_t> bytes = makeNifti2(s);
                test::writeBytes(path, gz ? test::gzipBytes(bytes) : bytes);
                VolumeData v = io::readVolume(path);
                expectVolume(v, s, 0, what);
                EXPECT_EQ(v.volumeCount, 1);
            }
}

TEST(Nifti2, IsRecognisedByItsMagicWithoutAnExtension) {
    auto path = test::scratchDirectory() / "nifti2-without-extension";
    test::writeBytes(path, makeNifti2(Nifti2Spec{}));
    expectVolume(io::readVolume(path), Nifti2Spec{}, 0, "no extension");
}

TEST(Nifti2, AffinePrecedenceInDoublePrecision) {
    Nifti2Spec s;
    s.pixdim[1] = 0.5, s.pixdim[2] = 2.0, s.pixdim[3] = 3.0;
    VolumeData pixdimOnly = io::readNiftiBytes(makeNifti2(s), "pixdim.nii");
    EXPECT_EQ(pixdimOnly.indexToWorld, glm::dmat4(glm::dvec4(0.5, 0, 0, 0), glm::dvec4(0, 2, 0, 0), glm::dvec4(0, 0, 3, 0), glm::dvec4(0, 0, 0, 1)));

    // The qform in doubles: the same nifti1.h METHOD 2, no float rounding of the quaternion.
    s.qformCode = 1;
    s.pixdim[0] = -1.0;
    s.quatern[0] = 0.1, s.quatern[1] = 0.2, s.quatern[2] = std::sqrt(0.5);
    s.qoffset[0] = 1.25, s.qoffset[1] = -2.5, s.qoffset[2] = 3.125;
    VolumeData q = io::readNiftiBytes(makeNifti2(s), "qform.nii");
    glm::dmat4 expected = io::niftiQformAffine(0.1, 0.2, std::sqrt(0.5), -1, {0.5, 2, 3}, {1.25, -2.5, 3.125});
    EXPECT_EQ(q.indexToWorld, expected);
    s.pixdim[0] = -0.5;  // any negative pixdim[0] is qfac -1, as in NIfTI-1 (nifti1_io)
    glm::dmat4 half = io::readNiftiBytes(makeNifti2(s), "qfac-half.nii").indexToWorld;
    EXPECT_TRUE(half == expected) << "pixdim[0] -0.5: third column z " << half[2][2] << ", qfac -1 gives " << expected[2][2];
    s.pixdim[0] = -1.0;

    // The sform wins, kept to the last bit of its doubles.
    s.sformCode = 1;
    const double srow[12] = {0.9, 0.1, 0.0, -10.000001, -0.1, 1.1, 0.2, 20.0, 0.0, -0.3, 1.3, 5.0};
    std::copy(srow, srow + 12, s.srow);
    VolumeData sf = io::readNiftiBytes(makeNifti2(s), "sform.nii");
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 4; ++col) EXPECT_EQ(sf.indexToWorld[col][row], srow[4 * row + col]);
}

TEST(Nifti2, HeaderImagePairWithNi2Magic) {
    Nifti2Spec s;
    s.pair = true, s.voxOffset = 0, s.bigEndian = true;
    auto dir = test::scratchDirectory();
    test::writeBytes(dir / "pair2.hdr", header2(s));
    test::writeBytes(dir / "pair2.img", voxels(s));
    expectVolume(io::readVolume(dir / "pair2.hdr"), s, 0, "pair");
    // The image gzipped beside the header.
    test::writeBytes(dir / "pair2gz.hdr", header2(s));
    test::writeBytes(dir / "pair2gz.img.gz", test::gzipBytes(voxels(s)));
    VolumeData gzipped = io::readVolume(dir / "pair2gz.hdr");
    expectVolume(gzipped, s, 0, "pair, gzipped image");
    EXPECT_EQ(gzipped.files, (std::vector<std::filesystem::path>{dir / "pair2gz.hdr", dir / "pair2gz.img.gz"})) << "both files of the pair";
    // Without the image: one error naming it.
    test::writeBytes(dir / "lonely2.hdr", header2(s));
    try {
        io::readVolume(dir / "lonely2.hdr");
        FAIL() << "a header without its image must be refused";
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), "image file") << e.what();
        EXPECT_NE(std::string(e.what()).find("lonely2.img"), std::string::npos) << e.what();
    }
}

TEST(Nifti2, FourAndFiveDimensionalFilesReadOneVolumeByIndex) {
    for (bool version2 : {false, true})
        for (bool gz : {false, true}) {
            Nifti2Spec s;
            s.rank = 5, s.dim4 = 2, s.dim5 = 3;  // six volumes, dim[4] varying fastest
            std::vector<std::uint8_t> bytes = makeNifti2(s);
            if (!version2) {
                // The same voxels behind a NIfTI-1 header.
                std::vector<std::uint8_t> b(352, 0);
                set<std::int32_t>(b, 0, 348, false);
                const std::int16_t dim[8] = {5, 3, 4, 5, 2, 3, 1, 1};
                for (int i = 0; i < 8; ++i) set<std::int16_t>(b, static_cast<std::size_t>(40 + 2 * i), dim[i], false);
                set<std::int16_t>(b, 70, 4, false);
                set<std::int16_t>(b, 72, 16, false);
                for (int i = 0; i < 4; ++i) set<float>(b, static_cast<std::size_t>(76 + 4 * i), 1.0f, false);
                set<float>(b, 108, 352.0f, false);
                std::memcpy(b.data() + 344, "n+1", 4);
                std::vector<std::uint8_t> v = voxels(s);
                b.insert(b.end(), v.begin(), v.end());
                bytes = b;
            }
            std::string what = std::string(version2 ? "nifti2" : "nifti1") + (gz ? ".nii.gz" : ".nii");
            auto path = test::scratchDirectory() / ("5d-" + what);
            test::writeBytes(path, gz ? test::gzipBytes(bytes) : bytes);
            for (int t = 0; t < 6; ++t) {
                io::VolumeReadOptions options;
                options.volumeIndex = t;
                VolumeData v = io::readVolume(path, options);
                EXPECT_EQ(v.volumeCount, 6) << what;
                EXPECT_EQ(v.volumeIndex, t) << what;
                expectVolume(v, s, t, what + " volume " + std::to_string(t));
            }
            for (int bad : {6, -1}) {
                io::VolumeReadOptions options;
                options.volumeIndex = bad;
                try {
                    io::readVolume(path, options);
                    FAIL() << what << ": index " << bad << " must be refused";
                } catch (const InputError& e) {
                    EXPECT_EQ(e.field(), "--volume / volume.index") << e.what();
                    EXPECT_NE(std::string(e.what()).find("0..5"), std::string::npos) << e.what();
                    EXPECT_NE(std::string(e.what()).find("6 volumes"), std::string::npos) << e.what();
                }
            }
        }
}

TEST(Nifti2, AGzipped4DFileIsInflatedOnlyUpToTheVolumeAskedFor) {
    // 64 volumes of 64^3 int16 (32 MiB inflated, a few KiB compressed); the last volume is cut off. The first
    // still reads: the reader stops inflating after it.
    Nifti2Spec s;
    s.dims = glm::ivec3(64), s.rank = 4, s.dim4 = 64;
    std::vector<std::uint8_t> bytes = header2(s);
    bytes.resize(static_cast<std::size_t>(s.voxOffset) + 63 * 64 * 64 * 64 * 2 + 1000, 0);
    auto path = test::scratchDirectory() / "cut-4d.nii.gz";
    test::writeBytes(path, test::gzipBytes(bytes));
    VolumeData first = io::readVolume(path);
    EXPECT_EQ(first.volumeCount, 64);
    EXPECT_EQ(first.value(5, 6, 7), 0.0);
    io::VolumeReadOptions last;
    last.volumeIndex = 63;
    try {
        io::readVolume(path, last);
        FAIL() << "the cut-off last volume must be refused";
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), "data") << e.what();
        EXPECT_NE(std::string(e.what()).find("volume 63 of 64"), std::string::npos) << e.what();
    }
}

TEST(Nifti2, NaNAndInfVoxelsAreNoDataInBothVersions) {
    Nifti2Spec s;
    s.datatype = 16, s.bitpix = 32;
    std::vector<std::uint8_t> bytes = makeNifti2(s);
    set<float>(bytes, 544 + 4 * 7, std::nanf(""), false);
    set<float>(bytes, 544 + 4 * 9, INFINITY, false);
    set<float>(bytes, 544 + 4 * 59, -INFINITY, false);  // the last voxel: (2, 3, 4), the largest value
    VolumeData v = io::readNiftiBytes(bytes, "holes.nii");
    EXPECT_EQ(v.noDataVoxels, 3u);
    EXPECT_TRUE(std::isnan(v.value(1, 2, 0)));  // index 7
    EXPECT_TRUE(std::isnan(v.value(0, 3, 0)));  // index 9
    EXPECT_TRUE(v.isNoData(59));
    EXPECT_FALSE(v.isNoData(58));
    EXPECT_EQ(v.value(1, 3, 4), 0.5 * (1 + 12 + 80));
    // The range covers the finite voxels only: 0 .. 0.5 * 93 (voxel 58, (1, 3, 4)).
    EXPECT_EQ(v.minValue, 0.0);
    EXPECT_EQ(v.maxValue, 0.5 * 93);
    // What they store lies far below the finite range (base/volume.h noDataTexelBelow).
    EXPECT_LT(v.noDataTexel, -1e9f);
    EXPECT_EQ(v.normalized(7), static_cast<double>(v.noDataTexel));

    // All voxels without data: nothing to show, refused.
    Nifti2Spec tiny;
    tiny.dims = glm::ivec3(1), tiny.datatype = 64, tiny.bitpix = 64;
    std::vector<std::uint8_t> empty = makeNifti2(tiny);
    set<double>(empty, 544, std::nan(""), false);
    try {
        io::readNiftiBytes(empty, "empty.nii");
        FAIL() << "a volume without any data must be refused";
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), "data") << e.what();
    }
}

void expectError(const std::vector<std::uint8_t>& bytes, const std::string& field) {
    test::expectInputError([&] { io::readNiftiBytes(bytes, "bad2.nii"); }, "bad2.nii", field);
}

TEST(Nifti2, MalformedFilesNameTheirField) {
    Nifti2Spec s;
    std::vector<std::uint8_t> good = makeNifti2(s);
    expectError(std::vector<std::uint8_t>(good.begin(), good.begin() + 400), "header");
    auto textMode = good;  // "\r\n" translated to "\n" by a text-mode transfer
    std::memcpy(textMode.data() + 4, "n+2\0\n\032\n\0", 8);
    expectError(textMode, "magic");
    auto sixD = good;
    set<std::int64_t>(sixD, 16, 6, false);
    set<std::int64_t>(sixD, 16 + 8 * 6, 2, false);
    expectError(sixD, "dim[6]");
    auto hugeDim = good;
    set<std::int64_t>(hugeDim, 16 + 8 * 2, std::int64_t(1) << 40, false);
    expectError(hugeDim, "dim[2]");
    auto hugeCount = good;
    set<std::int64_t>(hugeCount, 16, 5, false);
    set<std::int64_t>(hugeCount, 16 + 8 * 4, std::int64_t(1) << 20, false);
    set<std::int64_t>(hugeCount, 16 + 8 * 5, std::int64_t(1) << 20, false);
    expectError(hugeCount, "dim[4]*dim[5]");
    Nifti2Spec cifti = s;
    cifti.intentCode = 3001;  // NIFTI_INTENT_CONNECTIVITY_DENSE
    expectError(makeNifti2(cifti), "intent_code");
    auto farOffset = good;
    set<std::int64_t>(farOffset, 168, 1 << 20, false);
    expectError(farOffset, "vox_offset");
    auto negativeOffset = good;
    set<std::int64_t>(negativeOffset, 168, -8, false);
    expectError(negativeOffset, "vox_offset");
    auto badSrow = good;
    set<std::int32_t>(badSrow, 348, 1, false);
    set<double>(badSrow, 400, std::nan(""), false);
    expectError(badSrow, "srow");
    expectError(std::vector<std::uint8_t>(good.begin(), good.end() - 1), "data");
    Nifti2Spec pair = s;
    pair.pair = true;
    expectError(makeNifti2(pair), "magic");  // a pair's header is not a single file
}

}  // namespace
}  // namespace curette
