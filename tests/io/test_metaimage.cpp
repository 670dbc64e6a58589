// MetaImage reading on small files the test writes: every ElementType, both byte orders, .mha and .mhd + raw,
// zlib and gzip compression, the LPS -> RAS affine of an oblique TransformMatrix, 4-D volumes by index, and
// malformed headers (each error names its key).
//
// No MetaImage oracle is installed here (neither python3-vtk9 nor SimpleITK), so the expected affine is derived
// by hand from the MetaIO convention: ITK's MetaImageIO takes row i of TransformMatrix (file order) as the
// direction of index axis i, in LPS; world_LPS = Offset + sum_i index_i * ElementSpacing_i * row_i; RAS negates
// x and y.
#include "io/metaimage.h"
#include "io/volume_file.h"
#include "base/error.h"
#include "tests/io/io_test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

namespace curette {
namespace {

using test::put;

struct TypeCase {
    const char* name;
    ScalarType readAs;
    std::function<void(std::vector<std::uint8_t>&, int, bool)> write;  // writes the element for v = i + 4j + 20k
    std::function<double(int)> value;                                  // its physical value
};

// Values chosen so every one is exact in the storage curette picks (float32 for the 32- and 64-bit integers:
// v * 40000000 and v * 2^40 need at most 24 significant bits for v < 100).
std::vector<TypeCase> typeCases() {
    return {
        {"MET_UCHAR", ScalarType::UInt8, [](auto& b, int v, bool) { b.push_back(static_cast<std::uint8_t>(v)); }, [](int v) { return double(v); }},
        {"MET_CHAR", ScalarType::Int16, [](auto& b, int v, bool) { b.push_back(static_cast<std::uint8_t>(static_cast<std::int8_t>(v - 50))); },
         [](int v) { return v - 50.0; }},
        {"MET_USHORT", ScalarType::UInt16, [](auto& b, int v, bool be) { put<std::uint16_t>(b, static_cast<std::uint16_t>(v * 600), be); },
         [](int v) { return v * 600.0; }},
        {"MET_SHORT", ScalarType::Int16, [](auto& b, int v, bool be) { put<std::int16_t>(b, static_cast<std::int16_t>(v * 300 - 15000), be); },
         [](int v) { return v * 300.0 - 15000; }},
        {"MET_UINT", ScalarType::Float64, [](auto& b, int v, bool be) { put<std::uint32_t>(b, static_cast<std::uint32_t>(v) * 40000000u, be); },
         [](int v) { return v * 40000000.0; }},
        {"MET_INT", ScalarType::Int32, [](auto& b, int v, bool be) { put<std::int32_t>(b, v * -100000 - 7, be); },
         [](int v) { return v * -100000.0 - 7; }},
        {"MET_ULONG", ScalarType::Float64, [](auto& b, int v, bool be) { put<std::uint32_t>(b, static_cast<std::uint32_t>(v) * 40000000u, be); },
         [](int v) { return v * 40000000.0; }},
        {"MET_LONG", ScalarType::Int32, [](auto& b, int v, bool be) { put<std::int32_t>(b, v * -100000 - 7, be); },
         [](int v) { return v * -100000.0 - 7; }},
        {"MET_ULONG_LONG", ScalarType::Float64, [](auto& b, int v, bool be) { put<std::uint64_t>(b, static_cast<std::uint64_t>(v) << 40, be); },
         [](int v) { return std::ldexp(double(v), 40); }},
        {"MET_LONG_LONG", ScalarType::Float64, [](auto& b, int v, bool be) { put<std::int64_t>(b, -(static_cast<std::int64_t>(v) << 35), be); },
         [](int v) { return -std::ldexp(double(v), 35); }},
        {"MET_FLOAT", ScalarType::Float32, [](auto& b, int v, bool be) { put<float>(b, static_cast<float>(v) * 0.25f, be); },
         [](int v) { return v * 0.25; }},
        {"MET_DOUBLE", ScalarType::Float64, [](auto& b, int v, bool be) { put<double>(b, v * 0.125 - 3, be); }, [](int v) { return v * 0.125 - 3; }},
    };
}

constexpr glm::ivec3 kDims{3, 4, 5};
int pattern(int i, int j, int k) { return i + 4 * j + 20 * k; }

std::vector<std::uint8_t> samples(const TypeCase& t, bool bigEndian, int volumes = 1) {
    std::vector<std::uint8_t> b;
    for (int n = 0; n < volumes; ++n)
        for (int k = 0; k < kDims.z; ++k)
            for (int j = 0; j < kDims.y; ++j)
                for (int i = 0; i < kDims.x; ++i) t.write(b, pattern(i, j, k) + n, bigEndian);
    return b;
}

std::vector<std::uint8_t> concat(const std::string& header, const std::vector<std::uint8_t>& data) {
    std::vector<std::uint8_t> b(header.begin(), header.end());
    b.insert(b.end(), data.begin(), data.end());
    return b;
}

std::string header(const std::string& type, bool bigEndian, const std::string& extra = "", const std::string& dataFile = "LOCAL") {
    return "ObjectType = Image\nNDims = 3\nDimSize = 3 4 5\nElementType = " + type +
           "\nBinaryData = True\nBinaryDataByteOrderMSB = " + (bigEndian ? "True" : "False") + "\n" + extra +
           "ElementDataFile = " + dataFile + "\n";
}

// zlib (not gzip) framing, as MetaIO's compress2 writes it.
std::vector<std::uint8_t> zlibBytes(const std::vector<std::uint8_t>& in) {
    uLongf size = compressBound(static_cast<uLong>(in.size()));
    std::vector<std::uint8_t> out(size);
    compress2(out.data(), &size, in.data(), static_cast<uLong>(in.size()), 6);
    out.resize(size);
    return out;
}

void expectPattern(const VolumeData& v, const TypeCase& t, const std::string& what, int volume = 0) {
    ASSERT_EQ(v.dims, kDims) << what;
    EXPECT_EQ(v.sourceType, t.readAs) << what;
    for (int k = 0; k < kDims.z; ++k)
        for (int j = 0; j < kDims.y; ++j)
            for (int i = 0; i < kDims.x; ++i)
                ASSERT_EQ(v.value(i, j, k), t.value(pattern(i, j, k) + volume)) << what << " at " << i << "," << j << "," << k;
}

TEST(MetaImage, EveryElementTypeBothByteOrdersMhaAndMhd) {
    auto dir = test::scratchDirectory();
    for (const TypeCase& t : typeCases())
        for (bool bigEndian : {false, true}) {
            std::string what = std::string(t.name) + (bigEndian ? " MSB" : " LSB");
            auto mha = dir / (std::string(t.name) + (bigEndian ? "-msb" : "-lsb") + ".mha");
            test::writeBytes(mha, concat(header(t.name, bigEndian), samples(t, bigEndian)));
            expectPattern(io::readVolume(mha), t, what + " .mha");

            // .mhd with the data in a .raw beside it, named relative to the header's folder.
            std::string raw = std::string(t.name) + (bigEndian ? "-msb" : "-lsb") + ".raw";
            auto mhd = dir / (std::string(t.name) + (bigEndian ? "-msb" : "-lsb") + ".mhd");
            std::string text = header(t.name, bigEndian, "", raw);
            test::writeBytes(mhd, std::vector<std::uint8_t>(text.begin(), text.end()));
            test::writeBytes(dir / raw, samples(t, bigEndian));
            VolumeData detached = io::readVolume(mhd);
            expectPattern(detached, t, what + " .mhd");
            EXPECT_EQ(detached.files, (std::vector<std::filesystem::path>{mhd, dir / raw})) << "the header and its data file";
            EXPECT_EQ(io::readVolume(mha).files, (std::vector<std::filesystem::path>{mha}));
        }
}

TEST(MetaImage, ElementByteOrderMsbIsASynonymAndBooleansReadTheirFirstCharacter) {
    const TypeCase t = typeCases()[3];  // MET_SHORT
    std::string text = "NDims = 3\nDimSize = 3 4 5\nElementType = MET_SHORT\nElementByteOrderMSB = true\nElementDataFile = LOCAL\n";
    expectPattern(io::readMetaImageBytes(concat(text, samples(t, true)), "msb.mha", "/"), t, "ElementByteOrderMSB = true");
    text = "NDims = 3\nDimSize = 3 4 5\nElementType = MET_SHORT\nBinaryDataByteOrderMSB = 1\nElementDataFile = LOCAL\n";
    expectPattern(io::readMetaImageBytes(concat(text, samples(t, true)), "msb1.mha", "/"), t, "BinaryDataByteOrderMSB = 1");
    text = "NDims = 3\nDimSize = 3 4 5\nElementType = MET_SHORT\nBinaryDataByteOrderMSB = False\nElementDataFile = LOCAL\n";
    expectPattern(io::readMetaImageBytes(concat(text, samples(t, false)), "lsb.mha", "/"), t, "BinaryDataByteOrderMSB = False");
    // CRLF line ends (a header written on Windows) read the same.
    text = "NDims = 3\r\nDimSize = 3 4 5\r\nElementType = MET_SHORT\r\nElementDataFile = LOCAL\r\n";
    expectPattern(io::readMetaImageBytes(concat(text, samples(t, false)), "crlf.mha", "/"), t, "CRLF");
}

TEST(MetaImage, CompressedDataZlibAndGzipWithAndWithoutTheirSize) {
    auto dir = test::scratchDirectory();
    const TypeCase t = typeCases()[10];  // MET_FLOAT
    std::vector<std::uint8_t> plain = samples(t, false);
    for (bool gzip : {false, true})
        for (bool sized : {false, true}) {
            std::vector<std::uint8_t> packed = gzip ? test::gzipBytes(plain) : zlibBytes(plain);
            std::string extra = "CompressedData = True\n" + (sized ? "CompressedDataSize = " + std::to_string(packed.size()) + "\n" : "");
            std::string what = std::string(gzip ? "gzip" : "zlib") + (sized ? " sized" : " unsized");
            // LOCAL: with a size, trailing bytes after the stream are ignored.
            std::vector<std::uint8_t> file = concat(header("MET_FLOAT", false, extra), packed);
            if (sized) file.insert(file.end(), {1, 2, 3});
            expectPattern(io::readMetaImageBytes(file, "z.mha", dir), t, what + " LOCAL");
            // A separate .zraw.
            std::string name = std::string("z-") + (gzip ? "gz" : "zlib") + (sized ? "-sized" : "") + ".zraw";
            test::writeBytes(dir / name, packed);
            std::string text = header("MET_FLOAT", false, extra, name);
            test::writeBytes(dir / "z.mhd", std::vector<std::uint8_t>(text.begin(), text.end()));
            expectPattern(io::readVolume(dir / "z.mhd"), t, what + " .zraw");
        }
}

TEST(MetaImage, ObliqueTransformMatrixGivesTheRasAffine) {
    // Rows (directions of axes 0, 1, 2 in LPS), orthonormal and oblique in all three axes:
    //   a0 = ( 0.8,   0.6,  0  )   a1 = (-0.48, 0.64, 0.6)   a2 = (0.36, -0.48, 0.8)
    // ElementSpacing (0.5, 2, 3), Offset (10, -20, 30) LPS. Column i of the RAS affine is spacing_i * a_i with
    // x and y negated; the translation is the Offset with x and y negated:
    //   [ -0.4   0.96  -1.08  -10 ]
    //   [ -0.3  -1.28   1.44   20 ]
    //   [  0     1.2    2.4    30 ]
    // Check by hand, voxel (1, 2, 3): LPS = Offset + 0.5 a0 + 4 a1 + 9 a2 = (11.72, -21.46, 39.6), RAS
    // (-11.72, 21.46, 39.6), which the matrix gives too.
    const double expected[3][4] = {{-0.4, 0.96, -1.08, -10}, {-0.3, -1.28, 1.44, 20}, {0, 1.2, 2.4, 30}};
    const TypeCase t = typeCases()[0];
    for (auto [offsetKey, matrixKey] : {std::pair{"Offset", "TransformMatrix"}, {"Position", "Rotation"}, {"Origin", "Orientation"}}) {
        std::string extra = std::string(matrixKey) + " = 0.8 0.6 0 -0.48 0.64 0.6 0.36 -0.48 0.8\n" + offsetKey +
                            " = 10 -20 30\nElementSpacing = 0.5 2 3\nAnatomicalOrientation = RAI\n";
        VolumeData v = io::readMetaImageBytes(concat(header("MET_UCHAR", false, extra), samples(t, false)), "oblique.mha", "/");
        for (int row = 0; row < 3; ++row)
            for (int col = 0; col < 4; ++col)
                EXPECT_NEAR(v.indexToWorld[col][row], expected[row][col], 1e-12) << matrixKey << " row " << row << " col " << col;
        glm::dvec3 p(v.indexToWorld * glm::dvec4(1, 2, 3, 1));
        EXPECT_NEAR(p.x, -11.72, 1e-12);
        EXPECT_NEAR(p.y, 21.46, 1e-12);
        EXPECT_NEAR(p.z, 39.6, 1e-12);
    }
    // Without orientation keys: identity directions, so RAS = diag(-s0, -s1, s2) and the negated origin;
    // ElementSize stands in for a missing ElementSpacing.
    VolumeData plain = io::readMetaImageBytes(
        concat(header("MET_UCHAR", false, "ElementSize = 1.5 2.5 3.5\nOffset = 1 2 3\n"), samples(t, false)), "plain.mha", "/");
    EXPECT_EQ(plain.indexToWorld, glm::dmat4(glm::dvec4(-1.5, 0, 0, 0), glm::dvec4(0, -2.5, 0, 0), glm::dvec4(0, 0, 3.5, 0), glm::dvec4(-1, -2, 3, 1)));
}

TEST(MetaImage, HeaderSizeSkipsBytesOrFindsTheDataAtTheEnd) {
    auto dir = test::scratchDirectory();
    const TypeCase t = typeCases()[2];  // MET_USHORT
    std::vector<std::uint8_t> prefixed(16, 0xee);
    std::vector<std::uint8_t> data = samples(t, true);
    prefixed.insert(prefixed.end(), data.begin(), data.end());
    test::writeBytes(dir / "prefixed.raw", prefixed);
    for (const char* size : {"16", "-1"}) {
        std::string text = header("MET_USHORT", true, std::string("HeaderSize = ") + size + "\n", "prefixed.raw");
        test::writeBytes(dir / "prefixed.mhd", std::vector<std::uint8_t>(text.begin(), text.end()));
        expectPattern(io::readVolume(dir / "prefixed.mhd"), t, std::string("HeaderSize = ") + size);
    }
    // LOCAL with HeaderSize: MetaIO seeks from the file's start, so it counts the header text too.
    std::string text = header("MET_USHORT", true, "HeaderSize = 000\n");
    std::size_t skip = text.size() + 7;
    text = header("MET_USHORT", true, "HeaderSize = " + std::to_string(skip) + "\n");
    ASSERT_EQ(text.size() + 7, skip);
    std::vector<std::uint8_t> file = concat(text, std::vector<std::uint8_t>(7, 0xee));
    file.insert(file.end(), data.begin(), data.end());
    expectPattern(io::readMetaImageBytes(file, "local-skip.mha", dir), t, "LOCAL HeaderSize");
}

TEST(MetaImage, FourDimensionalImagesReadOneVolumeByIndex) {
    const TypeCase t = typeCases()[3];  // MET_SHORT
    std::string text =
        "NDims = 4\nDimSize = 3 4 5 3\nElementType = MET_SHORT\nElementSpacing = 1 1 1 2.5\nOffset = 0 0 0 7\n"
        "TransformMatrix = 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\nElementDataFile = LOCAL\n";
    std::vector<std::uint8_t> file = concat(text, samples(t, false, 3));
    for (int n = 0; n < 3; ++n) {
        VolumeData v = io::readMetaImageBytes(file, "4d.mha", "/", n);
        EXPECT_EQ(v.volumeCount, 3);
        EXPECT_EQ(v.volumeIndex, n);
        expectPattern(v, t, "volume " + std::to_string(n), n);
    }
    try {
        io::readMetaImageBytes(file, "4d.mha", "/", 3);
        FAIL() << "index 3 of 3 volumes must be refused";
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), "--volume / volume.index") << e.what();
        EXPECT_NE(std::string(e.what()).find("3 volumes"), std::string::npos) << e.what();
    }
    // Through readVolume and its options, as `curette info --volume 2` does.
    auto path = test::scratchDirectory() / "4d.mha";
    test::writeBytes(path, file);
    io::VolumeReadOptions options;
    options.volumeIndex = 2;
    expectPattern(io::readVolume(path, options), t, "readVolume volume 2", 2);
}

TEST(MetaImage, RecognisedByItsFirstLineWithoutAnExtension) {
    auto path = test::scratchDirectory() / "metaimage-without-extension";
    test::writeBytes(path, concat(header("MET_UCHAR", false), samples(typeCases()[0], false)));
    expectPattern(io::readVolume(path), typeCases()[0], "sniffed");
}

TEST(MetaImage, NaNVoxelsAreNoData) {
    std::vector<std::uint8_t> data = samples(typeCases()[10], true);
    test::set<float>(data, 4 * 5, std::nanf(""), true);
    VolumeData v = io::readMetaImageBytes(concat(header("MET_FLOAT", true), data), "nan.mha", "/");
    EXPECT_EQ(v.noDataVoxels, 1u);
    EXPECT_TRUE(std::isnan(v.value(2, 1, 0)));
    EXPECT_EQ(v.minValue, 0.0);
    EXPECT_EQ(v.maxValue, 94 * 0.25);  // voxel (2, 3, 4)
}

void expectError(const std::string& text, const std::vector<std::uint8_t>& data, const std::string& field,
                 const std::filesystem::path& dir = "/nonexistent-dir", int volume = 0) {
    try {
        io::readMetaImageBytes(concat(text, data), "bad.mha", dir, volume);
        FAIL() << "expected an InputError naming " << field << " for\n" << text;
    } catch (const InputError& e) {
        EXPECT_EQ(e.file(), "bad.mha") << e.what();
        EXPECT_EQ(e.field(), field) << e.what();
    }
}

TEST(MetaImage, MalformedHeadersNameTheirKey) {
    std::vector<std::uint8_t> data = samples(typeCases()[0], false);
    const std::string good = header("MET_UCHAR", false);
    auto with = [&](const std::string& from, const std::string& to) {
        std::string s = good;
        std::size_t at = s.find(from);
        EXPECT_NE(at, std::string::npos) << from;
        return s.replace(at, from.size(), to);
    };
    expectError("NDims = 3\nDimSize = 3 4 5\nElementType = MET_UCHAR\n", data, "ElementDataFile");
    expectError(with("NDims = 3", "NDims = 2"), data, "NDims");
    expectError(with("NDims = 3\n", ""), data, "NDims");
    expectError(with("DimSize = 3 4 5", "DimSize = 3 4"), data, "DimSize");
    expectError(with("DimSize = 3 4 5", "DimSize = 3 0 5"), data, "DimSize");
    expectError(with("DimSize = 3 4 5", "DimSize = 3 four 5"), data, "DimSize");
    expectError(with("DimSize = 3 4 5", "DimSize = 3 4 100000000"), data, "DimSize");
    expectError(with("MET_UCHAR", "MET_FLOAT_ARRAY"), data, "ElementType");
    expectError(with("ElementType = MET_UCHAR\n", ""), data, "ElementType");
    expectError(with("BinaryData = True\n", "BinaryData = True\nElementNumberOfChannels = 3\n"), data, "ElementNumberOfChannels");
    expectError(with("BinaryData = True", "BinaryData = False"), data, "BinaryData");
    expectError(with("ObjectType = Image", "ObjectType = Tube"), data, "ObjectType");
    expectError(with("ElementDataFile = LOCAL", "ElementDataFile = LIST 2D"), data, "ElementDataFile");
    expectError(with("ElementDataFile = LOCAL", "ElementDataFile = slice%03d.raw 1 5 1"), data, "ElementDataFile");
    expectError(with("ElementDataFile = LOCAL", "ElementDataFile = missing.raw"), data, "ElementDataFile");
    expectError(with("BinaryData = True\n", "BinaryData = True\nthis line has no equals sign\n"), data, "line 6");
    expectError(with("BinaryData = True\n", "BinaryData = True\nDimSize = 3 4 5\n"), data, "DimSize");
    expectError(with("BinaryData = True\n", "BinaryData = True\nElementSpacing = 1 -1 1\n"), data, "ElementSpacing");
    expectError(with("BinaryData = True\n", "BinaryData = True\nTransformMatrix = 1 0 0 1 0 0 0 0 1\n"), data, "TransformMatrix");
    expectError(with("BinaryData = True\n", "BinaryData = True\nTransformMatrix = 1 0 0 0 1 0\n"), data, "TransformMatrix");
    expectError(with("BinaryData = True\n", "BinaryData = True\nOffset = 0 0 0\nOrigin = 0 0 0\n"), data, "Offset/Origin");
    expectError(with("BinaryData = True\n", "BinaryData = True\nOffset = 0 nan 0\n"), data, "Offset");
    expectError(with("BinaryData = True\n", "BinaryData = True\nElementByteOrderMSB = True\n"), data, "ElementByteOrderMSB");
    expectError(with("BinaryData = True\n", "BinaryData = True\nHeaderSize = -2\n"), data, "HeaderSize");
    expectError(with("BinaryData = True\n", "BinaryData = True\nHeaderSize = 3\n"), data, "HeaderSize");
    expectError(good, std::vector<std::uint8_t>(data.begin(), data.end() - 1), "data");
    expectError(good, data, "--volume / volume.index", "/nonexistent-dir", 1);
    // Compressed: a corrupt stream, a stream that ends early, and a size beyond the file.
    std::vector<std::uint8_t> packed = zlibBytes(data);
    std::vector<std::uint8_t> corrupt = packed;
    corrupt[0] ^= 0x55;  // the zlib header's check bits no longer hold
    expectError(with("BinaryData = True\n", "BinaryData = True\nCompressedData = True\n"), corrupt, "CompressedData");
    std::vector<std::uint8_t> badCheck = packed;  // the data intact, the Adler-32 at the end damaged
    badCheck.at(badCheck.size() - 1) ^= 0x01;
    expectError(with("BinaryData = True\n", "BinaryData = True\nCompressedData = True\n"), badCheck, "CompressedData");
    expectError(with("BinaryData = True\n", "BinaryData = True\nCompressedData = True\n"), zlibBytes(std::vector<std::uint8_t>(data.begin(), data.end() - 2)),
                "data");
    expectError(with("BinaryData = True\n", "BinaryData = True\nCompressedData = True\nCompressedDataSize = 100000\n"), packed,
                "CompressedDataSize");
    expectError(with("BinaryData = True\n", "BinaryData = True\nCompressedData = True\nHeaderSize = -1\n"), packed, "HeaderSize");
    // A 4-D matrix whose fourth axis moves through space.
    expectError("NDims = 4\nDimSize = 3 4 5 1\nElementType = MET_UCHAR\nTransformMatrix = 1 0 0 0 0 1 0 0 0 0 1 0.5 0 0 0 1\nElementDataFile = LOCAL\n",
                data, "TransformMatrix");
}

TEST(MetaImage, AHeaderClaimingHugeCompressedDataCostsOnlyWhatItHolds) {
    // 2^40 voxels promised, a few bytes of stream: refused as short data, without allocating the promise.
    std::string text = "NDims = 3\nDimSize = 16384 16384 4096\nElementType = MET_UCHAR\nCompressedData = True\nElementDataFile = LOCAL\n";
    expectError(text, zlibBytes(std::vector<std::uint8_t>(1000, 7)), "data");
}

}  // namespace
}  // namespace curette
