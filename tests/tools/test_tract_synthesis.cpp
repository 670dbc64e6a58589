// The whole-brain-scale tractogram synthesiser (tools/tract_synthesis.h) and `curette tracts synth`: exact
// counts, every copy within the jitter bound of its source (and not on it), deterministic per seed, the
// N-copy synthesis a prefix of any larger one; and `curette bench tracts` at a tiny size writes its JSON.
#include "io/tck_writer.h"
#include "io/tract_file.h"
#include "tools/tract_synthesis.h"
#include "tests/tools/run_curette.h"
#include "tests/io/io_test_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

namespace curette {
namespace {

namespace fs = std::filesystem;
using testing::Invocation;
using testing::runCurette;

fs::path scratch() {
    fs::path dir = fs::temp_directory_path() / ("curette-synth-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    return dir;
}

// Two bundles of 3 and 4 arcs in a 60 mm box, 5-12 points each (unevenly spaced).
std::vector<Tractogram> bundles() {
    std::vector<Tractogram> out(2);
    for (int b = 0; b < 2; ++b) {
        out[b].source = "bundle" + std::to_string(b);
        for (int s = 0; s < 3 + b; ++s) {
            int n = 5 + 2 * s + b;
            for (int i = 0; i < n; ++i) {
                double x = std::pow(double(i) / (n - 1), 1.3);
                out[b].points.emplace_back(glm::vec3(10.0 + 40.0 * x, 30.0 + 10.0 * std::sin(3.0 * x + s) + 5.0 * b, 30.0 + 3.0 * s));
            }
            out[b].offsets.push_back(static_cast<std::uint32_t>(out[b].points.size()));
        }
    }
    return out;
}

std::vector<char> fileBytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(TractSynthesis, CountsAreExactAndCopiesFollowTheirSourcesInTurn) {
    std::vector<Tractogram> sources = bundles();
    TractSynthesisSettings settings;
    settings.count = 1003;
    Tractogram t = synthesiseTracts(sources, settings);
    ASSERT_EQ(t.streamlineCount(), 1003u);
    std::vector<std::size_t> sourceCounts;
    for (const Tractogram& b : sources)
        for (std::size_t s = 0; s < b.streamlineCount(); ++s) sourceCounts.push_back(b.pointCount(s));
    for (std::size_t i = 0; i < t.streamlineCount(); ++i) ASSERT_EQ(t.pointCount(i), sourceCounts[i % sourceCounts.size()]) << "copy " << i;
    EXPECT_EQ(t.points.size(), t.offsets.back());
}

TEST(TractSynthesis, EveryPointStaysWithinTheJitterBoundAndCopiesDoNotCoincide) {
    std::vector<Tractogram> sources = bundles();
    Tractogram flat;
    for (const Tractogram& b : sources) flat.append(b);
    for (double jitter : {0.5, 3.0}) {
        TractSynthesisSettings settings;
        settings.count = 700;
        settings.jitterMm = jitter;
        Tractogram t = synthesiseTracts(sources, settings);
        double worst = 0, meanOffset = 0;
        double closestCopies = 1e30;   // the closest two copies of one source come, as their mean point distance
        for (std::size_t i = 0; i < t.streamlineCount(); ++i) {
            std::size_t s = i % flat.streamlineCount();
            double sum = 0;
            for (std::size_t k = 0; k < t.pointCount(i); ++k) {
                double d = glm::distance(glm::dvec3(t.points[t.offsets[i] + k]), glm::dvec3(flat.points[flat.offsets[s] + k]));
                worst = std::max(worst, d);
                sum += d;
            }
            meanOffset += sum / double(t.pointCount(i));
            if (i >= flat.streamlineCount()) {
                std::size_t j = i - flat.streamlineCount();  // the previous copy of the same source
                double between = 0;
                for (std::size_t k = 0; k < t.pointCount(i); ++k)
                    between += glm::distance(t.points[t.offsets[i] + k], t.points[t.offsets[j] + k]);
                closestCopies = std::min(closestCopies, between / double(t.pointCount(i)));
            }
        }
        meanOffset /= double(t.streamlineCount());
        EXPECT_LE(worst, jitter + 1e-4) << "jitter " << jitter;      // float rounding of ~60 mm coordinates
        EXPECT_GT(worst, 0.6 * jitter) << "jitter " << jitter << ": the bound is far from used";
        EXPECT_GT(meanOffset, 0.15 * jitter) << "jitter " << jitter;
        EXPECT_GT(closestCopies, 1e-3 * jitter) << "jitter " << jitter << ": two copies of one source coincide";
        // The displacement bends the copy: it is not one rigid offset per copy.
        glm::dvec3 start = synthesisDisplacement(settings.seed, 5, jitter, 0.0), end = synthesisDisplacement(settings.seed, 5, jitter, 1.0);
        EXPECT_GT(glm::distance(start, end), 1e-3 * jitter);
    }
}

// The bound itself, over many more copies than a tractogram test can afford: |d(u)| <= J everywhere, and
// copies come close to it (the bound is the displacement's, not a loose one).
TEST(TractSynthesis, TheDisplacementNeverExceedsTheBoundAndComesNearIt) {
    const double jitter = 2.0;
    double largest = 0;
    for (std::size_t copy = 0; copy < 20000; ++copy)
        for (int k = 0; k <= 20; ++k) largest = std::max(largest, glm::length(synthesisDisplacement(9, copy, jitter, k / 20.0)));
    EXPECT_LE(largest, jitter);
    EXPECT_GT(largest, 0.8 * jitter);
}

TEST(TractSynthesis, TheFirstCopiesOfALargerSynthesisAreTheSmallerOne) {
    std::vector<Tractogram> sources = bundles();
    TractSynthesisSettings small, large;
    small.count = 50;
    large.count = 400;
    Tractogram a = synthesiseTracts(sources, small), b = synthesiseTracts(sources, large);
    ASSERT_EQ(std::vector<glm::vec3>(b.points.begin(), b.points.begin() + a.points.size()), a.points);
}

TEST(TractSynthesisCli, SameSeedSameFileDifferentSeedsDiffer) {
    fs::path dir = scratch();
    std::vector<Tractogram> sources = bundles();
    fs::create_directories(dir / "bundles" / "sub");
    io::writeTck(dir / "bundles" / "a.tck", sources[0]);
    io::writeTck(dir / "bundles" / "sub" / "b.tck", sources[1]);
    auto synth = [&](const std::string& name, int seed) {
        Invocation r = runCurette("tracts synth --from " + (dir / "bundles").string() + " --count 300 --seed " + std::to_string(seed) +
                                  " --jitter 2 --out " + (dir / name).string());
        EXPECT_EQ(r.exitCode, 0) << r.output;
        return fileBytes(dir / name);
    };
    std::vector<char> first = synth("s7.tck", 7), again = synth("s7-again.tck", 7), other = synth("s8.tck", 8);
    ASSERT_FALSE(first.empty());
    EXPECT_EQ(first, again);
    EXPECT_NE(first, other);
    Tractogram read = io::readTractogram(dir / "s7.tck");
    EXPECT_EQ(read.streamlineCount(), 300u);
    EXPECT_EQ(read.pointCount(0), sources[0].pointCount(0)) << "a.tck sorts before sub/b.tck";
    EXPECT_EQ(read.pointCount(3), sources[1].pointCount(0));
}

TEST(TractSynthesisCli, TheExtensionPicksTheFormatAndEachReadsAsTheTck) {
    fs::path dir = scratch();
    io::writeTck(dir / "one.tck", bundles()[0]);
    std::map<std::string, Tractogram> read;
    for (const char* extension : {".tck", ".trk", ".trx"}) {
        fs::path out = dir / (std::string("synth") + extension);
        Invocation r = runCurette("tracts synth --from " + (dir / "one.tck").string() + " --count 40 --seed 3 --out " + out.string());
        ASSERT_EQ(r.exitCode, 0) << r.output;
        read[extension] = io::readTractogram(out);
    }
    std::vector<char> trk = fileBytes(dir / "synth.trk"), trx = fileBytes(dir / "synth.trx");
    ASSERT_GE(trk.size(), 1000u);
    EXPECT_EQ(std::string(trk.data(), 5), "TRACK");
    EXPECT_EQ(std::string(trx.data(), 4), std::string("PK\3\4", 4)) << "a zip";
    const Tractogram& tck = read[".tck"];
    ASSERT_EQ(tck.streamlineCount(), 40u);
    EXPECT_EQ(read[".trx"].offsets, tck.offsets);
    EXPECT_EQ(read[".trx"].points, tck.points) << "TRX holds the float32 points as .tck does";
    ASSERT_EQ(read[".trk"].offsets, tck.offsets);
    for (std::size_t p = 0; p < tck.points.size(); ++p)  // .trk: float32 voxmm in a grid of a few hundred mm
        ASSERT_LT(glm::length(read[".trk"].points[p] - tck.points[p]), 1e-4f) << p;
}

TEST(TractSynthesisCli, BadArgumentsAreOneErrorLineAndNoFile) {
    fs::path dir = scratch();
    io::writeTck(dir / "one.tck", bundles()[0]);
    fs::path out = dir / "out.vtk";
    Invocation wrongFormat = runCurette("tracts synth --from " + (dir / "one.tck").string() + " --count 10 --out " + out.string());
    EXPECT_EQ(wrongFormat.exitCode, 2) << wrongFormat.output;
    EXPECT_NE(wrongFormat.output.find("--out: expected a .tck, .trk or .trx file name"), std::string::npos) << wrongFormat.output;
    EXPECT_FALSE(fs::exists(out));
    Invocation missing = runCurette("tracts synth --from " + (dir / "nowhere").string() + " --out " + (dir / "x.tck").string());
    EXPECT_EQ(missing.exitCode, 2) << missing.output;
    EXPECT_NE(missing.output.find("nowhere"), std::string::npos) << missing.output;
    EXPECT_FALSE(fs::exists(dir / "x.tck"));
}

TEST(BenchTracts, RunsAtATinySizeAndWritesItsJson) {
    fs::path dir = scratch();
    io::writeTck(dir / "source.tck", bundles()[1]);
    ASSERT_EQ(runCurette("tracts synth --from " + (dir / "source.tck").string() + " --count 120 --out " + (dir / "many.tck").string()).exitCode, 0);
    std::vector<std::uint8_t> voxels(16 * 16 * 16);
    for (int z = 0; z < 16; ++z)
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x) voxels[static_cast<std::size_t>((z * 16 + y) * 16 + x)] = (x - 7.5) * (x - 7.5) + (y - 7.5) * (y - 7.5) + (z - 7.5) * (z - 7.5) < 36 ? 120 : 0;
    test::writeBytes(dir / "ball.raw", voxels);
    std::ofstream(dir / "scene.json") << R"({
  "volume": {"path": "ball.raw", "format": "raw", "raw": {"dims": [16, 16, 16], "type": "uint8", "spacing": [4, 4, 4]}},
  "transfer_function": {"color": [[0, 0, 0, 0], [255, 0.8, 0.7, 0.6]], "opacity": [[0, 0], [100, 0.02], [255, 0.05]]},
  "camera": {"target": "center", "distance_mm": 200, "azimuth_deg": 30, "elevation_deg": 20, "fov_deg": 30},
  "shading": "dos",
  "tubes": [{"path": "many.tck", "radius_mm": 0.8, "sides": 6, "step_mm": 1.0}]
})";
    fs::path json = dir / "bench.json";
    Invocation r = runCurette("bench tracts --scene " + (dir / "scene.json").string() + " --counts 40,120 --size 32x32 --frames 1 --json " + json.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    std::ifstream in(json);
    nlohmann::json doc = nlohmann::json::parse(in);
    ASSERT_EQ(doc.at("rows").size(), 8u) << "lines, CPU tubes, GPU tubes and impostors at two counts";
    for (const nlohmann::json& row : doc.at("rows")) {
        EXPECT_GT(row.at("gpu_bytes").get<double>(), 0) << row.dump();
        EXPECT_GT(row.at("bytes_per_streamline").get<double>(), 0) << row.dump();
        EXPECT_GT(row.at("vertices").get<double>(), 0) << row.dump();
        EXPECT_GT(row.at("frame_ms").at("phong").get<double>(), 0) << row.dump();
        EXPECT_GT(row.at("frame_ms").at("dos").get<double>(), 0) << row.dump();
        EXPECT_TRUE(row.contains("build_total_ms")) << row.dump();
    }
    const nlohmann::json& gpu = doc.at("rows")[6];
    EXPECT_EQ(gpu.at("geometry"), "tubes (GPU)");
    EXPECT_EQ(gpu.at("streamlines"), 120);
    EXPECT_EQ(gpu.at("indices_and_colors_equal"), "yes");
    EXPECT_LT(gpu.at("max_vertex_error_mm").get<double>(), 1e-3);
    EXPECT_EQ(gpu.at("vertices"), doc.at("rows")[5].at("vertices")) << "the GPU builds what the CPU builds";
    EXPECT_EQ(doc.at("rows")[4].at("vertices").get<double>() < doc.at("rows")[5].at("vertices").get<double>(), true) << "lines are lighter than tubes";
    const nlohmann::json& impostors = doc.at("rows")[7];
    EXPECT_EQ(impostors.at("geometry"), "impostors");
    EXPECT_LT(impostors.at("bytes_per_streamline").get<double>(), gpu.at("bytes_per_streamline").get<double>()) << "impostors hold points, not rings";
    EXPECT_NE(r.output.find("bytes/streamline"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace curette
