// A scene's "tubes" may name any tract format the readers take: `curette render` on a tiny scene whose tubes
// are a .trx zip, a TRX folder and a .tck.gz draws them (the plan has the tube passes, and the image differs
// from the scene without tubes); a broken .trx is one error line naming the file and the field, exit 2, no PNG.
#include "tests/tools/run_curette.h"
#include "tests/io/io_test_support.h"
#include "tests/tracts/trx_test_writer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

namespace curette {
namespace {

namespace fs = std::filesystem;
using testing::Invocation;
using testing::runCurette;

fs::path scratch() {
    fs::path dir = fs::temp_directory_path() / ("curette-tract-cli-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    return dir;
}

// Three streamlines crossing the middle of the 16^3 x 4 mm volume below (world 0..60 mm).
Tractogram crossingTracts() {
    Tractogram t;
    t.source = "crossing";
    for (int axis = 0; axis < 3; ++axis) {
        for (int i = 0; i <= 10; ++i) {
            glm::vec3 p(30.0f);
            p[axis] = 10.0f + 4.0f * static_cast<float>(i);
            t.points.push_back(p);
        }
        t.offsets.push_back(static_cast<std::uint32_t>(t.points.size()));
    }
    return t;
}

std::vector<std::uint8_t> tckBytes(const Tractogram& t) {
    std::string header = "mrtrix tracks\ndatatype: Float32LE\ncount: " + std::to_string(t.streamlineCount()) + "\nfile: . 80\nEND\n";
    header.resize(80, '\n');
    std::vector<std::uint8_t> b(header.begin(), header.end());
    for (std::size_t s = 0; s < t.streamlineCount(); ++s) {
        for (std::uint32_t i = t.offsets[s]; i < t.offsets[s + 1]; ++i)
            for (int a = 0; a < 3; ++a) test::put<float>(b, t.points[i][a], false);
        for (int a = 0; a < 3; ++a) test::put<float>(b, NAN, false);
    }
    for (int a = 0; a < 3; ++a) test::put<float>(b, INFINITY, false);
    return b;
}

// A faint 16^3 ball (so the tubes show through) and, when `tubes` names a file, tubes from it.
fs::path writeScene(const fs::path& dir, const std::string& name, const std::string& tubes) {
    std::vector<std::uint8_t> voxels(16 * 16 * 16);
    for (int z = 0; z < 16; ++z)
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x) {
                double r = std::sqrt((x - 7.5) * (x - 7.5) + (y - 7.5) * (y - 7.5) + (z - 7.5) * (z - 7.5));
                voxels[static_cast<std::size_t>((z * 16 + y) * 16 + x)] = r < 6 ? 120 : 0;
            }
    test::writeBytes(dir / "ball.raw", voxels);
    std::string text = R"({
  "volume": {"path": "ball.raw", "format": "raw", "raw": {"dims": [16, 16, 16], "type": "uint8", "spacing": [4, 4, 4]}},
  "transfer_function": {"color": [[0, 0, 0, 0], [255, 0.8, 0.7, 0.6]], "opacity": [[0, 0], [100, 0.02], [255, 0.05]]},
  "camera": {"target": "center", "distance_mm": 200, "azimuth_deg": 30, "elevation_deg": 20, "fov_deg": 30},
  "shading": "phong",
  "image": {"width": 32, "height": 32})";
    if (!tubes.empty()) text += ",\n  \"tubes\": [{\"path\": \"" + tubes + "\", \"radius_mm\": 2.0, \"sides\": 6}]";
    text += "\n}\n";
    std::ofstream(dir / name) << text;
    return dir / name;
}

std::vector<char> fileBytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(TractFormatsCli, ASceneCanNameATrxZipATrxFolderOrATckGzAsTubes) {
    fs::path dir = scratch();
    Tractogram tracts = crossingTracts();
    test::TrxMembers members = test::trxMembers(tracts);
    test::writeTrxZip(dir / "crossing.trx", members, true);
    test::writeTrxFolder(dir / "crossing-folder.trx", members);
    test::writeBytes(dir / "crossing.tck.gz", test::gzipBytes(tckBytes(tracts)));

    fs::path bare = writeScene(dir, "bare.json", "");
    Invocation none = runCurette("render --scene " + bare.string() + " --size 32x32 --out " + (dir / "bare.png").string());
    ASSERT_EQ(none.exitCode, 0) << none.output;
    std::vector<char> barePng = fileBytes(dir / "bare.png");

    std::vector<std::vector<char>> pngs;
    for (const char* tubes : {"crossing.trx", "crossing-folder.trx", "crossing.tck.gz"}) {
        fs::path scene = writeScene(dir, std::string(tubes) + ".json", tubes);
        Invocation plan = runCurette("render --scene " + scene.string() + " --size 32x32 --plan");
        ASSERT_EQ(plan.exitCode, 0) << tubes << "\n" << plan.output;
        EXPECT_NE(plan.output.find("tubes G-buffer"), std::string::npos) << tubes << " gave no tubes:\n" << plan.output;
        fs::path png = dir / (std::string(tubes) + ".png");
        Invocation r = runCurette("render --scene " + scene.string() + " --size 32x32 --out " + png.string());
        ASSERT_EQ(r.exitCode, 0) << tubes << "\n" << r.output;
        pngs.push_back(fileBytes(png));
        EXPECT_FALSE(pngs.back().empty()) << tubes;
        EXPECT_NE(pngs.back(), barePng) << tubes << ": the tubes are not in the image";
    }
    // The same streamlines from three containers draw the same image.
    EXPECT_EQ(pngs[0], pngs[1]);
    EXPECT_EQ(pngs[0], pngs[2]);
}

TEST(TractFormatsCli, ABrokenTrxIsOneErrorLineNamingTheFileAndTheField) {
    fs::path dir = scratch();
    test::TrxMembers members = test::trxMembers(crossingTracts());
    members.erase("offsets.uint64");
    test::writeTrxZip(dir / "broken.trx", members, false);
    fs::path scene = writeScene(dir, "broken.json", "broken.trx");
    fs::path png = dir / "broken.png";
    fs::remove(png);
    Invocation r = runCurette("render --scene " + scene.string() + " --size 32x32 --out " + png.string());
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("broken.trx: offsets: expected"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(png)) << "no partial output";
}

}  // namespace
}  // namespace curette
