// report.json (schema, units in keys, null for infinite margins, provenance), the CSVs (header, RFC 4180 quoting) and
// the terminal summary with its WARNING lines.
#include "plan/report_output.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

namespace curette::plan {
namespace {

Report sample() {
    Report r;
    r.volumeSource = "head.nii.gz";
    r.dims = {181, 217, 181};
    r.spacingMm = glm::dvec3(1.0);
    r.voxelVolumeMl = 0.001;
    r.samplesPerVoxel = 41;
    r.removedMl = 12.5;
    r.removedUncertaintyMl = 0.04;
    r.touchedVoxels = 14000;
    StructureRow a;
    a.labelSet = "aal";
    a.id = 3;
    a.name = "Frontal, \"Sup\" L";
    a.isProtected = true;
    a.touched = true;
    a.removedMl = 1.25;
    a.volumeMl = 25;
    a.share = 0.05;
    a.intrusionDepthMm = 4.5;
    a.removedUncertaintyMl = 0.01;
    a.intrusionUncertaintyMm = 1.7;
    StructureRow b;
    b.labelSet = "aal";
    b.id = 9;
    b.name = "Far";
    b.isProtected = true;
    b.marginMm = std::numeric_limits<double>::infinity();
    r.structures = {a, b};
    BundleRow t;
    t.name = "CST left";
    t.isProtected = true;
    t.streamlines = 100;
    t.cut = 7;
    t.share = 0.07;
    t.removedLengthMm = 30;
    t.marginUncertaintyMm = 0.2;
    r.bundles = {t};
    return r;
}

ReportProvenance provenance() {
    ReportProvenance p;
    p.createdUtc = "2031-02-03T04:05:06Z";
    p.curetteVersion = "curette 9.9.9 (git abc)";
    p.files = {{"volume", "", "/data/head.nii.gz", 1, std::string(64, 'a')}, {"tracts", "CST left", "/data/cst.tck", 1, std::string(64, 'b')},
               {"volume", "", "/data/series", 120, std::string(64, 'c')}};
    p.transferFunctionJson = R"({"color": [[0, 1, 1, 1], [255, 1, 1, 1]], "opacity": [[0, 0], [255, 0.5]]})";
    p.meshes = {{"ball", {1, 2, 3}, glm::dquat(0.5, 0.5, -0.5, 0.5), {90, 0, 90}, {1, 1, 2}}};
    return p;
}

TEST(ReportOutput, JsonHasTheSchemaUnitsAndNullForInfiniteMargins) {
    nlohmann::json j = nlohmann::json::parse(reportJson(sample(), provenance()));
    EXPECT_EQ(j["schema"], "curette.report/1");
    EXPECT_EQ(j["removed_ml"], 12.5);
    EXPECT_EQ(j["volume"]["voxel_volume_ml"], 0.001);
    EXPECT_EQ(j["structures"][0]["name"], "Frontal, \"Sup\" L");
    EXPECT_EQ(j["structures"][0]["intrusion_depth_mm"], 4.5);
    EXPECT_EQ(j["removed_ml_uncertainty"], 0.04);
    EXPECT_EQ(j["structures"][0]["removed_ml_uncertainty"], 0.01);
    EXPECT_EQ(j["structures"][0]["intrusion_depth_uncertainty_mm"], 1.7);
    EXPECT_EQ(j["bundles"][0]["margin_uncertainty_mm"], 0.2);
    EXPECT_TRUE(j["structures"][1]["margin_mm"].is_null());
    EXPECT_EQ(j["bundles"][0]["cut_streamlines"], 7);
    EXPECT_EQ(j["warnings"].size(), 2u);
    EXPECT_TRUE(j["timings_ms"].contains("total_ms"));
}

TEST(ReportOutput, JsonRecordsItsProvenance) {
    nlohmann::json p = nlohmann::json::parse(reportJson(sample(), provenance()))["provenance"];
    EXPECT_EQ(p["created_utc"], "2031-02-03T04:05:06Z");
    EXPECT_EQ(p["curette_version"], "curette 9.9.9 (git abc)");
    ASSERT_EQ(p["files"].size(), 3u);
    nlohmann::json volume = {{"role", "volume"}, {"path", "/data/head.nii.gz"}, {"files", 1}, {"sha256", std::string(64, 'a')}};
    EXPECT_EQ(p["files"][0], volume) << "the volume has no name";
    EXPECT_EQ(p["files"][1]["name"], "CST left");
    EXPECT_EQ(p["files"][2]["files"], 120);
    EXPECT_EQ(p["transfer_function"]["opacity"], nlohmann::json::parse("[[0, 0], [255, 0.5]]"));
    ASSERT_EQ(p["clip_meshes"].size(), 1u);
    EXPECT_EQ(p["clip_meshes"][0]["orientation_wxyz"], nlohmann::json::parse("[0.5, 0.5, -0.5, 0.5]"));
    EXPECT_EQ(p["clip_meshes"][0]["position_mm"], nlohmann::json::parse("[1.0, 2.0, 3.0]"));
    EXPECT_EQ(p["clip_meshes"][0]["rotation_deg"], nlohmann::json::parse("[90.0, 0.0, 90.0]"));
    EXPECT_EQ(p["clip_meshes"][0]["scale"], nlohmann::json::parse("[1.0, 1.0, 2.0]"));
}

TEST(ReportOutput, CsvQuotesNamesPerRfc4180) {
    EXPECT_EQ(csvField("plain"), "plain");
    EXPECT_EQ(csvField("a,b"), "\"a,b\"");
    EXPECT_EQ(csvField("say \"hi\""), "\"say \"\"hi\"\"\"");
    EXPECT_EQ(csvField("two\nlines"), "\"two\nlines\"");
    const std::string csv = structuresCsv(sample());
    EXPECT_EQ(csv.substr(0, csv.find("\r\n")),
              "label_set,id,name,protected,touched,voxels,touched_voxels,volume_ml,removed_ml,removed_ml_uncertainty,share_fraction,"
              "intrusion_depth_mm,intrusion_depth_uncertainty_mm,margin_mm,margin_uncertainty_mm");
    EXPECT_NE(csv.find("aal,3,\"Frontal, \"\"Sup\"\" L\",true,true,0,0,25,1.25,0.01,0.05,4.5,1.7,0,0\r\n"), std::string::npos) << csv;
    EXPECT_NE(csv.find("aal,9,Far,true,false,0,0,0,0,0,0,0,0,,0\r\n"), std::string::npos) << "an infinite margin is empty: " << csv;
    const std::string bundles = bundlesCsv(sample());
    EXPECT_NE(bundles.find("CST left,true,100,7,0.07,0,30,0,0.2\r\n"), std::string::npos) << bundles;
}

TEST(ReportOutput, SummaryWarnsAboutProtectedTouchesAndFilesAreWritten) {
    const std::string summary = reportSummary(sample());
    EXPECT_NE(summary.find("removed 12.50 +-0.04 mL"), std::string::npos) << summary;
    EXPECT_NE(summary.find("1.250 +-0.010"), std::string::npos) << "each figure with its uncertainty: " << summary;
    EXPECT_NE(summary.find("WARNING: protected structure aal/Frontal, \"Sup\" L (id 3) touched"), std::string::npos) << summary;
    EXPECT_NE(summary.find("WARNING: protected bundle CST left cut: 7 of 100"), std::string::npos) << summary;
    EXPECT_EQ(summary.find("Far (id 9) touched"), std::string::npos);
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "curette_plan_report_test";
    std::filesystem::remove_all(dir);
    writeReportFiles(sample(), provenance(), dir / "nested");
    for (const char* name : {"report.json", "structures.csv", "bundles.csv"})
        EXPECT_TRUE(std::filesystem::exists(dir / "nested" / name)) << name;
    std::ifstream in(dir / "nested" / "report.json");
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_EQ(text.str(), reportJson(sample(), provenance()));
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace curette::plan
