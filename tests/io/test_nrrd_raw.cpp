// NRRD (attached and detached; raw, gzip, ascii; both endians; space directions, LPS) and raw volumes.
#include "io/nrrd.h"
#include "io/volume_file.h"
#include "base/error.h"
#include "tests/io/io_test_support.h"

#include <gtest/gtest.h>

namespace curette {
namespace {

using test::put;

// Voxel (i,j,k) of a 3x4x5 volume holds i + 4 j + 20 k.
std::vector<std::uint8_t> samples(const std::string& type, bool bigEndian) {
    std::vector<std::uint8_t> b;
    for (int k = 0; k < 5; ++k)
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 3; ++i) {
                int v = i + 4 * j + 20 * k;
                if (type == "uchar") b.push_back(static_cast<std::uint8_t>(v));
                else if (type == "short") put<std::int16_t>(b, static_cast<std::int16_t>(-v), bigEndian);
                else if (type == "ushort") put<std::uint16_t>(b, static_cast<std::uint16_t>(v * 10), bigEndian);
                else if (type == "int") put<std::int32_t>(b, v * 1000, bigEndian);
                else if (type == "float") put<float>(b, static_cast<float>(v) * 0.5f, bigEndian);
                else if (type == "double") put<double>(b, v * 0.25, bigEndian);
            }
    return b;
}

double expected(const std::string& type, int i, int j, int k) {
    double v = i + 4 * j + 20 * k;
    if (type == "short") return -v;
    if (type == "ushort") return v * 10;
    if (type == "int") return v * 1000;
    if (type == "float") return v * 0.5;
    if (type == "double") return v * 0.25;
    return v;
}

std::vector<std::uint8_t> text(const std::string& s) { return std::vector<std::uint8_t>(s.begin(), s.end()); }

TEST(Nrrd, EveryTypeEndianAndEncoding) {
    for (std::string type : {"uchar", "short", "ushort", "int", "float", "double"})
        for (bool big : {false, true})
            for (std::string encoding : {"raw", "gzip", "ascii"}) {
                std::string header = "NRRD0004\n# a comment\ntype: " + type + "\ndimension: 3\nsizes: 3 4 5\nencoding: " + encoding +
                                     "\nendian: " + (big ? "big" : "little") + "\nspacings: 1 1 1\nkey:=ignored\n\n";
                std::vector<std::uint8_t> data = samples(type, big);
                if (encoding == "gzip") data = test::gzipBytes(data);
                if (encoding == "ascii") {
                    std::string values;
                    for (int k = 0; k < 5; ++k)
                        for (int j = 0; j < 4; ++j)
                            for (int i = 0; i < 3; ++i) values += std::to_string(expected(type, i, j, k)) + ((i + j) % 3 ? " " : "\n");
                    data = text(values);
                }
                std::vector<std::uint8_t> file = text(header);
                file.insert(file.end(), data.begin(), data.end());
                VolumeData v = io::readNrrdBytes(file, "t.nrrd", ".");
                for (int k = 0; k < 5; ++k)
                    for (int j = 0; j < 4; ++j)
                        for (int i = 0; i < 3; ++i)
                            ASSERT_NEAR(v.value(i, j, k), expected(type, i, j, k), 1e-9) << type << " " << encoding << (big ? " big" : "");
            }
}

TEST(Nrrd, SpaceDirectionsOriginAndLpsToRas) {
    std::string header =
        "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 3 4 5\nencoding: raw\nspace: left-posterior-superior\n"
        "space directions: (0.9,0.1,0) (0,1.2,0.3) (0,0,2)\nspace origin: (10,20,30)\n\n";
    std::vector<std::uint8_t> file = text(header), data = samples("uchar", false);
    file.insert(file.end(), data.begin(), data.end());
    VolumeData v = io::readNrrdBytes(file, "lps.nrrd", ".");
    // LPS -> RAS negates x and y of every direction and of the origin.
    EXPECT_EQ(glm::dvec3(v.indexToWorld[0]), glm::dvec3(-0.9, -0.1, 0));
    EXPECT_EQ(glm::dvec3(v.indexToWorld[1]), glm::dvec3(0, -1.2, 0.3));
    EXPECT_EQ(glm::dvec3(v.indexToWorld[2]), glm::dvec3(0, 0, 2));
    EXPECT_EQ(glm::dvec3(v.indexToWorld[3]), glm::dvec3(-10, -20, 30));
}

TEST(Nrrd, DetachedHeaderWithByteSkipAndALeadingComponentAxis) {
    auto dir = test::scratchDirectory();
    std::vector<std::uint8_t> data(16, 0xAB);  // 16 bytes skipped
    auto body = samples("short", true);
    data.insert(data.end(), body.begin(), body.end());
    test::writeBytes(dir / "detached.raw", data);
    test::writeBytes(dir / "detached.nhdr",
                     text("NRRD0005\ntype: int16\ndimension: 4\nsizes: 1 3 4 5\nencoding: raw\nendian: big\nbyte skip: 16\n"
                          "space: RAS\nspace directions: none (1,0,0) (0,1,0) (0,0,1)\ndata file: detached.raw\n"));
    VolumeData v = io::readVolume(dir / "detached.nhdr");
    EXPECT_EQ(v.dims, glm::ivec3(3, 4, 5));
    EXPECT_EQ(v.files, (std::vector<std::filesystem::path>{dir / "detached.nhdr", dir / "detached.raw"})) << "the header and its data file";
    EXPECT_EQ(v.value(2, 3, 4), -94.0);
}

void expectError(const std::string& nrrd, const std::string& field) {
    try {
        io::readNrrdBytes(text(nrrd), "bad.nrrd", test::scratchDirectory());
        FAIL() << "expected an error naming " << field;
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), field) << e.what();
    }
}

TEST(Nrrd, MalformedHeadersNameTheirField) {
    expectError("NRRX0004\n", "magic");
    expectError("NRRD0004\ndimension: 3\nsizes: 3 4 5\nencoding: raw\n\n", "type");
    expectError("NRRD0004\ntype: uint32\ndimension: 3\nsizes: 3 4 5\nencoding: raw\nendian: little\n\n", "type");
    expectError("NRRD0004\ntype: uchar\ndimension: 3\nsizes: 3 4\nencoding: raw\n\n", "sizes");
    expectError("NRRD0004\ntype: uchar\ndimension: 3\nsizes: 3 0 5\nencoding: raw\n\n", "sizes");
    expectError("NRRD0004\ntype: uchar\ndimension: 2\nsizes: 3 4\nencoding: raw\n\n", "dimension");
    expectError("NRRD0004\ntype: uchar\ndimension: 3\nsizes: 3 4 5\nencoding: bzip2\n\n", "encoding");
    expectError("NRRD0004\ntype: short\ndimension: 3\nsizes: 3 4 5\nencoding: raw\n\n", "endian");
    expectError("NRRD0004\ntype: uchar\ndimension: 3\nsizes: 3 4 5\nencoding: raw\n\nabc", "data");
    expectError("NRRD0004\ntype: uchar\ndimension: 3\nsizes: 3 4 5\nencoding: raw\ndata file: missing.raw\n\n", "data file");
    expectError("NRRD0004\ntype: uchar\ndimension: 3\nsizes: 3 4 5\nencoding: raw\ndata file: LIST\n\n", "data file");
    expectError("NRRD0004\ntype: uchar\ndimension: 3\nsizes: 3 4 5\nencoding: raw\nspace directions: (1,0) (0,1) (0,0)\n\n" +
                    std::string(60, '\0'),
                "space directions");
    expectError("NRRD0004\ntype: uchar\ndimension: 3\nsizes: 3 4 5\nencoding: raw\nspace directions: (1,0,0) (2,0,0) (0,0,1)\n\n" +
                    std::string(60, '\0'),
                "space directions");
    expectError("NRRD0004\nthis line has no colon\n\n", "header line");
}

TEST(Raw, LayoutFromTheCommandLineAndSizeMismatch) {
    auto path = test::scratchDirectory() / "volume.raw";
    std::vector<std::uint8_t> bytes(10, 0);  // a 10-byte header
    auto body = samples("ushort", true);
    bytes.insert(bytes.end(), body.begin(), body.end());
    test::writeBytes(path, bytes);
    io::VolumeReadOptions options;
    options.raw = io::RawLayout{{3, 4, 5}, ScalarType::UInt16, true, {0.5, 0.5, 2.0}, {1, 2, 3}, 10, false};
    VolumeData v = io::readVolume(path, options);
    EXPECT_EQ(v.value(1, 2, 3), 10.0 * (1 + 8 + 60));
    EXPECT_EQ(glm::dvec3(v.indexToWorld[3]), glm::dvec3(1, 2, 3));
    EXPECT_EQ(v.indexToWorld[2][2], 2.0);
    options.raw->headerBytes = 12;
    try {
        io::readVolume(path, options);
        FAIL();
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), "size");
        EXPECT_NE(std::string(e.what()).find("130 bytes"), std::string::npos) << e.what();
    }
    options.raw->dims = {0, 4, 5};
    EXPECT_THROW(io::readVolume(path, options), InputError);
    EXPECT_THROW(io::readVolume(path), InputError) << "an unknown extension without a raw layout";
}

}  // namespace
}  // namespace curette
