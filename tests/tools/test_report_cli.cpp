// `curette report` and `replay --report` as a planner runs them: a sphere carved into a uniform volume
// beside two labels (one protected) and two streamlines (a protected bundle), against analytic answers:
// the removed volume, the label shares, the cut streamline and its chord, the spared one's margin, and
// exports that read back (labelmap, segmentation, closed cavity surface, plan scene, cut and spared tracts).
#include "io/nifti_writer.h"
#include "io/tck_writer.h"
#include "io/tract_file.h"
#include "io/volume_file.h"
#include "scene/scene.h"
#include "base/atomic_file.h"
#include "mesh/gltf_mesh.h"
#include "mesh/primitives.h"
#include "mesh/triangle_mesh.h"
#include "tests/tools/run_curette.h"
#include "tests/io/io_test_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <regex>

namespace curette {
namespace {

namespace fs = std::filesystem;
using testing::Invocation;
using testing::runCurette;

constexpr int kN = 48;                            // 48^3 voxels of 1 mm, voxel (i,j,k) centred at (i,j,k) mm
const glm::dvec3 kCentre(22.0, 24.3, 23.6);       // the carving sphere, off the voxel lattice
constexpr double kRadius = 10.0;

fs::path scratch(const std::string& name) { return curette::testing::freshScratchFolder("curette-report-cli", name); }

// The scene, its uniform volume, the labels (1 "left" where x < 20 mm, 2 "right" elsewhere; right is
// protected) and two streamlines along y: one through the sphere's centre, one 15 mm from it.
fs::path writePlanScene(const fs::path& dir, const std::string& extra = "") {
    test::writeBytes(dir / "uniform.raw", std::vector<std::uint8_t>(std::size_t(kN) * kN * kN, 120));
    LabelMap labels;
    labels.dims = glm::ivec3(kN);
    labels.ids.resize(labels.voxelCount());
    for (int k = 0; k < kN; ++k)
        for (int j = 0; j < kN; ++j)
            for (int i = 0; i < kN; ++i) labels.ids[labels.linearIndex(i, j, k)] = i < 20 ? 1 : 2;
    io::writeNiftiLabelmap(dir / "halves.nii.gz", labels);
    std::ofstream(dir / "halves.txt") << "1 left 200 60 60\n2 right 60 200 60\n";
    Tractogram tracts;
    for (double x : {kCentre.x, kCentre.x + 15.0}) {
        for (int n = 0; n <= 40; ++n) tracts.points.emplace_back(float(x), float(4.0 + n), float(kCentre.z));
        tracts.offsets.push_back(static_cast<std::uint32_t>(tracts.points.size()));
    }
    io::writeTck(dir / "pair.tck", tracts);
    std::ofstream(dir / "plan.json") << R"({
  "volume": {"path": "uniform.raw", "format": "raw", "raw": {"dims": [48, 48, 48], "type": "uint8"}},
  "transfer_function": {"color": [[0, 1, 1, 1], [255, 1, 1, 1]], "opacity": [[0, 0], [100, 0.5], [255, 0.5]]},
  "image": {"width": 32, "height": 32},
  "labels": [{"path": "halves.nii.gz", "table": "halves.txt", "protected": ["right"]}],
  "clip_meshes": [{"name": "ball", "mesh": {"shape": "sphere", "radius_mm": 10, "resolution": 4},
                   "position_mm": [22.0, 24.3, 23.6], "rotation_deg": [10, 20, 30]}],
  "tubes": [{"path": "pair.tck", "name": "pair", "protected": true}])" + extra + "\n}\n";
    return dir / "plan.json";
}

nlohmann::json readJson(const fs::path& p) {
    std::ifstream in(p);
    return nlohmann::json::parse(in);
}

// Rows of a report.json table by name.
std::map<std::string, nlohmann::json> rowsByName(const nlohmann::json& rows) {
    std::map<std::string, nlohmann::json> out;
    for (const nlohmann::json& r : rows) out[r.at("name").get<std::string>()] = r;
    return out;
}

// The spherical cap of height h of a ball of radius `radius`.
double capVolume(double radius, double h) { return std::numbers::pi * h * h * (3 * radius - h) / 3.0; }

std::string fileText(const fs::path& p) {
    std::vector<std::uint8_t> bytes = readFileBytes(p);
    return {bytes.begin(), bytes.end()};
}

// A binary STL read back as a mesh whose vertices are shared where their float positions are equal.
clip::TriangleMesh readStl(const fs::path& path) {
    std::vector<std::uint8_t> bytes = readFileBytes(path);
    std::uint32_t count;
    std::memcpy(&count, bytes.data() + 80, 4);
    EXPECT_EQ(bytes.size(), 84u + 50u * count);
    clip::TriangleMesh mesh;
    std::map<std::array<float, 3>, std::uint32_t> index;
    for (std::uint32_t t = 0; t < count; ++t) {
        glm::uvec3 tri;
        for (int v = 0; v < 3; ++v) {
            std::array<float, 3> p;
            std::memcpy(p.data(), bytes.data() + 84 + 50 * t + 12 + 12 * v, 12);
            auto [it, added] = index.emplace(p, static_cast<std::uint32_t>(mesh.positions.size()));
            if (added) mesh.positions.emplace_back(p[0], p[1], p[2]);
            tri[v] = it->second;
        }
        mesh.triangles.push_back(tri);
    }
    return mesh;
}

TEST(ReportCli, ASphereCarveIsMeasuredPerStructureAndBundleAndExported) {
    fs::path dir = scratch("sphere");
    fs::path scene = writePlanScene(dir);
    fs::path out = dir / "plan";
    Invocation r = runCurette("report --scene " + scene.string() + " --out " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("WARNING"), std::string::npos) << "the protected label is touched:\n" << r.output;
    nlohmann::json report = readJson(out / "report.json");

    // The sphere's own mesh volume (the icosphere is inscribed in the analytic sphere).
    double meshMl = clip::makeSphere(kRadius, 4).signedVolume() / 1000.0;
    double removed = report.at("removed_ml").get<double>();
    EXPECT_NEAR(removed, meshMl, 0.01 * meshMl) << "removed volume vs the mesh's own volume";

    // Label "left" holds voxel centres x < 20, i.e. the region x < 19.5: the sphere's cap beyond it.
    double leftMl = capVolume(kRadius, kRadius - (kCentre.x - 19.5)) / 1000.0, rightMl = 4.0 / 3.0 * std::numbers::pi * 1e3 / 1000.0 - leftMl;
    auto structures = rowsByName(report.at("structures"));
    ASSERT_TRUE(structures.count("left") && structures.count("right")) << report.dump(2);
    EXPECT_NEAR(structures["left"].at("removed_ml").get<double>(), leftMl, 0.03 * leftMl);
    EXPECT_NEAR(structures["right"].at("removed_ml").get<double>(), rightMl, 0.03 * rightMl);
    EXPECT_TRUE(structures["right"].at("protected").get<bool>());
    EXPECT_TRUE(structures["right"].at("touched").get<bool>());

    auto bundles = rowsByName(report.at("bundles"));
    ASSERT_TRUE(bundles.count("pair")) << report.dump(2);
    const nlohmann::json& pair = bundles["pair"];
    EXPECT_EQ(pair.at("streamlines").get<int>(), 2);
    EXPECT_EQ(pair.at("cut_streamlines").get<int>(), 1);
    EXPECT_NEAR(pair.at("removed_length_mm").get<double>(), 2 * kRadius, 1.0) << "the chord through the centre";

    // Exports: the labelmap on the source grid, the segmentation, a closed cavity surface, the plan scene,
    // the cut and the spared streamlines.
    VolumeData labelmap = io::readVolume(out / "removed.nii.gz");
    ASSERT_EQ(labelmap.dims, glm::ivec3(kN));
    double removedVoxels = 0;
    for (int k = 0; k < kN; ++k)
        for (int j = 0; j < kN; ++j)
            for (int i = 0; i < kN; ++i) removedVoxels += labelmap.value(i, j, k);
    EXPECT_NEAR(removedVoxels / 1000.0, meshMl, 0.03 * meshMl) << "voxels with more than half removed";
    std::string segText = fileText(out / "removed.seg.nrrd");
    EXPECT_NE(segText.find("Segment0_LabelValue:=1"), std::string::npos);
    EXPECT_NE(segText.find("space: left-posterior-superior"), std::string::npos);

    clip::TriangleMesh cavity = readStl(out / "cavity.stl");
    EXPECT_NO_THROW(clip::validateClosed(cavity)) << "the cavity surface must be watertight";
    EXPECT_NEAR(cavity.signedVolume() / 1000.0, meshMl, 0.05 * meshMl);
    clip::TriangleMesh gltf = clip::loadGltf(out / "cavity.gltf", 1000.0);
    EXPECT_EQ(gltf.triangles.size(), cavity.triangles.size());
    EXPECT_NEAR(gltf.signedVolume(), cavity.signedVolume(), 1e-4 * cavity.signedVolume()) << "glTF in metres reads back in mm";

    Scene planScene = loadScene(out / "plan-scene.json");
    ASSERT_EQ(planScene.clipMeshes.size(), 1u);
    EXPECT_LT(glm::length(planScene.clipMeshes[0].pose.position - kCentre), 1e-9);
    Scene original = loadScene(scene);
    glm::dquat a = original.clipMeshes[0].pose.orientation, b = planScene.clipMeshes[0].pose.orientation;
    EXPECT_GT(std::abs(glm::dot(a, b)), 1.0 - 1e-12) << "the plan scene re-creates the mesh's orientation";

    EXPECT_EQ(io::readTractogram(out / "tracts" / "pair-cut.tck").streamlineCount(), 1u);
    EXPECT_EQ(io::readTractogram(out / "tracts" / "pair-spared.tck").streamlineCount(), 1u);
}

// `sha256sum FILE`'s digest, computed outside curette.
std::string sha256sum(const fs::path& file) {
    std::string command = "sha256sum '" + file.string() + "'";
    FILE* pipe = popen(command.c_str(), "r");
    char digest[65] = {};
    std::size_t n = pipe ? std::fread(digest, 1, 64, pipe) : 0;
    if (pipe) pclose(pipe);
    return n == 64 ? std::string(digest, 64) : "(sha256sum failed on " + file.string() + ")";
}

// report.json says what it was made from: when (UTC), by which curette, the checksums of the volume, label and
// tract files, the TF and every mesh's pose.
TEST(ReportCli, TheReportRecordsItsProvenance) {
    fs::path dir = scratch("provenance");
    fs::path scene = writePlanScene(dir);
    Invocation r = runCurette("report --no-exports --scene " + scene.string() + " --out " + (dir / "out").string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    nlohmann::json report = readJson(dir / "out" / "report.json");
    ASSERT_TRUE(report.contains("provenance")) << report.dump(2);
    const nlohmann::json& p = report.at("provenance");

    std::string created = p.at("created_utc").get<std::string>();
    EXPECT_TRUE(std::regex_match(created, std::regex(R"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ)"))) << created;
    std::string version = runCurette("--version").output;
    EXPECT_EQ(p.at("curette_version").get<std::string>() + "\n", version);

    std::map<std::string, nlohmann::json> files;
    for (const nlohmann::json& f : p.at("files")) files[f.at("role").get<std::string>()] = f;
    ASSERT_TRUE(files.count("volume") && files.count("labels") && files.count("label_table") && files.count("tracts")) << p.dump(2);
    EXPECT_EQ(files["volume"].at("sha256").get<std::string>(), sha256sum(dir / "uniform.raw"));
    EXPECT_EQ(fs::path(files["volume"].at("path").get<std::string>()), fs::absolute(dir / "uniform.raw"));
    EXPECT_EQ(files["labels"].at("sha256").get<std::string>(), sha256sum(dir / "halves.nii.gz"));
    EXPECT_EQ(files["label_table"].at("sha256").get<std::string>(), sha256sum(dir / "halves.txt"));
    EXPECT_EQ(files["tracts"].at("sha256").get<std::string>(), sha256sum(dir / "pair.tck"));

    const nlohmann::json& tf = p.at("transfer_function");
    EXPECT_EQ(tf.at("opacity"), nlohmann::json::parse("[[0, 0], [100, 0.5], [255, 0.5]]")) << tf.dump();
    ASSERT_EQ(p.at("clip_meshes").size(), 1u);
    const nlohmann::json& mesh = p.at("clip_meshes")[0];
    EXPECT_EQ(mesh.at("name"), "ball");
    EXPECT_EQ(mesh.at("position_mm"), nlohmann::json::parse("[22.0, 24.3, 23.6]"));
    Scene original = loadScene(scene);
    glm::dquat q = original.clipMeshes[0].pose.orientation;
    EXPECT_EQ(mesh.at("orientation_wxyz"), nlohmann::json({q.w, q.x, q.y, q.z})) << "the pose as the report used it, exactly";
    EXPECT_EQ(mesh.at("scale"), nlohmann::json::parse("[1.0, 1.0, 1.0]"));

    // A volume of two files (a detached NRRD header and its data): one entry, the digest of their digests.
    std::ofstream(dir / "uniform.nhdr") << "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 48 48 48\nencoding: raw\ndata file: uniform.raw\n";
    std::string text = fileText(scene);
    const std::string raw = R"("volume": {"path": "uniform.raw", "format": "raw", "raw": {"dims": [48, 48, 48], "type": "uint8"}})";
    ASSERT_NE(text.find(raw), std::string::npos);
    text.replace(text.find(raw), raw.size(), R"("volume": {"path": "uniform.nhdr"})");
    std::ofstream(dir / "detached.json") << text;
    Invocation detached = runCurette("report --no-exports --scene " + (dir / "detached.json").string() + " --out " + (dir / "detached").string());
    ASSERT_EQ(detached.exitCode, 0) << detached.output;
    const nlohmann::json volume = readJson(dir / "detached" / "report.json").at("provenance").at("files").at(0);
    EXPECT_EQ(volume.at("files"), 2);
    std::ofstream(dir / "digests.txt") << sha256sum(dir / "uniform.nhdr") << "\n" << sha256sum(dir / "uniform.raw") << "\n";
    EXPECT_EQ(volume.at("sha256").get<std::string>(), sha256sum(dir / "digests.txt")) << "the files' digests in the order of their paths";
    EXPECT_EQ(readJson(dir / "detached" / "report.json").at("removed_ml"), report.at("removed_ml")) << "the same voxels";
}

TEST(ReportCli, TissueCanBeALabelSet) {
    // "right" is protected, so it is tissue under any rule: tissue "left" alone removes the whole sphere, "right"
    // alone only its part beyond the left cap.
    double leftMl = capVolume(kRadius, kRadius - (kCentre.x - 19.5)) / 1000.0;
    double sphereMl = clip::makeSphere(kRadius, 4).signedVolume() / 1000.0;
    for (auto [extra, expected] : std::vector<std::pair<std::string, double>>{
             {",\n  \"report\": {\"tissue\": \"labels\", \"tissue_labels\": [\"left\"]}", sphereMl},
             {",\n  \"report\": {\"tissue\": \"labels\", \"tissue_labels\": [\"right\"]}", sphereMl - leftMl},
             {",\n  \"report\": {\"tissue\": \"labels\"}", sphereMl}}) {
        fs::path dir = scratch("tissue-labels");
        fs::path scene = writePlanScene(dir, extra);
        Invocation r = runCurette("report --no-exports --scene " + scene.string() + " --out " + (dir / "out").string());
        ASSERT_EQ(r.exitCode, 0) << r.output;
        nlohmann::json report = readJson(dir / "out" / "report.json");
        EXPECT_NEAR(report.at("removed_ml").get<double>(), expected, 0.03 * expected) << extra;
        EXPECT_EQ(report.at("tissue").at("rule").get<std::string>(), "labels");
    }
}

TEST(ReportCli, AShownLabelIsTissueAtTheOpacityItIsDrawnWith) {
    // Above the TF's opacity (0.5) nothing but the protected "right" is tissue; with every label shown at 0.9,
    // as the image draws them, the whole sphere is. The exported region follows the report.
    const double sphereMl = clip::makeSphere(kRadius, 4).signedVolume() / 1000.0;
    const double leftMl = capVolume(kRadius, kRadius - (kCentre.x - 19.5)) / 1000.0;
    for (bool shown : {false, true}) {
        fs::path dir = scratch(shown ? "shown-labels" : "hidden-labels");
        fs::path scene = writePlanScene(dir, ",\n  \"report\": {\"opacity_threshold\": 0.7}");
        std::string text = fileText(scene);
        const std::string from = R"("protected": ["right"]})";
        if (shown) text.replace(text.find(from), from.size(), R"("protected": ["right"], "show": "all", "opacity": 0.9})");
        std::ofstream(scene) << text;
        Invocation r = runCurette("report --scene " + scene.string() + " --out " + (dir / "out").string());
        ASSERT_EQ(r.exitCode, 0) << r.output;
        nlohmann::json report = readJson(dir / "out" / "report.json");
        const double expected = shown ? sphereMl : sphereMl - leftMl;
        EXPECT_NEAR(report.at("removed_ml").get<double>(), expected, 0.03 * expected) << (shown ? "shown" : "hidden");
        EXPECT_EQ(rowsByName(report.at("structures")).count("left"), shown ? 1u : 0u);
    }
}

// A volume folded into pieces (render/model/volume_layout.h; the limit forced with CURETTE_MAX_3D_TEXTURE_SIZE, as
// for a scan longer than the GPU's 3D textures) reports the carve the unfolded volume reports, to the digit.
TEST(ReportCli, AFoldedVolumeReportsWhatTheUnfoldedOneReports) {
    fs::path dir = scratch("folded");
    test::writeBytes(dir / "long.raw", std::vector<std::uint8_t>(std::size_t(20) * 16 * 70, 120));
    std::ofstream(dir / "long.json") << R"({
  "volume": {"path": "long.raw", "format": "raw", "raw": {"dims": [20, 16, 70], "type": "uint8"}},
  "transfer_function": {"color": [[0, 1, 1, 1], [255, 1, 1, 1]], "opacity": [[0, 0], [100, 0.5], [255, 0.5]]},
  "image": {"width": 32, "height": 32},
  "clip_meshes": [{"name": "ball", "mesh": {"shape": "sphere", "radius_mm": 6, "resolution": 4},
                   "position_mm": [9.5, 7.8, 34.6]}]
})";
    auto removed = [&](const std::string& name) {
        Invocation r = runCurette("report --no-exports --scene " + (dir / "long.json").string() + " --out " + (dir / name).string());
        EXPECT_EQ(r.exitCode, 0) << r.output;
        return readJson(dir / name / "report.json").at("removed_ml").get<double>();
    };
    double unfolded = removed("unfolded");
    setenv("CURETTE_MAX_3D_TEXTURE_SIZE", "64", 1);   // z (70) folds into 2 pieces across y
    double folded = removed("folded");
    unsetenv("CURETTE_MAX_3D_TEXTURE_SIZE");
    EXPECT_GT(unfolded, 0.5);
    EXPECT_EQ(folded, unfolded);
}

TEST(ReportCli, BadArgumentsAndBadLabelNamesAreOneErrorLine) {
    fs::path dir = scratch("bad");
    fs::path scene = writePlanScene(dir);
    Invocation noOut = runCurette("report --scene " + scene.string());
    EXPECT_EQ(noOut.exitCode, 2) << noOut.output;
    EXPECT_NE(noOut.output.find("--out"), std::string::npos) << noOut.output;
    Invocation frame = runCurette("report --scene " + scene.string() + " --frame 3 --out " + (dir / "x").string());
    EXPECT_EQ(frame.exitCode, 2) << frame.output;
    EXPECT_NE(frame.output.find("--session"), std::string::npos) << frame.output;

    std::string text = fileText(scene);
    text.replace(text.find("[\"right\"]"), 9, "[\"middle\"]");
    std::ofstream(dir / "misnamed.json") << text;
    Invocation misnamed = runCurette("report --scene " + (dir / "misnamed.json").string() + " --out " + (dir / "y").string());
    EXPECT_EQ(misnamed.exitCode, 2) << misnamed.output;
    EXPECT_NE(misnamed.output.find("labels[0].protected[0]"), std::string::npos) << misnamed.output;
    EXPECT_NE(misnamed.output.find("\"middle\""), std::string::npos) << misnamed.output;
    EXPECT_FALSE(fs::exists(dir / "y" / "report.json")) << "nothing written on bad input";
}

TEST(ReportCli, AReplayWritesTheReportOverTime) {
    fs::path dir = scratch("replay");
    fs::path scene = writePlanScene(dir);
    fs::path session = dir / "carve.jsonl";
    Invocation rec = runCurette("record --scene " + scene.string() + " --out " + session.string() + " --synthetic spacemouse --frames 6 --fps 4");
    ASSERT_EQ(rec.exitCode, 0) << rec.output;
    fs::path out = dir / "replay";
    Invocation r = runCurette("replay " + session.string() + " --report --every 2 --size 16x16 --out " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    std::ifstream csv(out / "removal.csv");
    std::string header, line;
    std::getline(csv, header);
    EXPECT_EQ(header.rfind("frame,time_s,removed_ml", 0), 0u) << header;
    int rows = 0;
    while (std::getline(csv, line)) ++rows;
    EXPECT_EQ(rows, 3) << "frames 0, 2 and 4";
    EXPECT_TRUE(fs::exists(out / "report" / "frame_000000" / "report.json"));
    EXPECT_TRUE(fs::exists(out / "report" / "report.json"));
    EXPECT_TRUE(fs::exists(out / "report" / "cavity.stl")) << "the last reported frame's plan has the exports";
    // The session's last reported frame, reported directly, gives the same removed volume.
    Invocation direct = runCurette("report --session " + session.string() + " --frame 4 --no-exports --out " + (dir / "direct").string());
    ASSERT_EQ(direct.exitCode, 0) << direct.output;
    EXPECT_DOUBLE_EQ(readJson(dir / "direct" / "report.json").at("removed_ml").get<double>(),
                     readJson(out / "report" / "frame_000004" / "report.json").at("removed_ml").get<double>());
}

}  // namespace
}  // namespace curette
