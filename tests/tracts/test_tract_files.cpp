// TrackVis and MRtrix files: every variant the readers claim, the real dipy bundle, and malformed files.
#include "io/tract_file.h"
#include "base/error.h"
#include "tests/io/io_test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

namespace curette {
namespace {

using test::put;
using test::set;

struct TrkSpec {
    bool big = false;
    int version = 2;
    int scalars = 0, properties = 0;
    glm::dvec3 voxelSize{2, 2, 2};
    const char* order = "RAS";
    bool identityAffine = true;
    int declaredCount = -1;  // -1: the true count
};

// Two tracks: (1,2,3)-(5,6,7)-(9,10,11) and (0,0,0)-(4,0,0), in voxmm; scalar s = point index, property = track.
std::vector<std::uint8_t> makeTrk(const TrkSpec& s) {
    std::vector<std::uint8_t> h(1000, 0);
    std::memcpy(h.data(), "TRACK", 6);
    set<std::int16_t>(h, 6, 10, s.big);
    set<std::int16_t>(h, 8, 10, s.big);
    set<std::int16_t>(h, 10, 10, s.big);
    for (int a = 0; a < 3; ++a) set<float>(h, static_cast<std::size_t>(12 + 4 * a), static_cast<float>(s.voxelSize[a]), s.big);
    set<std::int16_t>(h, 36, static_cast<std::int16_t>(s.scalars), s.big);
    if (s.scalars) std::memcpy(h.data() + 38, "index", 5);
    set<std::int16_t>(h, 238, static_cast<std::int16_t>(s.properties), s.big);
    if (s.properties) std::memcpy(h.data() + 240, "track", 5);
    if (s.version == 2 && s.identityAffine)
        for (int d = 0; d < 4; ++d) set<float>(h, static_cast<std::size_t>(440 + 4 * (4 * d + d)), 1.0f, s.big);
    std::memcpy(h.data() + 948, s.order, 3);
    set<std::int32_t>(h, 988, s.declaredCount >= 0 ? s.declaredCount : 2, s.big);
    set<std::int32_t>(h, 992, s.version, s.big);
    set<std::int32_t>(h, 996, 1000, s.big);
    std::vector<std::vector<glm::vec3>> tracks = {{{1, 2, 3}, {5, 6, 7}, {9, 10, 11}}, {{0, 0, 0}, {4, 0, 0}}};
    for (std::size_t t = 0; t < tracks.size(); ++t) {
        put<std::int32_t>(h, static_cast<std::int32_t>(tracks[t].size()), s.big);
        for (std::size_t i = 0; i < tracks[t].size(); ++i) {
            for (int a = 0; a < 3; ++a) put<float>(h, tracks[t][i][a], s.big);
            for (int k = 0; k < s.scalars; ++k) put<float>(h, static_cast<float>(i), s.big);
        }
        for (int k = 0; k < s.properties; ++k) put<float>(h, static_cast<float>(t), s.big);
    }
    return h;
}

TEST(Trk, VersionsEndiansScalarsAndProperties) {
    for (bool big : {false, true})
        for (int version : {1, 2}) {
            TrkSpec s;
            s.big = big, s.version = version, s.scalars = 2, s.properties = 1;
            Tractogram t = io::readTrkBytes(makeTrk(s), "t.trk");
            ASSERT_EQ(t.streamlineCount(), 2u);
            ASSERT_EQ(t.points.size(), 5u);
            // v2 identity affine: world = voxmm / voxel size - 0.5; v1 (no affine): world = voxmm - size/2.
            glm::vec3 expected = version == 2 ? glm::vec3(5, 6, 7) / 2.0f - 0.5f : glm::vec3(5, 6, 7) - 1.0f;
            EXPECT_EQ(t.points[1], expected) << (big ? "big" : "little") << " v" << version;
            ASSERT_EQ(t.scalarNames.size(), 2u);
            EXPECT_EQ(t.scalarNames[0], "index");
            EXPECT_EQ(t.scalars[2 * 2], 2.0f);
            EXPECT_EQ(t.propertyNames[0], "track");
            EXPECT_EQ(t.properties[1], 1.0f);
        }
}

TEST(Trk, VoxelOrderThatDisagreesWithTheAffineIsReoriented) {
    TrkSpec s;
    s.order = "LAS";  // header says x grows to the left; the identity affine says right
    Tractogram t = io::readTrkBytes(makeTrk(s), "las.trk");
    // x' = (dim - 1) - x in voxels before the affine: (10 - 1) - (5/2 - 0.5) = 7.
    EXPECT_FLOAT_EQ(t.points[1].x, 7.0f);
    EXPECT_FLOAT_EQ(t.points[1].y, 2.5f);
}

TEST(Trk, TheDipyArcuateFasciculusMatchesNibabel) {
    Tractogram t = io::readTractogram("/usr/local/share/curette/dipy-bundles/sub_1/AF_L.trk");
    EXPECT_EQ(t.streamlineCount(), 50u);
    EXPECT_EQ(t.points.size(), 1000u);
    // nibabel 5 (Debian python3-nibabel) reads the first point and the bounding box as:
    EXPECT_NEAR(t.points[0].x, -41.438972, 1e-5);
    EXPECT_NEAR(t.points[0].y, -14.871033, 1e-5);
    EXPECT_NEAR(t.points[0].z, -40.816006, 1e-5);
    glm::vec3 lo(1e9f), hi(-1e9f);
    for (glm::vec3 p : t.points) lo = glm::min(lo, p), hi = glm::max(hi, p);
    EXPECT_NEAR(lo.x, -59.71528, 1e-4);
    EXPECT_NEAR(hi.y, 46.01281, 1e-4);
    EXPECT_NEAR(hi.z, 24.732552, 1e-4);
}

void expectTrkError(std::vector<std::uint8_t> bytes, const std::string& field) {
    try {
        io::readTrkBytes(bytes, "bad.trk");
        FAIL() << "expected an error naming " << field;
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), field) << e.what();
    }
}

TEST(Trk, MalformedFilesNameTheirField) {
    std::vector<std::uint8_t> good = makeTrk({});
    expectTrkError(std::vector<std::uint8_t>(good.begin(), good.begin() + 500), "header");
    auto id = good;
    id[0] = 'X';
    expectTrkError(id, "id_string");
    auto size = good;
    set<std::int32_t>(size, 996, 999, false);
    expectTrkError(size, "hdr_size");
    auto scalars = good;
    set<std::int16_t>(scalars, 36, 11, false);
    expectTrkError(scalars, "n_scalars");
    TrkSpec moreCounted;
    moreCounted.declaredCount = 3;
    expectTrkError(makeTrk(moreCounted), "n_count");
    TrkSpec fewerCounted;
    fewerCounted.declaredCount = 1;
    expectTrkError(makeTrk(fewerCounted), "n_count");
    expectTrkError(std::vector<std::uint8_t>(good.begin(), good.end() - 6), "track 1 n_points");
    auto negative = good;
    set<std::int32_t>(negative, 1000, -5, false);
    expectTrkError(negative, "track 0 n_points");
    auto absurd = good;
    set<std::int32_t>(absurd, 1000, 2000000000, false);
    expectTrkError(absurd, "track 0 n_points");
    auto nan = good;
    set<float>(nan, 1004 + 12, std::nanf(""), false);
    expectTrkError(nan, "track 0 point 1");
    // n_count 0 means "read to the end".
    auto open = good;
    set<std::int32_t>(open, 988, 0, false);
    EXPECT_EQ(io::readTrkBytes(open, "open.trk").streamlineCount(), 2u);
}

std::vector<std::uint8_t> makeTck(const std::string& datatype, const std::vector<std::vector<glm::dvec3>>& tracks, bool terminate = true,
                                  const std::string& count = "") {
    bool big = datatype.back() == 'E' && datatype[datatype.size() - 2] == 'B';
    bool doubles = datatype.find("64") != std::string::npos;
    std::string header = "mrtrix tracks\ndatatype: " + datatype + "\n" + (count.empty() ? "" : "count: " + count + "\n") + "file: . ";
    std::size_t offset = header.size() + 16;
    header += std::to_string(offset) + "\nEND\n";
    header.resize(offset, '\n');
    std::vector<std::uint8_t> b(header.begin(), header.end());
    auto triple = [&](double x, double y, double z) {
        for (double v : {x, y, z}) {
            if (doubles) put<double>(b, v, big);
            else put<float>(b, static_cast<float>(v), big);
        }
    };
    for (const auto& t : tracks) {
        for (glm::dvec3 p : t) triple(p.x, p.y, p.z);
        triple(NAN, NAN, NAN);
    }
    if (terminate) triple(INFINITY, INFINITY, INFINITY);
    return b;
}

TEST(Tck, EveryDatatypeAndTheDelimiters) {
    std::vector<std::vector<glm::dvec3>> tracks = {{{1, 2, 3}, {4, 5, 6}}, {{-1, -2, -3}, {0, 0, 0}, {7, 8, 9}}};
    for (std::string type : {"Float32LE", "Float32BE", "Float64LE", "Float64BE"}) {
        Tractogram t = io::readTckBytes(makeTck(type, tracks, true, "2"), "t.tck");
        ASSERT_EQ(t.streamlineCount(), 2u) << type;
        EXPECT_EQ(t.pointCount(1), 3u);
        EXPECT_EQ(t.points[4], glm::vec3(7, 8, 9)) << type;
    }
    // A missing Inf terminator after a complete streamline is read (with a warning).
    EXPECT_EQ(io::readTckBytes(makeTck("Float32LE", tracks, false), "open.tck").streamlineCount(), 2u);
}

TEST(Tck, MalformedFilesNameTheirField) {
    auto expectError = [](std::vector<std::uint8_t> b, const std::string& field) {
        try {
            io::readTckBytes(b, "bad.tck");
            FAIL() << "expected an error naming " << field;
        } catch (const InputError& e) {
            EXPECT_EQ(e.field(), field) << e.what();
        }
    };
    std::vector<std::vector<glm::dvec3>> tracks = {{{1, 2, 3}, {4, 5, 6}}};
    auto good = makeTck("Float32LE", tracks);
    auto text = [](const std::string& s) { return std::vector<std::uint8_t>(s.begin(), s.end()); };
    expectError(text("mrtrix image\n"), "magic");
    expectError(text("mrtrix tracks\nfile: . 30\nEND\n"), "datatype");
    expectError(text("mrtrix tracks\ndatatype: Int16LE\nfile: . 50\nEND\n"), "datatype");
    expectError(text("mrtrix tracks\ndatatype: Float32LE\nEND\n"), "file");
    expectError(text("mrtrix tracks\ndatatype: Float32LE\nfile: . 999999\nEND\n"), "file");
    expectError(text("mrtrix tracks\ndatatype: Float32LE\nfile: . 50\n"), "header");
    auto truncated = good;
    truncated.resize(truncated.size() - 24);  // drop the NaN delimiter and the Inf terminator
    expectError(truncated, "data");
    auto partialNan = good;
    std::size_t dataStart = partialNan.size() - 4 * 3 * 4;
    set<float>(partialNan, dataStart + 4, std::nanf(""), false);  // a NaN in the middle of a point
    expectError(partialNan, "point 0");
}

}  // namespace
}  // namespace curette
