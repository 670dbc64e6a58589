// The volume formats as a user meets them: `curette info` and `curette render` on 4-D NIfTI-1 and NIfTI-2 files
// (nibabel's test data), a MetaImage file, a volume with NaN voxels ("no data"), and the statistics `info`
// prints, which leave those voxels out.
#include "scene/volume_statistics.h"
#include "tests/tools/run_curette.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

namespace {

using curette::testing::Invocation;
Invocation run(const std::string& arguments) { return curette::testing::runCurette(arguments); }

const std::string kSource = CURETTE_SOURCE_DIR;
const std::string kNibabel = "/usr/local/share/curette/nibabel-data";

std::filesystem::path scratch() {
    auto dir = std::filesystem::temp_directory_path() / ("curette-formats-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    return dir;
}

void writeText(const std::filesystem::path& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
}

int count(const std::string& text, const std::string& what) {
    int n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

TEST(VolumeFormatsCli, InfoShowsWhichVolumeOfA4DFile) {
    ASSERT_TRUE(std::filesystem::exists(kNibabel + "/example4d.nii.gz")) << "run scripts/setup (nibabel's test data)";
    Invocation first = run("info " + kNibabel + "/example4d.nii.gz");
    ASSERT_EQ(first.exitCode, 0) << first.output;
    EXPECT_NE(first.output.find("128 x 96 x 24"), std::string::npos) << first.output;
    EXPECT_NE(first.output.find("volumes      2 (showing index 0, --volume N)"), std::string::npos) << first.output;
    EXPECT_NE(first.output.find("max 1162"), std::string::npos) << first.output;  // nibabel 5.0.0: volume 0 max 1162

    Invocation second = run("info " + kNibabel + "/example4d.nii.gz --volume 1");
    ASSERT_EQ(second.exitCode, 0) << second.output;
    EXPECT_NE(second.output.find("volumes      2 (showing index 1, --volume N)"), std::string::npos) << second.output;
    EXPECT_NE(second.output.find("max 1140"), std::string::npos) << second.output;  // nibabel 5.0.0: volume 1 max 1140

    // NIfTI-2, and a 3-D file, which has no volumes line.
    Invocation nifti2 = run("info " + kNibabel + "/example_nifti2.nii.gz --volume 1");
    ASSERT_EQ(nifti2.exitCode, 0) << nifti2.output;
    EXPECT_NE(nifti2.output.find("32 x 20 x 12"), std::string::npos) << nifti2.output;
    EXPECT_NE(nifti2.output.find("min 46  max 757"), std::string::npos) << nifti2.output;  // nibabel 5.0.0, volume 1
    Invocation threeD = run("info " + kNibabel + "/anatomical.nii");
    ASSERT_EQ(threeD.exitCode, 0) << threeD.output;
    EXPECT_EQ(threeD.output.find("volumes "), std::string::npos) << threeD.output;

    Invocation beyond = run("info " + kNibabel + "/example4d.nii.gz --volume 2");
    EXPECT_EQ(beyond.exitCode, 2) << beyond.output;
    EXPECT_EQ(count(beyond.output, "\n"), 1) << "one error line: " << beyond.output;
    EXPECT_NE(beyond.output.find("--volume"), std::string::npos) << beyond.output;
    EXPECT_NE(beyond.output.find("volume.index"), std::string::npos) << beyond.output;
    EXPECT_NE(beyond.output.find("2 volumes"), std::string::npos) << beyond.output;
}

TEST(VolumeFormatsCli, RenderOpensAVolumeOfA4DFileByItsSceneIndex) {
    ASSERT_TRUE(std::filesystem::exists(kNibabel + "/example_nifti2.nii.gz")) << "run scripts/setup (nibabel's test data)";
    auto dir = scratch();
    auto scene = [&](const std::string& file, int index) {
        std::string name = "scene-" + std::to_string(index) + ".json";
        writeText(dir / name, "{\n  \"volume\": {\"path\": \"" + kNibabel + "/" + file + "\", \"index\": " + std::to_string(index) +
                                  "},\n  \"transfer_function\": \"" + kSource + "/assets/tf/mri_t1.json\",\n  \"shading\": \"phong\"\n}\n");
        return dir / name;
    };
    for (const char* file : {"example_nifti2.nii.gz", "example4d.nii.gz"}) {
        auto out = dir / (std::string(file) + ".png");
        std::filesystem::remove(out);
        Invocation ok = run("render --scene " + scene(file, 1).string() + " --out " + out.string() + " --size 32x32");
        ASSERT_EQ(ok.exitCode, 0) << file << ": " << ok.output;
        std::ifstream png(out, std::ios::binary);
        char magic[8] = {};
        png.read(magic, 8);
        EXPECT_EQ(std::string(magic + 1, 3), "PNG") << file;
    }
    auto bad = dir / "beyond.png";
    std::filesystem::remove(bad);
    Invocation beyond = run("render --scene " + scene("example_nifti2.nii.gz", 2).string() + " --out " + bad.string() + " --size 32x32");
    EXPECT_EQ(beyond.exitCode, 2) << beyond.output;
    EXPECT_NE(beyond.output.find("volume.index"), std::string::npos) << beyond.output;
    EXPECT_NE(beyond.output.find("2 volumes"), std::string::npos) << beyond.output;
    EXPECT_FALSE(std::filesystem::exists(bad)) << "no partial output";
}

TEST(VolumeFormatsCli, InfoCountsNoDataVoxelsAndWarnsOnce) {
    ASSERT_TRUE(std::filesystem::exists(kNibabel + "/resampled_anat_moved.nii")) << "run scripts/setup (nibabel's test data)";
    // The tests run with CURETTE_LOG=error; the warning needs warn.
    const char* previous = std::getenv("CURETTE_LOG");
    std::string saved = previous ? previous : "";
    ::setenv("CURETTE_LOG", "warn", 1);
    Invocation r = run("info " + kNibabel + "/resampled_anat_moved.nii");
    if (previous) ::setenv("CURETTE_LOG", saved.c_str(), 1);
    else ::unsetenv("CURETTE_LOG");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    // nibabel 5.0.0: 153 NaN voxels; nanmin 409.3004455566406, nanmax 13360.9619140625.
    EXPECT_NE(r.output.find("no data      153 voxels (NaN/Inf): transparent"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("min 409.3  max 13361"), std::string::npos) << r.output;
    EXPECT_EQ(count(r.output, "are NaN or Inf"), 1) << "warned once: " << r.output;
}

TEST(VolumeFormatsCli, InfoReadsAMetaImage) {
    auto path = scratch() / "tiny.mha";
    std::string header =
        "ObjectType = Image\nNDims = 3\nDimSize = 2 2 2\nElementType = MET_SHORT\nElementSpacing = 0.5 0.5 2\n"
        "Offset = 10 20 30\nTransformMatrix = 1 0 0 0 1 0 0 0 1\nBinaryDataByteOrderMSB = False\nElementDataFile = LOCAL\n";
    std::vector<std::int16_t> values = {-5, 0, 1, 2, 3, 4, 5, 700};
    std::string bytes = header;
    bytes.append(reinterpret_cast<const char*>(values.data()), values.size() * 2);
    writeText(path, bytes);
    Invocation r = run("info " + path.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("2 x 2 x 2"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("min -5  max 700"), std::string::npos) << r.output;
    // LPS Offset (10, 20, 30) is RAS (-10, -20, 30); the x and y spacings flip sign.
    EXPECT_NE(r.output.find("[   -0.5000    0.0000    0.0000   -10.0000 ]"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("[    0.0000    0.0000    2.0000    30.0000 ]"), std::string::npos) << r.output;

    writeText(path, "NDims = 3\nDimSize = 2 2 2\nElementType = MET_SHORT\nElementNumberOfChannels = 3\nElementDataFile = LOCAL\n");
    Invocation vector = run("info " + path.string());
    EXPECT_EQ(vector.exitCode, 2) << vector.output;
    EXPECT_NE(vector.output.find("ElementNumberOfChannels"), std::string::npos) << vector.output;
}

// A volume longer than llvmpipe's 3D texture limit (2048): `info` says how the renderer will fold it, GL-free,
// for the default limit and a stated one.
TEST(VolumeFormatsCli, InfoSaysHowAVolumeOverTheTextureLimitIsStored) {
    auto path = scratch() / "thin.mha";
    std::string bytes = "NDims = 3\nDimSize = 2 3 2049\nElementType = MET_UCHAR\nElementDataFile = LOCAL\n";
    bytes.append(std::size_t(2 * 3 * 2049), '\x40');
    writeText(path, bytes);
    Invocation r = run("info " + path.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("GPU layout   z folded into 2 pieces of 1026 voxels side by side along x: one 3D texture of 5 x 3 x 1026 texels"),
              std::string::npos) << r.output;
    Invocation fits = run("info " + path.string() + " --texture-limit 4096");
    EXPECT_NE(fits.output.find("GPU layout   one 3D texture of 2 x 3 x 2049 texels (3D texture limit 4096)"), std::string::npos) << fits.output;
    Invocation none = run("info " + path.string() + " --texture-limit 64");
    EXPECT_EQ(none.exitCode, 0) << none.output;
    EXPECT_NE(none.output.find("GPU layout   none fits the 3D texture limit 64"), std::string::npos) << none.output;
}

// Statistics leave voxels without data out: the same as a volume of the finite values alone.
TEST(VolumeStatistics, IgnoreNoDataVoxels) {
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    std::vector<float> withHoles = {nan, 3.0f, -1.0f, inf, 7.5f, 0.0f, nan, 2.0f, -inf, 10.0f, 4.0f, nan};
    std::vector<float> finite;
    for (float v : withHoles)
        if (std::isfinite(v)) finite.push_back(v);
    auto build = [](const std::vector<float>& v) {
        return curette::buildVolume("<test>", {static_cast<int>(v.size()), 1, 1}, curette::ScalarType::Float32,
                                    reinterpret_cast<const std::uint8_t*>(v.data()), false, 1.0, 0.0, glm::dmat4(1.0));
    };
    curette::VolumeData holes = build(withHoles), plain = build(finite);
    EXPECT_EQ(holes.noDataVoxels, 5u);
    EXPECT_EQ(holes.minValue, -1.0);
    EXPECT_EQ(holes.maxValue, 10.0);
    curette::VolumeStatistics a = curette::computeStatistics(holes), b = curette::computeStatistics(plain);
    EXPECT_EQ(a.min, b.min);
    EXPECT_EQ(a.max, b.max);
    EXPECT_EQ(a.mean, b.mean);
    EXPECT_DOUBLE_EQ(a.mean, 25.5 / 7);
    EXPECT_EQ(a.standardDeviation, b.standardDeviation);
    EXPECT_EQ(a.nonZeroFraction, 6.0 / 7);
    EXPECT_EQ(a.percentiles, b.percentiles);
    EXPECT_EQ(a.histogram, b.histogram);
    std::uint64_t counted = 0;
    for (std::uint64_t c : a.histogram) counted += c;
    EXPECT_EQ(counted, 7u);
}

}  // namespace
