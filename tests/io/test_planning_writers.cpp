// The plan's exports, each read back by curette's own readers: NIfTI-1 label maps (io::readVolume, and the
// qform through io::niftiQformAffine), Slicer .seg.nrrd (io::readNrrd, LPS back to RAS; key lines checked as
// text), binary STL (parsed here), glTF/.glb (clip::loadGltf) and MRtrix .tck (io::readTractogram).
#include "io/gzip.h"
#include "io/mesh_writers.h"
#include "io/nifti.h"
#include "io/nifti_writer.h"
#include "io/nrrd.h"
#include "io/seg_nrrd_writer.h"
#include "io/tck_writer.h"
#include "io/tract_file.h"
#include "io/volume_file.h"
#include "base/atomic_file.h"
#include "base/error.h"
#include "base/label_map.h"
#include "mesh/gltf_mesh.h"
#include "mesh/primitives.h"
#include "tests/io/io_test_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>

namespace curette {
namespace {

const std::filesystem::path& kTemplates = test::kMricronTemplates;

// An oblique, anisotropic index-to-world affine (a rotation about a skew axis times voxel sizes, offset).
glm::dmat4 obliqueAffine() {
    return glm::translate(glm::dmat4(1.0), glm::dvec3(-91.25, 37.5, -12.0)) *
           glm::rotate(glm::dmat4(1.0), 0.61, glm::normalize(glm::dvec3(0.3, -1.0, 0.7))) *
           glm::scale(glm::dmat4(1.0), glm::dvec3(0.7, 1.3, 2.4));
}

LabelMap sampleLabels(glm::ivec3 dims, const glm::dmat4& affine, int maxId, unsigned seed) {
    LabelMap map;
    map.dims = dims;
    map.indexToWorld = affine;
    map.source = "sample";
    map.ids.resize(map.voxelCount());
    std::mt19937 random(seed);
    std::uniform_int_distribution<int> id(0, maxId);
    for (std::uint16_t& v : map.ids) v = static_cast<std::uint16_t>(id(random));
    return map;
}

void expectAffineNear(const glm::dmat4& got, const glm::dmat4& want, double tolerance) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) EXPECT_NEAR(got[c][r], want[c][r], tolerance) << "column " << c << " row " << r;
}

template <typename T>
T at(const std::vector<std::uint8_t>& bytes, std::size_t offset) {
    T v;
    std::memcpy(&v, bytes.data() + offset, sizeof v);
    return v;
}

// The affine a NIfTI-1 file's qform describes (nifti1.h METHOD 2, through curette's reader function).
glm::dmat4 qformOfFile(const std::vector<std::uint8_t>& header) {
    glm::dvec3 pixdim(at<float>(header, 80), at<float>(header, 84), at<float>(header, 88));
    return io::niftiQformAffine(at<float>(header, 256), at<float>(header, 260), at<float>(header, 264), at<float>(header, 76), pixdim,
                                {at<float>(header, 268), at<float>(header, 272), at<float>(header, 276)});
}

std::vector<std::uint8_t> fileBytes(const std::filesystem::path& path) {
    std::vector<std::uint8_t> bytes = readFileBytes(path);
    return io::isGzip(bytes) ? io::gunzip(bytes, path.string(), 1u << 30) : bytes;
}

// --- NIfTI ---------------------------------------------------------------------------------------------

TEST(NiftiLabelmapWriter, ObliqueAnisotropicRoundTripKeepsAffineAndEveryVoxel) {
    for (const char* name : {"oblique.nii.gz", "oblique.nii"}) {
        std::filesystem::path path = test::scratchDirectory() / name;
        LabelMap labels = sampleLabels({11, 7, 5}, obliqueAffine(), 200, 3);
        io::writeNiftiLabelmap(path, labels);
        EXPECT_EQ(io::isGzip(readFileBytes(path)), std::string(name).ends_with(".gz"));
        VolumeData volume = io::readVolume(path);
        EXPECT_EQ(volume.sourceType, ScalarType::UInt8);
        expectAffineNear(volume.indexToWorld, labels.indexToWorld, 1e-5);  // float32 srow
        LabelMap back = labelMapFromVolume(volume);
        EXPECT_EQ(back.dims, labels.dims);
        EXPECT_EQ(back.ids, labels.ids);
        std::vector<std::uint8_t> header = fileBytes(path);
        EXPECT_EQ(at<std::int16_t>(header, 252), 2);  // qform_code
        EXPECT_EQ(at<std::int16_t>(header, 254), 2);  // sform_code
        EXPECT_EQ(at<float>(header, 76), 1.0f);       // qfac
        EXPECT_EQ(at<float>(header, 108), 352.0f);
        EXPECT_EQ(header[123], 2);  // mm
        EXPECT_EQ(std::memcmp(header.data() + 344, "n+1\0", 4), 0);
        expectAffineNear(qformOfFile(header), labels.indexToWorld, 1e-5);
        EXPECT_NEAR(at<float>(header, 84), 1.3, 1e-6);  // pixdim = column norms
    }
}

TEST(NiftiLabelmapWriter, IdsAbove255AreUint16) {
    std::filesystem::path path = test::scratchDirectory() / "wide.nii";
    LabelMap labels = sampleLabels({6, 5, 4}, glm::scale(glm::dmat4(1.0), glm::dvec3(1, 2, 3)), 65535, 5);
    labels.ids[0] = 65535;
    io::writeNiftiLabelmap(path, labels);
    VolumeData volume = io::readVolume(path);
    EXPECT_EQ(volume.sourceType, ScalarType::UInt16);
    EXPECT_EQ(labelMapFromVolume(volume).ids, labels.ids);
    EXPECT_EQ(at<std::int16_t>(readFileBytes(path), 70), 512);
}

TEST(NiftiLabelmapWriter, ReflectionGivesQfacMinusOne) {
    // RAS -> LAS as FSL's radiological images: det < 0.
    std::filesystem::path path = test::scratchDirectory() / "mirrored.nii";
    glm::dmat4 affine = obliqueAffine() * glm::scale(glm::dmat4(1.0), glm::dvec3(-1, 1, 1));
    ASSERT_LT(glm::determinant(glm::dmat3(affine)), 0);
    LabelMap labels = sampleLabels({4, 5, 6}, affine, 9, 8);
    io::writeNiftiLabelmap(path, labels);
    std::vector<std::uint8_t> header = readFileBytes(path);
    EXPECT_EQ(at<float>(header, 76), -1.0f);
    EXPECT_EQ(at<std::int16_t>(header, 252), 2);
    expectAffineNear(qformOfFile(header), affine, 1e-5);
    expectAffineNear(io::readVolume(path).indexToWorld, affine, 1e-5);
}

TEST(NiftiLabelmapWriter, ShearedAffineHasNoQform) {
    std::filesystem::path path = test::scratchDirectory() / "sheared.nii";
    glm::dmat4 affine(1.0);
    affine[1][0] = 0.4;  // j moves along x too
    LabelMap labels = sampleLabels({3, 3, 3}, affine, 4, 9);
    io::writeNiftiLabelmap(path, labels);
    std::vector<std::uint8_t> header = readFileBytes(path);
    EXPECT_EQ(at<std::int16_t>(header, 252), 0);
    expectAffineNear(io::readVolume(path).indexToWorld, affine, 1e-6);
}

TEST(NiftiLabelmapWriter, AalRoundTrip) {
    SKIP_WITHOUT_MRICRON("aal.nii.gz");
    LabelMap aal = labelMapFromVolume(io::readVolume(kTemplates / "aal.nii.gz"));
    std::filesystem::path path = test::scratchDirectory() / "aal-copy.nii.gz";
    io::writeNiftiLabelmap(path, aal);
    LabelMap back = labelMapFromVolume(io::readVolume(path));
    EXPECT_EQ(back.indexToWorld, aal.indexToWorld);  // integer offsets and unit steps are exact in float32
    EXPECT_TRUE(back.ids == aal.ids);
}

// --- Slicer .seg.nrrd -------------------------------------------------------------------------------------

std::string headerOf(const std::filesystem::path& path) {
    std::vector<std::uint8_t> bytes = readFileBytes(path);
    std::string text(bytes.begin(), bytes.end());
    return text.substr(0, text.find("\n\n") + 1);
}

TEST(SlicerSegmentationWriter, RoundTripThroughTheNrrdReader) {
    std::filesystem::path path = test::scratchDirectory() / "plan.seg.nrrd";
    LabelMap labels;
    labels.dims = {8, 6, 5};
    labels.indexToWorld = obliqueAffine();
    labels.ids.assign(labels.voxelCount(), 0);
    // Label 1 in the box i 2..4, j 1..3, k 0..2; label 3 in one voxel (7, 5, 4).
    for (int k = 0; k <= 2; ++k)
        for (int j = 1; j <= 3; ++j)
            for (int i = 2; i <= 4; ++i) labels.ids[labels.linearIndex(i, j, k)] = 1;
    labels.ids[labels.linearIndex(7, 5, 4)] = 3;
    std::vector<io::SegmentInfo> segments = {{1, "Segment_1", "removed region", {1.0, 0.5, 0.0}},
                                             {3, "spared", "corticospinal tract", {0.0, 0.0, 1.0}},
                                             {5, "empty", "nothing", {0.25, 0.25, 0.25}}};
    io::writeSlicerSegmentation(path, labels, segments);

    VolumeData volume = io::readNrrd(path);
    EXPECT_EQ(volume.sourceType, ScalarType::UInt8);
    expectAffineNear(volume.indexToWorld, labels.indexToWorld, 1e-12);  // written to full precision, LPS -> RAS by the reader
    EXPECT_EQ(labelMapFromVolume(volume).ids, labels.ids);

    std::string header = headerOf(path);
    auto hasLine = [&](const std::string& line) { return header.find("\n" + line + "\n") != std::string::npos; };
    EXPECT_TRUE(header.starts_with("NRRD0004\n"));
    for (const char* line :
         {"type: uchar", "dimension: 3", "space: left-posterior-superior", "sizes: 8 6 5", "kinds: domain domain domain", "encoding: gzip",
          "Segmentation_MasterRepresentation:=Binary labelmap", "Segmentation_ContainedRepresentationNames:=Binary labelmap|",
          "Segmentation_ReferenceImageExtentOffset:=0 0 0", "Segment0_ID:=Segment_1", "Segment0_Name:=removed region",
          "Segment0_Color:=1 0.5 0", "Segment0_LabelValue:=1", "Segment0_Layer:=0", "Segment0_Extent:=2 4 1 3 0 2", "Segment0_Tags:=",
          "Segment0_NameAutoGenerated:=0", "Segment0_ColorAutoGenerated:=0", "Segment1_ID:=spared", "Segment1_LabelValue:=3",
          "Segment1_Layer:=0", "Segment1_Extent:=7 7 5 5 4 4", "Segment2_Extent:=0 -1 0 -1 0 -1", "Segment2_Layer:=0"})
        EXPECT_TRUE(hasLine(line)) << line << "\nin\n" << header;
    // Space directions are IJK -> LPS: the RAS columns with x and y negated; the origin likewise.
    const glm::dmat4& m = labels.indexToWorld;
    std::size_t at0 = header.find("space origin: (");
    ASSERT_NE(at0, std::string::npos);
    double ox = 0, oy = 0, oz = 0;
    ASSERT_EQ(std::sscanf(header.c_str() + at0, "space origin: (%lf,%lf,%lf)", &ox, &oy, &oz), 3);
    EXPECT_EQ(ox, -m[3][0]);  // shortest round-trip text: the same doubles
    EXPECT_EQ(oy, -m[3][1]);
    EXPECT_EQ(oz, m[3][2]);
    std::size_t atDirections = header.find("space directions: (");
    ASSERT_NE(atDirections, std::string::npos);
    double d[9];
    ASSERT_EQ(std::sscanf(header.c_str() + atDirections, "space directions: (%lf,%lf,%lf) (%lf,%lf,%lf) (%lf,%lf,%lf)", &d[0], &d[1], &d[2],
                          &d[3], &d[4], &d[5], &d[6], &d[7], &d[8]),
              9);
    for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(d[3 * c], -m[c][0]);
        EXPECT_EQ(d[3 * c + 1], -m[c][1]);
        EXPECT_EQ(d[3 * c + 2], m[c][2]);
    }
}

TEST(SlicerSegmentationWriter, IdsAbove255AreUshortLittleEndian) {
    std::filesystem::path path = test::scratchDirectory() / "wide.seg.nrrd";
    LabelMap labels = sampleLabels({5, 4, 3}, glm::scale(glm::dmat4(1.0), glm::dvec3(0.5, 0.5, 1.5)), 1000, 4);
    io::writeSlicerSegmentation(path, labels, {{1000, "a", "a", {1, 0, 0}}});
    std::string header = headerOf(path);
    EXPECT_NE(header.find("\ntype: ushort\n"), std::string::npos);
    EXPECT_NE(header.find("\nendian: little\n"), std::string::npos);
    VolumeData volume = io::readNrrd(path);
    EXPECT_EQ(labelMapFromVolume(volume).ids, labels.ids);
    expectAffineNear(volume.indexToWorld, labels.indexToWorld, 0);
}

TEST(SlicerSegmentationWriter, BadSegmentsAreRefused) {
    std::filesystem::path path = test::scratchDirectory() / "bad.seg.nrrd";
    LabelMap labels = sampleLabels({2, 2, 2}, glm::dmat4(1.0), 3, 1);
    test::expectInputError([&] { io::writeSlicerSegmentation(path, labels, {{0, "a", "a", {1, 0, 0}}}); }, path.string(),
                           "Segment0_LabelValue");
    test::expectInputError([&] { io::writeSlicerSegmentation(path, labels, {{1, "a", "a", {1, 0, 0}}, {2, "a", "b", {1, 0, 0}}}); },
                           path.string(), "Segment1_ID");
    test::expectInputError([&] { io::writeSlicerSegmentation(path, labels, {{1, "a", "x\ny", {1, 0, 0}}}); }, path.string(),
                           "Segment0_Name");
    test::expectInputError([&] { io::writeSlicerSegmentation(path, labels, {{1, "a", "a", {1.5, 0, 0}}}); }, path.string(),
                           "Segment0_Color");
    EXPECT_FALSE(std::filesystem::exists(path));
}

// --- STL ---------------------------------------------------------------------------------------------------

struct StlFile {
    std::string header;
    std::vector<glm::vec3> normals;
    std::vector<std::array<glm::vec3, 3>> triangles;
};

StlFile parseStl(const std::vector<std::uint8_t>& bytes) {
    StlFile stl;
    stl.header.assign(bytes.begin(), bytes.begin() + 80);
    std::uint32_t count = at<std::uint32_t>(bytes, 80);
    EXPECT_EQ(bytes.size(), 84 + 50 * std::size_t{count});
    for (std::uint32_t t = 0; t < count; ++t) {
        std::size_t base = 84 + 50 * std::size_t{t};
        auto vec = [&](std::size_t o) { return glm::vec3(at<float>(bytes, o), at<float>(bytes, o + 4), at<float>(bytes, o + 8)); };
        stl.normals.push_back(vec(base));
        stl.triangles.push_back({vec(base + 12), vec(base + 24), vec(base + 36)});
        EXPECT_EQ(at<std::uint16_t>(bytes, base + 48), 0);
    }
    return stl;
}

// The STL's triangles as a mesh (vertices welded, as a reader would).
clip::TriangleMesh meshOf(const StlFile& stl) {
    clip::TriangleMesh mesh;
    mesh.source = "stl";
    for (const auto& t : stl.triangles) {
        auto base = static_cast<std::uint32_t>(mesh.positions.size());
        mesh.positions.insert(mesh.positions.end(), t.begin(), t.end());
        mesh.triangles.emplace_back(base, base + 1, base + 2);
    }
    clip::weldVertices(mesh, 1e-4);
    return mesh;
}

clip::TriangleMesh shiftedSphere() {
    clip::TriangleMesh mesh = clip::makeSphere(12.5, 2);
    for (glm::vec3& p : mesh.positions) p += glm::vec3(-30.25f, 14.0f, 52.5f);
    return mesh;
}

TEST(MeshWriters, StlInRasAndLps) {
    clip::TriangleMesh sphere = shiftedSphere();
    for (io::MeshSpace space : {io::MeshSpace::Ras, io::MeshSpace::Lps}) {
        const bool lps = space == io::MeshSpace::Lps;
        std::filesystem::path path = test::scratchDirectory() / (lps ? "cavity-lps.stl" : "cavity-ras.stl");
        io::writeStl(path, sphere, space);
        StlFile stl = parseStl(readFileBytes(path));
        EXPECT_NE(stl.header.find(lps ? "SPACE=LPS" : "SPACE=RAS"), std::string::npos) << stl.header;
        EXPECT_FALSE(stl.header.starts_with("solid"));
        ASSERT_EQ(stl.triangles.size(), sphere.triangles.size());
        for (std::size_t t = 0; t < sphere.triangles.size(); ++t) {
            for (int v = 0; v < 3; ++v) {
                glm::vec3 ras = sphere.positions[sphere.triangles[t][v]];
                EXPECT_EQ(stl.triangles[t][static_cast<std::size_t>(v)], lps ? glm::vec3(-ras.x, -ras.y, ras.z) : ras);
            }
            EXPECT_NEAR(glm::length(stl.normals[t]), 1.0, 1e-6);
            // The normal points away from the sphere's centre (outward, winding kept in both spaces).
            glm::vec3 centre = lps ? glm::vec3(30.25f, -14.0f, 52.5f) : glm::vec3(-30.25f, 14.0f, 52.5f);
            EXPECT_GT(glm::dot(stl.normals[t], stl.triangles[t][0] - centre), 0.0f);
        }
        clip::TriangleMesh back = meshOf(stl);
        EXPECT_NO_THROW(clip::validateClosed(back));
        EXPECT_GT(back.signedVolume(), 0.0);
        EXPECT_NEAR(back.signedVolume(), sphere.signedVolume(), 1e-6 * sphere.signedVolume());
    }
}

TEST(MeshWriters, BadMeshesAreRefused) {
    std::filesystem::path path = test::scratchDirectory() / "bad.stl";
    clip::TriangleMesh empty;
    test::expectInputError([&] { io::writeStl(path, empty, io::MeshSpace::Ras); }, path.string(), "mesh");
    clip::TriangleMesh broken = clip::makeBox({1, 2, 3});
    broken.triangles[0].y = 1000;
    test::expectInputError([&] { io::writeStl(path, broken, io::MeshSpace::Ras); }, path.string(), "mesh");
    std::filesystem::path obj = test::scratchDirectory() / "mesh.obj";
    test::expectInputError([&] { io::writeGltf(obj, clip::makeBox({1, 2, 3}), io::MeshSpace::Ras); }, obj.string(), "extension");
    EXPECT_FALSE(std::filesystem::exists(path));
}

// --- glTF --------------------------------------------------------------------------------------------------

// Each triangle as its three positions, rotated to start at the smallest (winding kept), sorted.
std::vector<std::array<glm::vec3, 3>> triangleSet(const clip::TriangleMesh& mesh, glm::vec3 flip = glm::vec3(1.0f)) {
    auto less = [](glm::vec3 a, glm::vec3 b) { return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z); };
    std::vector<std::array<glm::vec3, 3>> set;
    for (const glm::uvec3& t : mesh.triangles) {
        std::array<glm::vec3, 3> v = {mesh.positions[t.x] * flip, mesh.positions[t.y] * flip, mesh.positions[t.z] * flip};
        for (glm::vec3& p : v) p = glm::round(p * 1000.0f) / 1000.0f;  // a micrometre grid against float rounding
        std::size_t first = static_cast<std::size_t>(std::min_element(v.begin(), v.end(), less) - v.begin());
        std::rotate(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(first), v.end());
        set.push_back(v);
    }
    std::sort(set.begin(), set.end(), [&](const auto& a, const auto& b) {
        return std::lexicographical_compare(a.begin(), a.end(), b.begin(), b.end(), less);
    });
    return set;
}

TEST(MeshWriters, GltfAndGlbLoadBackAsTheSameClipMesh) {
    clip::TriangleMesh sphere = shiftedSphere();
    for (const char* name : {"cavity.gltf", "cavity.glb"}) {
        for (io::MeshSpace space : {io::MeshSpace::Ras, io::MeshSpace::Lps}) {
            std::filesystem::path path = test::scratchDirectory() / name;
            io::writeGltf(path, sphere, space);
            // Positions in millimetres under a node scale of 0.001 (metres); curette's "units": "m" -> x1000.
            clip::TriangleMesh back = clip::loadGltf(path, 1000.0);
            EXPECT_NO_THROW(clip::validateClosed(back));
            EXPECT_EQ(back.positions.size(), sphere.positions.size());
            glm::vec3 flip = space == io::MeshSpace::Lps ? glm::vec3(-1, -1, 1) : glm::vec3(1);
            EXPECT_EQ(triangleSet(back), triangleSet(sphere, flip)) << name;
            EXPECT_NEAR(back.signedVolume(), sphere.signedVolume(), 1e-5 * sphere.signedVolume());
        }
    }
}

TEST(MeshWriters, GltfJsonHasScaleBoundsAndUnitNormals) {
    clip::TriangleMesh box = clip::makeBox({10, 20, 30});
    std::filesystem::path path = test::scratchDirectory() / "box.gltf";
    io::writeGltf(path, box, io::MeshSpace::Ras);
    std::vector<std::uint8_t> bytes = readFileBytes(path);
    nlohmann::json gltf = nlohmann::json::parse(bytes.begin(), bytes.end());
    EXPECT_EQ(gltf["asset"]["version"], "2.0");
    EXPECT_EQ(gltf["nodes"][0]["scale"], nlohmann::json::array({0.001, 0.001, 0.001}));
    const nlohmann::json& position = gltf["accessors"][0];
    EXPECT_EQ(position["min"], nlohmann::json::array({-5.0, -10.0, -15.0}));
    EXPECT_EQ(position["max"], nlohmann::json::array({5.0, 10.0, 15.0}));
    EXPECT_EQ(gltf["accessors"][2]["componentType"], 5125);  // UNSIGNED_INT
    EXPECT_TRUE(gltf["buffers"][0]["uri"].get<std::string>().starts_with("data:application/octet-stream;base64,"));
    // The same file as .glb: normals read from the binary chunk are unit length and point outward.
    std::filesystem::path glb = test::scratchDirectory() / "box.glb";
    io::writeGltf(glb, box, io::MeshSpace::Ras);
    std::vector<std::uint8_t> g = readFileBytes(glb);
    ASSERT_EQ(at<std::uint32_t>(g, 0), 0x46546C67u);
    EXPECT_EQ(at<std::uint32_t>(g, 8), g.size());
    std::uint32_t jsonLength = at<std::uint32_t>(g, 12);
    std::size_t bin = 20 + jsonLength + 8;
    std::size_t n = box.positions.size();
    for (std::size_t v = 0; v < n; ++v) {
        glm::vec3 normal(at<float>(g, bin + 12 * n + 12 * v), at<float>(g, bin + 12 * n + 12 * v + 4), at<float>(g, bin + 12 * n + 12 * v + 8));
        EXPECT_NEAR(glm::length(normal), 1.0, 1e-6);
        EXPECT_GT(glm::dot(normal, box.positions[v]), 0.0f);
    }
}

// --- TCK ---------------------------------------------------------------------------------------------------

TEST(TckWriter, RoundTripThroughTheTractReader) {
    Tractogram tracts;
    tracts.points = {{1, 2, 3}, {4, 5, 6.5f}, {-7.25f, 8, 9}, {10, 11, 12}, {13, 14, 15}};
    tracts.offsets = {0, 2, 2, 5};  // the second streamline is empty
    std::filesystem::path path = test::scratchDirectory() / "spared.tck";
    io::writeTck(path, tracts);
    Tractogram back = io::readTractogram(path);
    ASSERT_EQ(back.streamlineCount(), 2u);
    EXPECT_EQ(back.offsets, (std::vector<std::uint32_t>{0, 2, 5}));
    EXPECT_EQ(back.points, tracts.points);
    std::vector<std::uint8_t> bytes = readFileBytes(path);
    std::string text(bytes.begin(), bytes.end());
    std::size_t end = text.find("\nEND\n");
    ASSERT_NE(end, std::string::npos);
    std::string header = text.substr(0, end + 5);
    EXPECT_TRUE(header.starts_with("mrtrix tracks\n"));
    EXPECT_NE(header.find("\ncount: 2\n"), std::string::npos);
    EXPECT_NE(header.find("\ndatatype: Float32LE\n"), std::string::npos);
    EXPECT_NE(header.find("\nfile: . " + std::to_string(header.size()) + "\n"), std::string::npos) << header;
    // 5 points, 2 NaN delimiters, 1 Inf terminator.
    EXPECT_EQ(bytes.size(), header.size() + 12 * (5 + 2 + 1));
    EXPECT_TRUE(std::isinf(at<float>(bytes, bytes.size() - 4)));
    EXPECT_TRUE(std::isnan(at<float>(bytes, bytes.size() - 16)));
}

TEST(TckWriter, NonFinitePointsAreRefused) {
    Tractogram tracts;
    tracts.points = {{1, 2, 3}, {NAN, 0, 0}};
    tracts.offsets = {0, 2};
    std::filesystem::path path = test::scratchDirectory() / "nan.tck";
    test::expectInputError([&] { io::writeTck(path, tracts); }, path.string(), "points[1]");
    tracts.offsets = {0, 3};
    test::expectInputError([&] { io::writeTck(path, tracts); }, path.string(), "offsets");
    EXPECT_FALSE(std::filesystem::exists(path));
}

}  // namespace
}  // namespace curette
