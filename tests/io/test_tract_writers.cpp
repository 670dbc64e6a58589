// The .trk and TRX writers (io/trk_writer.h, io/trx_writer.h): each file read back by curette's readers
// (io/tract_file.h, io/trx.h) and by an independent one (tests/io/read_tracts_oracle.py: nibabel for .trk,
// Python's zipfile with its CRC-32 check for TRX) gives the written points; bad input is refused as writeTck
// refuses it, leaving no file.
#include "io/trk_writer.h"
#include "io/trx_writer.h"
#include "io/tract_file.h"
#include "base/atomic_file.h"
#include "base/error.h"
#include "tests/io/io_test_support.h"

#include <gtest/gtest.h>
#include <zip.h>

#include <array>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <sstream>
#include <sys/wait.h>

namespace curette {
namespace {

namespace fs = std::filesystem;

template <typename T>
T at(const std::vector<std::uint8_t>& bytes, std::size_t offset) {
    T value;
    std::memcpy(&value, bytes.data() + offset, sizeof(T));
    return value;
}

// Odd coordinates (fractions no binary float holds exactly, tiny and negative values, a point far from the
// others), a streamline of one point and an empty one, per-point scalars and per-streamline properties.
Tractogram oddTractogram() {
    Tractogram t;
    t.points = {{-80.123456f, 120.5f, -0.001f}, {1e-7f, -1e-7f, 3.25f}, {95.9999f, -110.0001f, 70.7f},  // 3 points
                {0.1f, 0.2f, 0.3f},                                                                    // 1 point
                {-100.0f, 100.0f, 0.0f}, {33.333332f, -66.66667f, 99.99999f}};                         // 2 points
    t.offsets = {0, 3, 4, 4, 6};  // the third streamline is empty
    t.scalarNames = {"fa", "a_name_of_20_bytes__"};
    for (std::size_t p = 0; p < t.points.size(); ++p) t.scalars.push_back(0.1f * static_cast<float>(p)), t.scalars.push_back(-static_cast<float>(p));
    t.propertyNames = {"length"};
    t.properties = {3.5f, 0.0f, -1.0f, 7.25f};
    return t;
}

// What .trk keeps of oddTractogram(): the empty streamline and its property are left out (nibabel drops empty
// streamlines on reading).
Tractogram withoutTheEmptyStreamline(Tractogram t) {
    t.offsets = {0, 3, 4, 6};
    t.properties = {3.5f, 0.0f, 7.25f};
    return t;
}

// .trk stores voxmm (shifted by the grid origin) as float32, so a point comes back to float32 precision of
// the larger of its own magnitude and the grid's extent (here below 256 mm): one ulp of 256.
constexpr float kTrkTolerance = 256.0f * FLT_EPSILON;

void expectSamePoints(const Tractogram& read, const Tractogram& written, float tolerance, const std::string& what) {
    ASSERT_EQ(read.offsets, written.offsets) << what;
    ASSERT_EQ(read.points.size(), written.points.size()) << what;
    for (std::size_t p = 0; p < read.points.size(); ++p)
        for (int a = 0; a < 3; ++a) {
            if (tolerance == 0) EXPECT_EQ(read.points[p][a], written.points[p][a]) << what << " point " << p << " axis " << a;
            else EXPECT_NEAR(read.points[p][a], written.points[p][a], tolerance) << what << " point " << p << " axis " << a;
        }
}

// What tests/io/read_tracts_oracle.py prints: the streamlines, and per streamline each scalar's values.
struct OracleRead {
    int exitCode = -1;
    std::string output;
    Tractogram tracts;
    std::map<std::string, std::vector<float>> scalars;
};

OracleRead readWithOracle(const fs::path& file) {
    OracleRead r;
    std::string command = "/usr/bin/python3 '" CURETTE_SOURCE_DIR "/tests/io/read_tracts_oracle.py' '" + file.string() + "' 2>&1";
    FILE* pipe = popen(command.c_str(), "r");
    std::array<char, 4096> buffer;
    while (std::size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe)) r.output.append(buffer.data(), n);
    int status = pclose(pipe);
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::istringstream in(r.output);
    std::string word;
    std::size_t count = 0;
    in >> word >> count;
    for (std::size_t s = 0; s < count && in; ++s) {
        std::size_t n = 0, scalarCount = 0;
        in >> word >> n >> scalarCount;
        for (std::size_t i = 0; i < n; ++i) {
            glm::vec3 p;
            in >> p.x >> p.y >> p.z;
            r.tracts.points.push_back(p);
        }
        r.tracts.offsets.push_back(static_cast<std::uint32_t>(r.tracts.points.size()));
        for (std::size_t k = 0; k < scalarCount; ++k) {
            std::string name;
            in >> word >> name;
            for (std::size_t i = 0; i < n; ++i) in >> r.scalars[name].emplace_back();
        }
    }
    return r;
}

bool pythonInstalled() { return fs::exists("/usr/bin/python3"); }

// --- .trk --------------------------------------------------------------------------------------------------

TEST(TrkWriter, RoundTripThroughTheTractReader) {
    Tractogram written = oddTractogram();
    fs::path path = test::scratchDirectory() / "odd.trk";
    io::writeTrk(path, written);
    Tractogram read = io::readTractogram(path);
    written = withoutTheEmptyStreamline(written);
    expectSamePoints(read, written, kTrkTolerance, path.string());
    EXPECT_EQ(read.scalarNames, written.scalarNames);
    EXPECT_EQ(read.scalars, written.scalars);
    EXPECT_EQ(read.propertyNames, written.propertyNames);
    EXPECT_EQ(read.properties, written.properties);
}

TEST(TrkWriter, TheHeaderIsVersion2WithEveryPointInsideItsGrid) {
    Tractogram written = oddTractogram();
    written.scalarNames.clear(), written.scalars.clear(), written.propertyNames.clear(), written.properties.clear();
    fs::path path = test::scratchDirectory() / "header.trk";
    io::writeTrk(path, written);
    std::vector<std::uint8_t> b = readFileBytes(path);
    ASSERT_GE(b.size(), 1000u);
    EXPECT_EQ(std::string(reinterpret_cast<const char*>(b.data()), 6), std::string("TRACK\0", 6));
    EXPECT_EQ(at<std::int32_t>(b, 996), 1000) << "hdr_size";
    EXPECT_EQ(at<std::int32_t>(b, 992), 2) << "version";
    EXPECT_EQ(at<std::int32_t>(b, 988), 3) << "n_count: the streamlines with points";
    EXPECT_EQ(std::string(reinterpret_cast<const char*>(b.data()) + 948, 4), std::string("RAS\0", 4)) << "voxel_order";
    EXPECT_EQ(at<std::int16_t>(b, 36), 0) << "n_scalars";
    EXPECT_EQ(at<std::int16_t>(b, 238), 0) << "n_properties";
    glm::vec3 extent;
    for (int a = 0; a < 3; ++a) {
        std::int16_t dim = at<std::int16_t>(b, 6 + 2 * a);
        float voxel = at<float>(b, 12 + 4 * a);
        EXPECT_GT(dim, 0);
        EXPECT_GT(voxel, 0.0f);
        extent[a] = static_cast<float>(dim) * voxel;
        // vox_to_ras's diagonal is the voxel size: the grid's axes are R, A, S.
        EXPECT_EQ(at<float>(b, 440 + 4 * (4 * a + a)), voxel);
    }
    EXPECT_EQ(at<float>(b, 440 + 4 * 15), 1.0f);
    // 6 points of 12 bytes and a 4-byte count per streamline written.
    ASSERT_EQ(b.size(), 1000u + 3 * 4 + 12 * 6);
    written = withoutTheEmptyStreamline(written);
    // TrackVis draws a point where its voxmm lies in the grid [0, dim * voxel_size) (the corner of voxel 0 is 0).
    std::size_t pos = 1000;
    for (int s = 0; s < 3; ++s) {
        std::int32_t n = at<std::int32_t>(b, pos);
        EXPECT_EQ(n, static_cast<std::int32_t>(written.pointCount(static_cast<std::size_t>(s))));
        pos += 4;
        for (std::int32_t i = 0; i < n; ++i, pos += 12)
            for (int a = 0; a < 3; ++a) {
                float voxmm = at<float>(b, pos + 4 * static_cast<std::size_t>(a));
                EXPECT_GT(voxmm, 0.0f) << "streamline " << s << " point " << i;
                EXPECT_LT(voxmm, extent[a]) << "streamline " << s << " point " << i;
            }
    }
}

TEST(TrkWriter, NibabelReadsTheWrittenPointsAndScalars) {
    if (!pythonInstalled()) GTEST_SKIP() << "/usr/bin/python3 is not installed (the oracle is nibabel, Debian python3-nibabel)";
    Tractogram written = oddTractogram();
    written.propertyNames.clear(), written.properties.clear();
    fs::path path = test::scratchDirectory() / "nibabel.trk";
    io::writeTrk(path, written);
    OracleRead r = readWithOracle(path);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    written = withoutTheEmptyStreamline(written);
    expectSamePoints(r.tracts, written, kTrkTolerance, "nibabel " + path.string());
    for (std::size_t k = 0; k < written.scalarNames.size(); ++k) {
        const std::vector<float>& values = r.scalars[written.scalarNames[k]];
        ASSERT_EQ(values.size(), written.points.size()) << written.scalarNames[k] << "\n" << r.output;
        for (std::size_t p = 0; p < values.size(); ++p) EXPECT_EQ(values[p], written.scalars[2 * p + k]) << written.scalarNames[k] << " " << p;
    }
}

// --- TRX ---------------------------------------------------------------------------------------------------

TEST(TrxWriter, RoundTripIsExactAndTheZipIsStoredWithTheSpecsMembers) {
    Tractogram written = oddTractogram();
    fs::path path = test::scratchDirectory() / "odd.trx";
    io::writeTrx(path, written);
    Tractogram read = io::readTractogram(path);
    expectSamePoints(read, written, 0.0f, path.string());
    int error = 0;
    zip_t* zip = zip_open(path.c_str(), ZIP_RDONLY | ZIP_CHECKCONS, &error);
    ASSERT_NE(zip, nullptr) << "libzip error " << error;
    std::vector<std::string> names;
    for (zip_int64_t i = 0; i < zip_get_num_entries(zip, 0); ++i) {
        zip_stat_t stat;
        ASSERT_EQ(zip_stat_index(zip, static_cast<zip_uint64_t>(i), 0, &stat), 0);
        names.push_back(stat.name);
        EXPECT_EQ(stat.comp_method, ZIP_CM_STORE) << stat.name;
        EXPECT_EQ(stat.size, stat.comp_size) << stat.name;
    }
    zip_discard(zip);
    EXPECT_EQ(names, (std::vector<std::string>{"header.json", "offsets.uint64", "positions.3.float32"}));
}

TEST(TrxWriter, PythonsZipfileChecksEveryCrcAndReadsTheSamePoints) {
    if (!pythonInstalled()) GTEST_SKIP() << "/usr/bin/python3 is not installed (the oracle is Python's zipfile)";
    Tractogram written = oddTractogram();
    fs::path path = test::scratchDirectory() / "python.trx";
    io::writeTrx(path, written);
    OracleRead r = readWithOracle(path);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    expectSamePoints(r.tracts, written, 0.0f, "zipfile " + path.string());
    // An empty tractogram is a valid archive too.
    fs::path empty = test::scratchDirectory() / "empty.trx";
    io::writeTrx(empty, Tractogram{});
    OracleRead e = readWithOracle(empty);
    ASSERT_EQ(e.exitCode, 0) << e.output;
    EXPECT_EQ(e.tracts.streamlineCount(), 0u);
    EXPECT_EQ(io::readTractogram(empty).streamlineCount(), 0u);
}

// --- bad input ---------------------------------------------------------------------------------------------

TEST(TractWriters, NonFinitePointsAndBadOffsetsAreRefusedLeavingNoFile) {
    for (const char* extension : {".trk", ".trx"}) {
        auto write = [&](const fs::path& path, const Tractogram& t) {
            if (std::string(extension) == ".trk") io::writeTrk(path, t);
            else io::writeTrx(path, t);
        };
        Tractogram tracts;
        tracts.points = {{1, 2, 3}, {NAN, 0, 0}};
        tracts.offsets = {0, 2};
        fs::path path = test::scratchDirectory() / (std::string("bad") + extension);
        test::expectInputError([&] { write(path, tracts); }, path.string(), "points[1]");
        tracts.points[1] = {0, INFINITY, 0};
        test::expectInputError([&] { write(path, tracts); }, path.string(), "points[1]");
        tracts.points[1] = {0, 0, 0};
        tracts.offsets = {0, 3};
        test::expectInputError([&] { write(path, tracts); }, path.string(), "offsets");
        EXPECT_FALSE(fs::exists(path)) << extension;
        for (const fs::directory_entry& e : fs::directory_iterator(test::scratchDirectory()))
            EXPECT_EQ(e.path().filename().string().find(".bad"), std::string::npos) << "a temporary file was left: " << e.path();
    }
    // .trk only: its header holds 10 scalar names of 20 bytes, and the scalars must fill the points.
    Tractogram tracts = oddTractogram();
    fs::path path = test::scratchDirectory() / "names.trk";
    tracts.scalarNames[1] = "a_name_of_21_bytes___";
    test::expectInputError([&] { io::writeTrk(path, tracts); }, path.string(), "scalarNames[1]");
    tracts = oddTractogram();
    tracts.scalars.pop_back();
    test::expectInputError([&] { io::writeTrk(path, tracts); }, path.string(), "scalars");
    EXPECT_FALSE(fs::exists(path));
}

}  // namespace
}  // namespace curette
