// Tract formats beyond the synthetic .trk/.tck files: nibabel's own test tractograms (each read with the
// counts and coordinates nibabel gives, or refused where nibabel refuses), a .tck with a stale count, the
// gzip-compressed variants, and TRX (zip stored or deflated, or a folder; every positions and offsets dtype;
// both offsets lengths the spec versions disagree on; malformed archives).
#include "io/trx.h"
#include "io/tract_file.h"
#include "base/atomic_file.h"
#include "base/error.h"
#include "base/log.h"
#include "tests/io/io_test_support.h"
#include "tests/tracts/trx_test_writer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>

namespace curette {
namespace {

namespace fs = std::filesystem;

const fs::path kNibabel = "/usr/local/share/curette/nibabel-data";

// A missing folder is a broken test machine (scripts/setup installs it), not a reason to pass.
void requireNibabelData() { ASSERT_TRUE(fs::is_directory(kNibabel)) << kNibabel << " is missing: nibabel's test data must be installed"; }

// Everything log::warn writes while `f` runs (the tests run with CURETTE_LOG=error, so warnings are
// switched on here).
template <typename F>
std::string warningsOf(F&& f) {
    log::Level before = log::level();
    log::setLevel(log::Level::Warn);
    ::testing::internal::CaptureStderr();
    try {
        f();
    } catch (...) {
        ::testing::internal::GetCapturedStderr();
        log::setLevel(before);
        throw;
    }
    std::string text = ::testing::internal::GetCapturedStderr();
    log::setLevel(before);
    return text;
}

// What nibabel 5.0.0 (Debian python3-nibabel, nibabel.streamlines.load(f).streamlines, RAS mm) reports.
struct NibabelFile {
    const char* name;
    std::size_t streamlines, points;
    std::vector<std::size_t> firstLengths;  // the first few streamlines' point counts
    glm::vec3 first, last;                  // first point of the first streamline, last of the last
};

const glm::vec3 kSimpleFirst(0, 1, 2), kSimpleLast(12, 13, 14);
const glm::vec3 kStandardFirst(-0.5f, -1.5f, 1.0f), kStandardLast(3.5f, 13.5f, 11.0f);

const std::vector<NibabelFile> kReadable = {
    {"simple.tck", 3, 8, {1, 2, 5}, kSimpleFirst, kSimpleLast},
    {"simple_big_endian.tck", 3, 8, {1, 2, 5}, kSimpleFirst, kSimpleLast},
    {"standard.tck", 120, 360, {3, 3, 3}, kStandardFirst, kStandardLast},
    // header count 615000, one NaN-delimited streamline, -Inf terminator: read (with a warning).
    {"matlab_nan.tck", 1, 108, {108}, {-0.1301320344209671f, -0.45225098729133606f, 7.438110828399658f},
     {-0.9685187339782715f, -19.076133728027344f, 14.556561470031738f}},
    // command_history split over two header lines; 253 points all at (-0, 0, -0).
    {"multiline_header_field.tck", 1, 253, {253}, {0, 0, 0}, {0, 0, 0}},
    {"empty.tck", 0, 0, {}, {}, {}},
    {"simple.trk", 3, 8, {1, 2, 5}, kSimpleFirst, kSimpleLast},
    {"complex.trk", 3, 8, {1, 2, 5}, kSimpleFirst, kSimpleLast},
    {"complex_big_endian.trk", 3, 8, {1, 2, 5}, kSimpleFirst, kSimpleLast},
    {"standard.trk", 120, 360, {3, 3, 3}, kStandardFirst, kStandardLast},
    {"standard.LPS.trk", 120, 360, {3, 3, 3}, kStandardFirst, kStandardLast},
    {"empty.trk", 0, 0, {}, {}, {}},
};

void expectMatches(const Tractogram& t, const NibabelFile& f) {
    ASSERT_EQ(t.streamlineCount(), f.streamlines) << f.name;
    ASSERT_EQ(t.points.size(), f.points) << f.name;
    for (std::size_t s = 0; s < f.firstLengths.size(); ++s) EXPECT_EQ(t.pointCount(s), f.firstLengths[s]) << f.name << " streamline " << s;
    if (f.points == 0) return;
    for (int a = 0; a < 3; ++a) {
        EXPECT_NEAR(t.points.front()[a], f.first[a], 1e-6) << f.name << " first point, axis " << a;
        EXPECT_NEAR(t.points.back()[a], f.last[a], 1e-6) << f.name << " last point, axis " << a;
    }
}

TEST(NibabelTractograms, EachReadsAsNibabelReadsIt) {
    requireNibabelData();
    for (const NibabelFile& f : kReadable) {
        SCOPED_TRACE(f.name);
        expectMatches(io::readTractogram(kNibabel / f.name), f);
    }
}

TEST(NibabelTractograms, InnerPointsAndBoundsMatchNibabel) {
    requireNibabelData();
    // nibabel 5.0.0: streamline 1 point 1 is (3, 4, 5) in the simple/complex files; in the standard files
    // streamline 1 point 1 is (0, 0, 2), streamline 57 point 1 is (1, 12, 12), the bounds are (-0.5, -1.5, -1)
    // to (3.5, 13.5, 13); in matlab_nan.tck point 50 is (-0.12385104, -7.97723, 13.812924).
    for (const char* name : {"simple.tck", "complex.trk", "complex_big_endian.trk"}) {
        Tractogram t = io::readTractogram(kNibabel / name);
        EXPECT_EQ(t.points[t.offsets[1] + 1], glm::vec3(3, 4, 5)) << name;
        // complex.trk carries per-point scalars and per-streamline properties nibabel also reads.
    }
    for (const char* name : {"standard.tck", "standard.trk", "standard.LPS.trk"}) {
        Tractogram t = io::readTractogram(kNibabel / name);
        for (int a = 0; a < 3; ++a) {
            EXPECT_NEAR(t.points[t.offsets[1] + 1][a], glm::vec3(0, 0, 2)[a], 1e-6) << name;
            EXPECT_NEAR(t.points[t.offsets[57] + 1][a], glm::vec3(1, 12, 12)[a], 1e-6) << name;
        }
        glm::vec3 lo(1e9f), hi(-1e9f);
        for (glm::vec3 p : t.points) lo = glm::min(lo, p), hi = glm::max(hi, p);
        for (int a = 0; a < 3; ++a) {
            EXPECT_NEAR(lo[a], glm::vec3(-0.5f, -1.5f, -1)[a], 1e-6) << name;
            EXPECT_NEAR(hi[a], glm::vec3(3.5f, 13.5f, 13)[a], 1e-6) << name;
        }
    }
    Tractogram nan = io::readTractogram(kNibabel / "matlab_nan.tck");
    EXPECT_NEAR(nan.points[50].x, -0.12385103851556778, 1e-7);
    EXPECT_NEAR(nan.points[50].y, -7.977230072021484, 1e-6);
    EXPECT_NEAR(nan.points[50].z, 13.8129243850708, 1e-6);
}

TEST(NibabelTractograms, TheOnesNibabelRefusesAreRefusedNamingTheField) {
    requireNibabelData();
    // nibabel 5.0.0: HeaderError "Missing END in the header." (twice) and "Invalid magic number".
    struct Refused {
        const char* name;
        const char* field;
    };
    for (Refused r : {Refused{"no_header_end.tck", "header"}, Refused{"no_header_end_eof.tck", "header"},
                      Refused{"no_magic_number.tck", "magic"}}) {
        try {
            io::readTractogram(kNibabel / r.name);
            ADD_FAILURE() << r.name << " was read";
        } catch (const InputError& e) {
            EXPECT_EQ(e.field(), r.field) << e.what();
            EXPECT_NE(std::string(e.what()).find(r.name), std::string::npos) << e.what();
        }
    }
}

TEST(NibabelTractograms, MatlabsStaleCountIsAWarningAndTheDataIsRead) {
    requireNibabelData();
    Tractogram t;
    std::string warnings = warningsOf([&] { t = io::readTractogram(kNibabel / "matlab_nan.tck"); });
    EXPECT_EQ(t.streamlineCount(), 1u);
    EXPECT_NE(warnings.find("matlab_nan.tck"), std::string::npos) << warnings;
    EXPECT_NE(warnings.find("615000"), std::string::npos) << warnings;
}

// A .tck as MATLAB writers leave it: count 5 in the header, 3 streamlines in the data.
std::vector<std::uint8_t> staleCountTck() {
    std::string header = "mrtrix tracks\ndatatype: Float32LE\ncount: 5\nfile: . 64\nEND\n";
    header.resize(64, '\n');
    std::vector<std::uint8_t> b(header.begin(), header.end());
    auto triple = [&](float x, float y, float z) {
        for (float v : {x, y, z}) test::put<float>(b, v, false);
    };
    for (int s = 0; s < 3; ++s) {
        for (int i = 0; i <= s; ++i) triple(static_cast<float>(s), static_cast<float>(i), 1.5f);
        triple(NAN, NAN, NAN);
    }
    triple(INFINITY, INFINITY, INFINITY);
    return b;
}

TEST(Tck, AStaleHeaderCountWarnsNamingBothCountsAndReadsTheData) {
    fs::path path = test::scratchDirectory() / "stale-count.tck";
    test::writeBytes(path, staleCountTck());
    Tractogram t;
    std::string warnings = warningsOf([&] { t = io::readTractogram(path); });
    ASSERT_EQ(t.streamlineCount(), 3u);
    EXPECT_EQ(t.points.size(), 6u);
    EXPECT_EQ(t.pointCount(2), 3u);
    EXPECT_EQ(t.points[5], glm::vec3(2, 2, 1.5f));
    EXPECT_NE(warnings.find(path.string()), std::string::npos) << warnings;
    EXPECT_NE(warnings.find("count 5"), std::string::npos) << warnings;
    EXPECT_NE(warnings.find(" 3 streamlines"), std::string::npos) << warnings;
}

void expectSameTractogram(const Tractogram& a, const Tractogram& b, const std::string& what) {
    ASSERT_EQ(a.offsets, b.offsets) << what;
    ASSERT_EQ(a.points.size(), b.points.size()) << what;
    for (std::size_t i = 0; i < a.points.size(); ++i) ASSERT_EQ(a.points[i], b.points[i]) << what << " point " << i;
}

TEST(GzipTractograms, TrkGzAndTckGzReadAsTheirUncompressedFiles) {
    requireNibabelData();
    for (const char* name : {"standard.trk", "complex_big_endian.trk", "standard.tck", "matlab_nan.tck", "simple_big_endian.tck"}) {
        fs::path gz = test::scratchDirectory() / (std::string(name) + ".gz");
        test::writeBytes(gz, test::gzipBytes(readFileBytes(kNibabel / name)));
        Tractogram plain = io::readTractogram(kNibabel / name), unzipped = io::readTractogram(gz);
        expectSameTractogram(plain, unzipped, name);
        EXPECT_EQ(unzipped.scalars, plain.scalars) << name;
        EXPECT_EQ(unzipped.source, gz.string());
    }
    Tractogram standard = io::readTractogram(test::scratchDirectory() / "standard.trk.gz");
    expectMatches(standard, kReadable[9]);
}

TEST(GzipTractograms, CorruptOrUnknownCompressedFilesNameTheProblem) {
    fs::path dir = test::scratchDirectory();
    std::vector<std::uint8_t> gz = test::gzipBytes(staleCountTck());
    std::vector<std::uint8_t> cut(gz.begin(), gz.begin() + static_cast<std::ptrdiff_t>(gz.size() / 2));
    test::writeBytes(dir / "cut.tck.gz", cut);
    try {
        io::readTractogram(dir / "cut.tck.gz");
        ADD_FAILURE() << "a truncated gzip stream was read";
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), "gzip stream") << e.what();
    }
    test::writeBytes(dir / "plain.trk.gz", staleCountTck());  // not gzip at all
    EXPECT_THROW(io::readTractogram(dir / "plain.trk.gz"), InputError);
    test::writeBytes(dir / "volume.nii.gz", gz);
    try {
        io::readTractogram(dir / "volume.nii.gz");
        ADD_FAILURE() << "a .nii.gz was taken as a tractogram";
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), "extension") << e.what();
        EXPECT_NE(std::string(e.what()).find(".trx"), std::string::npos) << "the error lists the formats: " << e.what();
    }
}

// Seven streamlines of 1 to 31 points, every coordinate a multiple of 1/4 within +-120 mm, so float16
// (11 significant bits) holds it exactly and every dtype must give the same floats.
Tractogram exampleTractogram() {
    std::mt19937 random(7);
    std::uniform_int_distribution<int> quarter(-480, 480);
    Tractogram t;
    t.source = "example";
    for (std::size_t length : {1, 2, 31, 5, 3, 17, 8}) {
        for (std::size_t i = 0; i < length; ++i)
            t.points.emplace_back(static_cast<float>(quarter(random)) / 4, static_cast<float>(quarter(random)) / 4,
                                  static_cast<float>(quarter(random)) / 4);
        t.offsets.push_back(static_cast<std::uint32_t>(t.points.size()));
    }
    return t;
}

TEST(Trx, EveryDtypeOffsetsLengthAndCompressionReadsWhatWasWritten) {
    Tractogram written = exampleTractogram();
    fs::path dir = test::scratchDirectory();
    int cases = 0;
    for (std::string positions : {"float16", "float32", "float64"})
        for (std::string offsets : {"uint32", "uint64"})
            for (bool sentinel : {false, true})
                for (bool deflate : {false, true}) {
                    std::string name = positions + "-" + offsets + (sentinel ? "-n+1" : "-n") + (deflate ? "-deflated" : "-stored") + ".trx";
                    test::TrxMembers members = test::trxMembers(written, {positions, offsets, sentinel, true});
                    fs::path path = dir / name;
                    test::writeTrxZip(path, members, deflate);
                    std::map<std::string, int> methods = test::zipMethods(path);
                    ASSERT_EQ(methods.count("positions.3." + positions), 1u) << name;
                    EXPECT_EQ(methods["positions.3." + positions], deflate ? ZIP_CM_DEFLATE : ZIP_CM_STORE) << name;
                    Tractogram read = io::readTractogram(path);
                    expectSameTractogram(read, written, name);
                    EXPECT_EQ(read.source, path.string());
                    ++cases;
                }
    EXPECT_EQ(cases, 24);
}

TEST(Trx, TheFolderFormReadsAsTheZip) {
    Tractogram written = exampleTractogram();
    fs::path folder = test::scratchDirectory() / "folder.trx";
    test::writeTrxFolder(folder, test::trxMembers(written, {"float16", "uint32", false, true}));
    ASSERT_TRUE(fs::is_directory(folder / "dpv"));
    expectSameTractogram(io::readTractogram(folder), written, "folder.trx");
    // A folder is TRX whatever its name.
    fs::path plain = test::scratchDirectory() / "bundle";
    test::writeTrxFolder(plain, test::trxMembers(written, {"float64", "uint64", true, false}));
    expectSameTractogram(io::readTractogram(plain), written, "bundle/");
}

TEST(Trx, Float16SpecialValuesConvertExactly) {
    // Bit patterns and their values (IEEE 754 binary16): one, minus two, 1/3 rounded, the largest finite,
    // the smallest subnormal 2^-24, the largest subnormal 1023 * 2^-24, minus the smallest normal 2^-14,
    // zero and minus zero.
    std::vector<std::pair<std::uint16_t, float>> cases = {
        {0x3c00, 1.0f}, {0xc000, -2.0f}, {0x3555, 0.333251953125f}, {0x7bff, 65504.0f}, {0x0001, std::ldexp(1.0f, -24)},
        {0x03ff, 1023 * std::ldexp(1.0f, -24)}, {0x8400, -std::ldexp(1.0f, -14)}, {0x0000, 0.0f}, {0x8000, -0.0f}};
    test::TrxMembers m;
    m["header.json"] = test::textBytes(test::trxHeaderJson(1, 3));
    for (const auto& c : cases) test::appendLittle(m["positions.3.float16"], c.first);
    for (std::uint32_t o : {0u, 3u}) test::appendLittle(m["offsets.uint32"], o);
    fs::path path = test::scratchDirectory() / "halves.trx";
    test::writeTrxZip(path, m, false);
    Tractogram t = io::readTractogram(path);
    ASSERT_EQ(t.points.size(), 3u);
    for (std::size_t i = 0; i < cases.size(); ++i) {
        float got = t.points[i / 3][static_cast<int>(i % 3)];
        EXPECT_EQ(got, cases[i].second) << std::hex << cases[i].first;
        EXPECT_EQ(std::signbit(got), std::signbit(cases[i].second)) << std::hex << cases[i].first;
    }
    // Inf and NaN are not coordinates.
    m["positions.3.float16"][0] = 0x00, m["positions.3.float16"][1] = 0x7c;
    test::writeTrxZip(path, m, false);
    EXPECT_THROW(io::readTractogram(path), InputError);
}

struct TrxError {
    std::string what;
    test::TrxMembers members;
    std::string field;  // the field the error must name
};

TEST(Trx, MalformedArchivesNameTheirField) {
    Tractogram t = exampleTractogram();  // 7 streamlines, 67 points
    test::TrxMembers good = test::trxMembers(t);
    auto with = [&](auto change) {
        test::TrxMembers m = good;
        change(m);
        return m;
    };
    auto setOffset = [](test::TrxMembers& m, std::size_t i, std::uint64_t v) { std::memcpy(m["offsets.uint64"].data() + 8 * i, &v, 8); };
    auto rename = [](test::TrxMembers& m, const std::string& from, const std::string& to) {
        m[to] = m[from];
        m.erase(from);
    };
    std::vector<TrxError> cases = {
        {"no header", with([](auto& m) { m.erase("header.json"); }), "header.json"},
        {"header only in a sub-folder", with([&](auto& m) { rename(m, "header.json", "x/header.json"); }), "header.json"},
        {"header not JSON", with([](auto& m) { m["header.json"] = test::textBytes("{\"NB_STREAMLINES\": 7,"); }), "line 1, column 22"},
        {"header not an object", with([](auto& m) { m["header.json"] = test::textBytes("[1, 2]"); }), ""},
        {"no NB_VERTICES", with([](auto& m) { m["header.json"] = test::textBytes(R"({"VOXEL_TO_RASMM": [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]], "DIMENSIONS": [1,1,1], "NB_STREAMLINES": 7})"); }), "NB_VERTICES"},
        {"no affine", with([](auto& m) { m["header.json"] = test::textBytes(R"({"DIMENSIONS": [1,1,1], "NB_STREAMLINES": 7, "NB_VERTICES": 67})"); }), "VOXEL_TO_RASMM"},
        {"NB_VERTICES disagrees with positions", with([](auto& m) { m["header.json"] = test::textBytes(test::trxHeaderJson(7, 66)); }), "positions.3.float32"},
        {"NB_STREAMLINES disagrees with offsets", with([](auto& m) { m["header.json"] = test::textBytes(test::trxHeaderJson(9, 67)); }), "offsets.uint64"},
        {"vertices without streamlines", with([](auto& m) { m["header.json"] = test::textBytes(test::trxHeaderJson(0, 67)); }), "NB_VERTICES"},
        {"positions cut short", with([](auto& m) { m["positions.3.float32"].resize(66 * 12 + 4); }), "positions.3.float32"},
        {"no positions", with([](auto& m) { m.erase("positions.3.float32"); }), "positions"},
        {"two positions arrays", with([&](auto& m) { m["positions.3.float64"] = std::vector<std::uint8_t>(67 * 24); }), "positions"},
        {"positions of an unknown dtype", with([&](auto& m) { rename(m, "positions.3.float32", "positions.3.int32"); }), "positions.3.int32"},
        {"positions with 2 columns", with([&](auto& m) { rename(m, "positions.3.float32", "positions.2.float32"); }), "positions.2.float32"},
        {"a NaN position", with([](auto& m) { float nan = NAN; std::memcpy(m["positions.3.float32"].data() + 12 * 4 + 4, &nan, 4); }), "positions.3.float32 vertex 4"},
        {"no offsets", with([](auto& m) { m.erase("offsets.uint64"); }), "offsets"},
        {"offsets of an unknown dtype", with([&](auto& m) { rename(m, "offsets.uint64", "offsets.float64"); }), "offsets.float64"},
        {"offsets not starting at 0", with([&](auto& m) { setOffset(m, 0, 1); }), "offsets.uint64[0]"},
        {"offsets out of order", with([&](auto& m) { setOffset(m, 3, 2); }), "offsets.uint64[3]"},
        {"offsets out of range", with([&](auto& m) { setOffset(m, 6, 68); }), "offsets.uint64[6]"},
        {"an N+1 sentinel that is not NB_VERTICES", with([&](auto& m) { setOffset(m, 7, 66); }), "offsets.uint64[7]"},
    };
    fs::path path = test::scratchDirectory() / "bad.trx";
    for (const TrxError& c : cases)
        for (bool folder : {false, true}) {
            fs::path where = folder ? test::scratchDirectory() / "bad-folder" : path;
            if (folder) {
                test::writeTrxFolder(where, c.members);
            } else {
                test::writeTrxZip(where, c.members, true);
            }
            try {
                io::readTractogram(where);
                ADD_FAILURE() << c.what << " was read";
            } catch (const InputError& e) {
                if (!c.field.empty()) {
                    EXPECT_EQ(e.field(), c.field) << c.what << ": " << e.what();
                }
                EXPECT_NE(std::string(e.what()).find(where.string()), std::string::npos) << c.what << ": " << e.what();
                EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "one line: " << e.what();
            }
        }
}

TEST(Trx, DamagedZipsAreRefused) {
    Tractogram t = exampleTractogram();
    fs::path dir = test::scratchDirectory();
    test::writeTrxZip(dir / "stored.trx", test::trxMembers(t), false);
    std::vector<std::uint8_t> bytes = readFileBytes(dir / "stored.trx");
    auto refused = [](const std::vector<std::uint8_t>& b, const std::string& field) {
        try {
            io::readTrxZipBytes(b, "damaged.trx");
            ADD_FAILURE() << "read a damaged zip (expected " << field << ")";
        } catch (const InputError& e) {
            EXPECT_EQ(e.field(), field) << e.what();
        }
    };
    refused(std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(bytes.size() / 2)), "zip archive");
    refused(test::textBytes("mrtrix tracks\n"), "zip archive");
    // One flipped bit inside the stored positions: the CRC-32 check must catch it.
    std::vector<std::uint8_t> flipped = bytes;
    std::vector<std::uint8_t> positions = test::trxMembers(t)["positions.3.float32"];
    auto at = std::search(flipped.begin(), flipped.end(), positions.begin(), positions.begin() + 24);
    ASSERT_NE(at, flipped.end());
    at[13] ^= 0x10;
    refused(flipped, "positions.3.float32");
    // No entries at all: an empty zip has no header.
    refused({}, "header.json");
}

TEST(Trx, ANibabelTrkWrittenAsTrxReadsBackWithNibabelsValues) {
    requireNibabelData();
    const NibabelFile& standard = kReadable[9];
    ASSERT_STREQ(standard.name, "standard.trk");
    Tractogram trk = io::readTractogram(kNibabel / standard.name);
    for (bool deflate : {false, true}) {
        fs::path path = test::scratchDirectory() / (deflate ? "standard-deflated.trx" : "standard-stored.trx");
        test::writeTrxZip(path, test::trxMembers(trk), deflate);
        Tractogram trx = io::readTractogram(path);
        expectSameTractogram(trx, trk, path.string());
        expectMatches(trx, standard);
    }
}

// The fuzz seeds (tests/fuzz/corpus/trx/) are two archives these helpers write: a stored one with float32
// positions and N + 1 uint64 offsets, and a deflated one with float16 positions and N uint32 offsets. This
// checks the committed seeds still read as that; to regenerate them, copy the files this test writes into
// $TMPDIR/curette-io-<pid>/ over the corpus.
Tractogram seedTractogram() {
    Tractogram t;
    t.source = "seed";
    t.points = {{1, 2, 3}, {4, 5, 6.5f}, {-1, -2, -3}, {0, 0.25f, 8}, {7, 8, 9}};
    t.offsets = {0, 2, 5};
    return t;
}

TEST(Trx, TheFuzzSeedsAreTheArchivesTheseTestsWrite) {
    fs::path dir = test::scratchDirectory();
    test::writeTrxZip(dir / "stored-float32-uint64.trx", test::trxMembers(seedTractogram(), {"float32", "uint64", true, true}), false);
    test::writeTrxZip(dir / "deflated-float16-uint32.trx", test::trxMembers(seedTractogram(), {"float16", "uint32", false, false}), true);
    for (const char* name : {"stored-float32-uint64.trx", "deflated-float16-uint32.trx"}) {
        fs::path seed = fs::path(CURETTE_SOURCE_DIR) / "tests/fuzz/corpus/trx" / name;
        ASSERT_TRUE(fs::exists(seed)) << seed;
        EXPECT_LE(fs::file_size(seed), 4096u) << "run_fuzzer's -max_len";
        expectSameTractogram(io::readTractogram(seed), seedTractogram(), name);
        expectSameTractogram(io::readTractogram(dir / name), seedTractogram(), name);
    }
}

}  // namespace
}  // namespace curette
