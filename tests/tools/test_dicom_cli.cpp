// `curette info` and `curette render` on DICOM folders, run as a user would: the table of series, which one
// opens, the patient's name and ids only with --show-identifiers, one error line for a refused series, and a
// scene whose volume is a DICOM folder.
#include "tests/tools/run_curette.h"
#include "tests/io/dicom_test_writer.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>

namespace {

namespace fs = std::filesystem;
using curette::test::DicomImageSpec;
using curette::testing::Invocation;

const std::string kSource = CURETTE_SOURCE_DIR;

fs::path testDirectory() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    fs::path dir = fs::temp_directory_path() / ("curette-dicom-cli-" + std::to_string(::getpid())) / info->name();
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

bool mentionsThePatient(const std::string& text) {
    for (const char* id : {"Doe", "Jane", "ID-4711", "19700101", "ACC-99"})
        if (text.find(id) != std::string::npos) return true;
    return false;
}

DicomImageSpec janeDoe(const std::string& seriesNumber, const std::string& description, const std::string& studyUid) {
    DicomImageSpec spec;
    spec.studyUid = studyUid;
    spec.seriesUid = curette::test::newUid();
    spec.seriesNumber = seriesNumber;
    spec.seriesDescription = description;
    spec.patientName = "Doe^Jane";
    spec.patientId = "ID-4711";
    spec.patientBirthDate = "19700101";
    spec.accessionNumber = "ACC-99";
    return spec;
}

// An axial CT series of Jane Doe: 16 x 16 pixels of 1.5 mm, slices 2 mm apart at the given z; a bright ball
// (1000 HU) in air (-1000 HU), stored as int16 with RescaleIntercept -1024.
std::string writeSeries(const fs::path& dir, const std::string& number, const std::string& description,
                        std::initializer_list<double> z, const std::string& studyUid) {
    DicomImageSpec spec = janeDoe(number, description, studyUid);
    spec.rows = spec.columns = 16;
    spec.pixelSpacing = {1.5, 1.5};
    spec.rescaleIntercept = "-1024";
    int k = 0;
    for (double position : z) {
        spec.position = {-12, -12, position};
        spec.instanceNumber = k + 1;
        spec.pixels.clear();
        for (int j = 0; j < 16; ++j)
            for (int i = 0; i < 16; ++i) {
                double dx = (i - 7.5) * 1.5, dy = (j - 7.5) * 1.5, dz = position - 8;
                spec.pixels.push_back(dx * dx + dy * dy + dz * dz < 64 ? 2024 : 24);
            }
        curette::test::writeDicom(dir / (number + "-" + std::to_string(k++) + ".dcm"), spec);
    }
    return spec.seriesUid;
}

TEST(DicomCli, InfoListsTheSeriesAndOpensTheLargestWithoutThePatient) {
    fs::path dir = testDirectory();
    const std::string study = curette::test::newUid();
    std::string main = writeSeries(dir, "3", "head axial", {0, 2, 4, 6, 8, 10, 12, 14, 16}, study);
    DicomImageSpec localizer = janeDoe("1", "scout", study);
    localizer.imageType = "ORIGINAL\\PRIMARY\\LOCALIZER";
    localizer.orientation = {0, 1, 0, 0, 0, -1};
    localizer.pixels.assign(12, 100);
    curette::test::writeDicom(dir / "scout.dcm", localizer);

    Invocation r = curette::testing::runCurette("info " + dir.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("DICOM        2 series"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(main), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(localizer.seriesUid), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("16 x 16 x 9"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("opens        series 3 \"head axial\": the default"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("dimensions   16 x 16 x 9"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("min -1000  max 1000"), std::string::npos) << r.output;
    EXPECT_FALSE(mentionsThePatient(r.output)) << r.output;

    Invocation scout = curette::testing::runCurette("info " + dir.string() + " --series 1");
    ASSERT_EQ(scout.exitCode, 0) << scout.output;
    EXPECT_NE(scout.output.find("opens        series 1 \"scout\": asked for"), std::string::npos) << scout.output;
    EXPECT_FALSE(mentionsThePatient(scout.output)) << scout.output;

    Invocation shown = curette::testing::runCurette("info " + dir.string() + " --show-identifiers");
    ASSERT_EQ(shown.exitCode, 0) << shown.output;
    EXPECT_NE(shown.output.find("Doe^Jane"), std::string::npos) << shown.output;
    EXPECT_NE(shown.output.find("ID-4711"), std::string::npos) << shown.output;
}

TEST(DicomCli, RefusedSeriesAndUnknownSeriesAreOneErrorWithoutThePatient) {
    fs::path dir = testDirectory();
    writeSeries(dir, "4", "gap", {0, 2, 6, 8}, curette::test::newUid());
    Invocation r = curette::testing::runCurette("info " + dir.string());
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("series 4 \"gap\": expected every slice of a regularly spaced series, got 1 slice missing"),
              std::string::npos)
        << r.output;
    EXPECT_FALSE(mentionsThePatient(r.output)) << r.output;

    Invocation unknown = curette::testing::runCurette("info " + dir.string() + " --series 12");
    EXPECT_EQ(unknown.exitCode, 2) << unknown.output;
    EXPECT_NE(unknown.output.find("series: expected the number or SeriesInstanceUID of one of the series"), std::string::npos)
        << unknown.output;
    EXPECT_FALSE(mentionsThePatient(unknown.output)) << unknown.output;
}

TEST(DicomCli, RenderOpensTheDicomFolderOfAScene) {
    fs::path dir = testDirectory();
    fs::path series = dir / "series";
    fs::create_directories(series);
    writeSeries(series, "2", "ball", {0, 2, 4, 6, 8, 10, 12, 14, 16}, curette::test::newUid());
    fs::path scene = dir / "scene.json";
    std::ofstream(scene) << R"({
  "volume": {"path": ")" << series.string() << R"("},
  "transfer_function": ")" << kSource << R"(/assets/tf/ct_bone.json",
  "camera": {"target": "center", "distance_mm": "fit", "azimuth_deg": 30, "elevation_deg": 20, "fov_deg": 30},
  "shading": "phong",
  "image": {"width": 32, "height": 32, "background": [0, 0, 0, 1]}
})";
    fs::path png = dir / "ball.png";
    Invocation r = curette::testing::runCurette("render --scene " + scene.string() + " --out " + png.string() + " --size 32x32");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    std::ifstream in(png, std::ios::binary);
    char magic[8] = {};
    in.read(magic, 8);
    EXPECT_EQ(std::string(magic + 1, 3), "PNG");
    EXPECT_FALSE(mentionsThePatient(r.output)) << r.output;
}

// `sha256sum FILE`'s digest, computed outside curette.
std::string sha256sum(const fs::path& file) {
    FILE* pipe = popen(("sha256sum '" + file.string() + "'").c_str(), "r");
    char digest[65] = {};
    std::size_t n = pipe ? std::fread(digest, 1, 64, pipe) : 0;
    if (pipe) pclose(pipe);
    return n == 64 ? std::string(digest, 64) : "(sha256sum failed on " + file.string() + ")";
}

// The report of a carve into a DICOM series records the digest of the series' files (not of the other series
// in the folder) and names no patient, in its output or in the text files it writes.
TEST(DicomCli, AReportChecksumsTheSeriesFilesWithoutThePatient) {
    fs::path dir = testDirectory();
    fs::path series = dir / "series";
    fs::create_directories(series);
    std::string study = curette::test::newUid();
    writeSeries(series, "2", "ball", {0, 2, 4, 6, 8, 10, 12, 14, 16}, study);
    writeSeries(series, "3", "scout", {0, 2}, study);
    fs::path scene = dir / "scene.json";
    std::ofstream(scene) << R"({
  "volume": {"path": ")" << series.string() << R"("},
  "transfer_function": ")" << kSource << R"(/assets/tf/ct_bone.json",
  "report": {"tissue": "all"},
  "clip_meshes": [{"name": "ball", "mesh": {"shape": "sphere", "radius_mm": 5}, "position_mm": [0, 0, 8]}]
})";
    fs::path out = dir / "plan";
    Invocation r = curette::testing::runCurette("report --scene " + scene.string() + " --out " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_FALSE(mentionsThePatient(r.output)) << r.output;
    for (const char* name : {"report.json", "structures.csv", "bundles.csv", "plan-scene.json"})
        EXPECT_FALSE(mentionsThePatient(curette::testing::readTextFile(out / name))) << name;

    nlohmann::json volume = nlohmann::json::parse(curette::testing::readTextFile(out / "report.json")).at("provenance").at("files").at(0);
    EXPECT_EQ(volume.at("role"), "volume");
    EXPECT_EQ(volume.at("files"), 9) << "series 2's slices";
    std::ofstream digests(dir / "digests.txt");
    for (int k = 0; k < 9; ++k) digests << sha256sum(series / ("2-" + std::to_string(k) + ".dcm")) << "\n";
    digests.close();
    EXPECT_EQ(volume.at("sha256").get<std::string>(), sha256sum(dir / "digests.txt"));
}

}  // namespace
