// `curette report --dicom` checked by tools no one here wrote: dciodvfy (Debian dicom3tools) validates every
// object against its IOD, plastimatch rasterises the RT Structure Set back onto the series, and pydicom reads
// the Segmentation and the series it references (tests/tools/read_dicom_seg.py). Two plans: a carve into a
// small CT series the test writes (the objects reference it) and into the NIfTI head of the default scene
// (curette writes the scan as a DICOM series and the objects reference that). Each check skips, saying so,
// only when its tool is not installed (scripts/setup installs them).
#include "io/dicom_plan_reader.h"
#include "io/nifti_writer.h"
#include "io/volume_file.h"
#include "base/label_map.h"
#include "tests/io/dicom_test_writer.h"
#include "tests/tools/run_curette.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>

namespace curette {
namespace {

namespace fs = std::filesystem;
using testing::Invocation;
using testing::runCurette;

const std::string kSource = CURETTE_SOURCE_DIR;

// stdout and stderr of a shell command, and its exit code.
Invocation shell(const std::string& command) {
    FILE* pipe = popen((command + " 2>&1").c_str(), "r");
    std::string output;
    char buffer[4096];
    while (std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) output.append(buffer, n);
    int status = pclose(pipe);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

bool installed(const std::string& command) { return shell("command -v " + command).exitCode == 0; }
bool pydicomInstalled() { return shell("/usr/bin/python3 -c 'import pydicom'").exitCode == 0; }

bool mentionsThePatient(const std::string& text) {
    for (const char* id : {"Doe", "Jane", "ID-4711", "19700101", "ACC-99"})
        if (text.find(id) != std::string::npos) return true;
    return false;
}

// In any file, binary ones too: the whole values (no three letters a base64 buffer may hold by chance).
bool holdsThePatient(const std::string& bytes) {
    for (const char* id : {"Doe^Jane", "ID-4711", "19700101", "ACC-99"})
        if (bytes.find(id) != std::string::npos) return true;
    return false;
}

// A plan written by `curette report --dicom` and what the checks compare it with.
struct Plan {
    fs::path out, series;           // the plan folder; the series the objects reference
    Invocation report;
    LabelMap removed;               // removed.nii.gz
    std::uint64_t removedVoxels = 0;
};

LabelMap readLabels(const fs::path& path) { return labelMapFromVolume(io::readVolume(path)); }

void finish(Plan& plan) {
    ASSERT_EQ(plan.report.exitCode, 0) << plan.report.output;
    plan.removed = readLabels(plan.out / "removed.nii.gz");
    for (std::uint16_t id : plan.removed.ids) plan.removedVoxels += id == 1;
    ASSERT_GT(plan.removedVoxels, 0u);
}

// An axial CT series of Jane Doe: 32 x 32 pixels of 1.5 mm, 20 slices 2 mm apart, a 15 mm ball of 1000 HU in
// air centred at LPS (0, 0, 19), stored with RescaleIntercept -1024; beside it a label map on the same grid
// ("near": columns 0-15, "far": the others, protected).
const Plan& ctPlan() {
    static Plan plan = [] {
        Plan p;
        fs::path dir = testing::freshScratchFolder("curette-dicom-export", "ct");
        p.series = dir / "series";
        fs::create_directories(p.series);
        test::DicomImageSpec spec;
        spec.studyUid = test::newUid();
        spec.seriesUid = test::newUid();
        spec.frameOfReferenceUid = test::newUid();
        spec.patientName = "Doe^Jane";
        spec.patientId = "ID-4711";
        spec.patientBirthDate = "19700101";
        spec.accessionNumber = "ACC-99";
        spec.rows = spec.columns = 32;
        spec.pixelSpacing = {1.5, 1.5};
        spec.sliceThickness = 2.0;
        spec.rescaleIntercept = "-1024";
        for (int k = 0; k < 20; ++k) {
            spec.position = {-24, -24, 2.0 * k};
            spec.instanceNumber = k + 1;
            spec.sopInstanceUid.clear();
            spec.pixels.clear();
            for (int j = 0; j < 32; ++j)
                for (int i = 0; i < 32; ++i) {
                    double dx = -24 + 1.5 * i, dy = -24 + 1.5 * j, dz = 2.0 * k - 19;
                    spec.pixels.push_back(dx * dx + dy * dy + dz * dz < 225 ? 2024 : 24);
                }
            test::writeDicom(p.series / ("ct-" + std::to_string(k) + ".dcm"), spec);
        }
        LabelMap labels;
        labels.dims = {32, 32, 20};
        // The series' RAS affine: LPS (-24 + 1.5 i, -24 + 1.5 j, 2 k).
        labels.indexToWorld = glm::dmat4(glm::dvec4(-1.5, 0, 0, 0), glm::dvec4(0, -1.5, 0, 0), glm::dvec4(0, 0, 2, 0), glm::dvec4(24, 24, 0, 1));
        labels.ids.resize(labels.voxelCount());
        for (int k = 0; k < 20; ++k)
            for (int j = 0; j < 32; ++j)
                for (int i = 0; i < 32; ++i) labels.ids[labels.linearIndex(i, j, k)] = i < 16 ? 1 : 2;
        io::writeNiftiLabelmap(dir / "halves.nii.gz", labels);
        std::ofstream(dir / "halves.txt") << "1 near 200 60 60\n2 far 60 200 60\n";
        std::ofstream(dir / "scene.json") << R"({
  "volume": {"path": ")" << p.series.string() << R"("},
  "transfer_function": ")" << kSource << R"(/assets/tf/ct_bone.json",
  "labels": [{"path": "halves.nii.gz", "table": "halves.txt", "protected": ["far"]}],
  "report": {"tissue": "all"},
  "clip_meshes": [{"name": "ball", "mesh": {"shape": "sphere", "radius_mm": 8}, "position_mm": [-3.2, 4.1, 17.3]}]
})";
        p.out = dir / "plan";
        p.report = runCurette("report --dicom --scene " + (dir / "scene.json").string() + " --out " + p.out.string());
        finish(p);
        return p;
    }();
    return plan;
}

// The default scene's NIfTI head (MNI Colin27, 181 x 217 x 181 at 1 mm) with a 6 mm sphere carved into the
// left frontal lobe.
const Plan& headPlan() {
    static Plan plan = [] {
        Plan p;
        fs::path dir = testing::freshScratchFolder("curette-dicom-export", "head");
        nlohmann::json scene = nlohmann::json::parse(testing::readTextFile(kSource + "/assets/scenes/head.json"));
        scene["transfer_function"] = kSource + "/assets/tf/mri_t1.json";
        scene["report"] = {{"tissue", "all"}};
        scene["clip_meshes"] = nlohmann::json::parse(R"([{"name": "ball", "mesh": {"shape": "sphere", "radius_mm": 6}, "position_mm": [-30.3, 20.6, 30.2]}])");
        std::ofstream(dir / "scene.json") << scene.dump(2);
        p.out = dir / "plan";
        p.series = p.out / "scan-dicom";
        p.report = runCurette("report --dicom --scene " + (dir / "scene.json").string() + " --out " + p.out.string());
        finish(p);
        return p;
    }();
    return plan;
}

// dciodvfy's messages about one file: "Error - ..." lines and "Warning - ..." lines.
struct Validation {
    std::vector<std::string> errors, warnings;
};
Validation dciodvfy(const fs::path& file) {
    Invocation r = shell("dciodvfy '" + file.string() + "'");
    Validation v;
    std::istringstream lines(r.output);
    for (std::string line; std::getline(lines, line);) {
        if (line.rfind("Error", 0) == 0) v.errors.push_back(line);
        if (line.rfind("Warning", 0) == 0) v.warnings.push_back(line);
    }
    return v;
}

void expectValid(const fs::path& file) {
    Validation v = dciodvfy(file);
    EXPECT_TRUE(v.errors.empty()) << file << ":\n" << [&] {
        std::string all;
        for (const std::string& e : v.errors) all += e + "\n";
        return all;
    }();
    std::set<std::string> distinct(v.warnings.begin(), v.warnings.end());
    std::cout << "dciodvfy " << file.filename().string() << ": " << v.errors.size() << " errors, " << distinct.size() << " distinct warnings\n";
    for (const std::string& w : distinct) std::cout << "  " << w << "\n";
}

void expectDciodvfyPasses(const Plan& plan, bool seriesWrittenByCurette) {
    if (!installed("dciodvfy")) GTEST_SKIP() << "dciodvfy (Debian package dicom3tools) is not installed";
    expectValid(plan.out / "seg.dcm");
    expectValid(plan.out / "rtstruct.dcm");
    if (seriesWrittenByCurette) expectValid(plan.series / "slice-0001.dcm");
}

// The RT Structure Set rasterised by plastimatch onto the series it references, against removed.nii.gz:
// the contours follow pixel edges (io/slice_contours.h), so each slice's voxels come back exactly where the
// rasteriser tests pixel centres: the expected difference is 0 voxels a slice.
void expectPlastimatchGivesTheRemovedRegion(const Plan& plan) {
    if (!installed("plastimatch")) GTEST_SKIP() << "plastimatch (Debian package plastimatch) is not installed";
    fs::path prefix = plan.out.parent_path() / "plastimatch";
    fs::remove_all(prefix);
    Invocation r = shell("plastimatch convert --input '" + (plan.out / "rtstruct.dcm").string() + "' --referenced-ct '" + plan.series.string() +
                         "' --output-prefix '" + prefix.string() + "' --prefix-format nii.gz");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    fs::path removedFile;
    for (const auto& entry : fs::directory_iterator(prefix))
        if (entry.path().filename().string().find("removed") != std::string::npos) removedFile = entry.path();
    ASSERT_FALSE(removedFile.empty()) << "no structure named removed in " << prefix << "\n" << r.output;
    LabelMap back = readLabels(removedFile);
    LabelMap onGrid = resampleNearest(back, plan.removed.dims, plan.removed.indexToWorld);
    std::uint64_t both = 0, theirs = 0;
    for (std::size_t n = 0; n < onGrid.ids.size(); ++n) {
        theirs += onGrid.ids[n] != 0;
        both += onGrid.ids[n] != 0 && plan.removed.ids[n] == 1;
    }
    double dice = 2.0 * double(both) / double(theirs + plan.removedVoxels);
    double volumeRatio = double(theirs) / double(plan.removedVoxels);
    std::cout << "plastimatch: " << theirs << " voxels back for " << plan.removedVoxels << " removed, Dice " << dice << ", volume ratio "
              << volumeRatio << "\n";
    EXPECT_GE(dice, 0.95);
    EXPECT_NEAR(volumeRatio, 1.0, 0.02);
}

// The Segmentation read by pydicom: consistent with the series (the script's "problems"), its segments, and
// segment 1's voxels, placed by each frame's ImagePositionPatient, equal to removed.nii.gz voxel for voxel.
void expectPydicomReadsTheSeg(const Plan& plan) {
    if (!pydicomInstalled()) GTEST_SKIP() << "pydicom for /usr/bin/python3 (Debian package python3-pydicom) is not installed";
    Invocation r = shell("/usr/bin/python3 '" + kSource + "/tests/tools/read_dicom_seg.py' '" + (plan.out / "seg.dcm").string() + "' '" +
                         plan.series.string() + "'");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    nlohmann::json seg = nlohmann::json::parse(r.output);
    EXPECT_TRUE(seg.at("problems").empty()) << seg.at("problems").dump(1);
    ASSERT_GE(seg.at("segments").size(), 1u);
    const nlohmann::json& removed = seg.at("segments").at(0);
    EXPECT_EQ(removed.at("number"), 1);
    EXPECT_EQ(removed.at("label"), "removed region");
    EXPECT_EQ(removed.at("algorithm_type"), "SEMIAUTOMATIC");
    EXPECT_EQ(removed.at("type").at(0), "REMOVED");
    EXPECT_GT(seg.at("frames").get<int>(), 0);

    const glm::dmat4 worldToIndex = glm::inverse(plan.removed.indexToWorld);
    std::vector<std::uint8_t> fromSeg(plan.removed.voxelCount(), 0);
    for (const nlohmann::json& v : seg.at("voxels")) {
        if (v.at(0) != 1) continue;
        glm::dvec3 corner = glm::dvec3(worldToIndex * glm::dvec4(-v.at(1).get<double>(), -v.at(2).get<double>(), v.at(3).get<double>(), 1.0));
        ASSERT_NEAR(corner.x, 0.0, 1e-3);
        ASSERT_NEAR(corner.y, 0.0, 1e-3);
        int k = int(std::lround(corner.z));
        ASSERT_NEAR(corner.z, k, 1e-3);
        fromSeg[plan.removed.linearIndex(v.at(4).get<int>(), v.at(5).get<int>(), k)] = 1;
    }
    std::uint64_t differing = 0;
    for (std::size_t n = 0; n < fromSeg.size(); ++n) differing += fromSeg[n] != (plan.removed.ids[n] == 1 ? 1 : 0);
    EXPECT_EQ(differing, 0u) << "voxels where the SEG's removed region and removed.nii.gz differ";
}

TEST(DicomExportCt, TheObjectsReferenceTheSourceSeriesAndNameNoPatient) {
    const Plan& plan = ctPlan();
    EXPECT_NE(plan.report.output.find("they reference the source DICOM series (20 images"), std::string::npos) << plan.report.output;
    EXPECT_NE(plan.report.output.find("3 regions: removed region, far, near"), std::string::npos) << plan.report.output;
    EXPECT_FALSE(mentionsThePatient(plan.report.output)) << plan.report.output;
    EXPECT_FALSE(fs::exists(plan.out / "scan-dicom"));
    for (const char* object : {"seg.dcm", "rtstruct.dcm"})
        EXPECT_TRUE(holdsThePatient(testing::readTextFile(plan.out / object))) << object << " carries the source's patient and study";
}

TEST(DicomExportCt, DciodvfyFindsNoError) { expectDciodvfyPasses(ctPlan(), false); }
TEST(DicomExportCt, PydicomReadsTheSegOverTheSourceSeries) { expectPydicomReadsTheSeg(ctPlan()); }
TEST(DicomExportCt, PlastimatchRasterisesTheStructureSetToTheRemovedRegion) { expectPlastimatchGivesTheRemovedRegion(ctPlan()); }

// --anonymize: the scan is written again under new UIDs and no file of the plan holds the patient's name or ids.
TEST(DicomExportCt, AnonymizeLeavesNoIdentifierInThePlan) {
    const Plan& source = ctPlan();
    fs::path out = source.out.parent_path() / "anonymous";
    Invocation r = runCurette("report --dicom --anonymize --scene " + (source.out.parent_path() / "scene.json").string() + " --out " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("--anonymize: patient and study replaced"), std::string::npos) << r.output;
    EXPECT_FALSE(mentionsThePatient(r.output)) << r.output;
    int files = 0;
    for (const auto& entry : fs::recursive_directory_iterator(out))
        if (entry.is_regular_file()) {
            ++files;
            EXPECT_FALSE(holdsThePatient(testing::readTextFile(entry.path()))) << entry.path();
        }
    EXPECT_GT(files, 20);
    Invocation bad = runCurette("report --anonymize --scene " + (source.out.parent_path() / "scene.json").string() + " --out " + out.string());
    EXPECT_EQ(bad.exitCode, 2) << bad.output;
    EXPECT_NE(bad.output.find("--anonymize"), std::string::npos) << bad.output;
}

// curette's own reader: the SEG as a label volume whose segment 1 is removed.nii.gz voxel for voxel, and
// `curette info` on both objects.
void expectCuretteReadsThePlanBack(const Plan& plan, const std::vector<std::string>& roiWords) {
    io::DicomSegmentationVolume seg = io::readDicomSegmentation(plan.out / "seg.dcm");
    ASSERT_GE(seg.segments.size(), 1u);
    EXPECT_EQ(seg.segments[0].label, "removed region");
    EXPECT_EQ(seg.segments[0].voxels, plan.removedVoxels);
    LabelMap onGrid = resampleNearest(seg.labels, plan.removed.dims, plan.removed.indexToWorld);
    std::uint64_t differing = 0;
    for (std::size_t n = 0; n < onGrid.ids.size(); ++n) differing += (onGrid.ids[n] == 1) != (plan.removed.ids[n] == 1);
    EXPECT_EQ(differing, 0u) << "voxels where curette's reading of the SEG and removed.nii.gz differ";

    Invocation info = runCurette("info " + (plan.out / "seg.dcm").string());
    ASSERT_EQ(info.exitCode, 0) << info.output;
    EXPECT_NE(info.output.find("DICOM SEG    " + std::to_string(seg.segments.size()) + " segments"), std::string::npos) << info.output;
    EXPECT_NE(info.output.find("removed region"), std::string::npos) << info.output;
    EXPECT_FALSE(mentionsThePatient(info.output)) << info.output;
    Invocation rois = runCurette("info " + (plan.out / "rtstruct.dcm").string());
    ASSERT_EQ(rois.exitCode, 0) << rois.output;
    for (const std::string& word : roiWords) EXPECT_NE(rois.output.find(word), std::string::npos) << word << "\n" << rois.output;
    EXPECT_FALSE(mentionsThePatient(rois.output)) << rois.output;
}

TEST(DicomExportCt, CuretteReadsThePlanBack) {
    expectCuretteReadsThePlanBack(ctPlan(), {"DICOM RTSTRUCT  3 ROIs", "removed region", "CAVITY", "near", "ORGAN", "far", "AVOIDANCE"});
}
TEST(DicomExportHead, CuretteReadsThePlanBack) { expectCuretteReadsThePlanBack(headPlan(), {"DICOM RTSTRUCT  1 ROIs", "removed region", "CAVITY"}); }

TEST(DicomExportHead, TheScanIsWrittenAsADicomSeriesTheObjectsReference) {
    const Plan& plan = headPlan();
    EXPECT_NE(plan.report.output.find("the scan is not DICOM"), std::string::npos) << plan.report.output;
    int slices = 0;
    for (const auto& entry : fs::directory_iterator(plan.series)) slices += entry.path().extension() == ".dcm";
    EXPECT_EQ(slices, 181);
}

TEST(DicomExportHead, DciodvfyFindsNoError) { expectDciodvfyPasses(headPlan(), true); }
TEST(DicomExportHead, PydicomReadsTheSegOverTheWrittenSeries) { expectPydicomReadsTheSeg(headPlan()); }
TEST(DicomExportHead, PlastimatchRasterisesTheStructureSetToTheRemovedRegion) { expectPlastimatchGivesTheRemovedRegion(headPlan()); }

}  // namespace
}  // namespace curette
