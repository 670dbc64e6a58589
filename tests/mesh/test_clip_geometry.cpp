// Clip meshes on the CPU: closed, outward primitives with the right size; the winding-number inside test;
// validation of bad meshes; glTF loading with node transforms, units and clear errors.
#include "base/error.h"
#include "base/json_reader.h"
#include "mesh/gltf_mesh.h"
#include "mesh/mesh_description.h"
#include "mesh/primitives.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <random>

namespace curette::clip {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(Primitives, ClosedOutwardAndTheirAnalyticSize) {
    struct Case {
        const char* name;
        TriangleMesh mesh;
        double volume, area, tolerance;  // relative tolerance from the tessellation
    };
    const double r = 10, h = 30, R = 20, rt = 5;
    std::vector<Case> cases;
    cases.push_back({"sphere", makeSphere(r, 5), 4.0 / 3.0 * kPi * r * r * r, 4 * kPi * r * r, 3e-3});
    cases.push_back({"box", makeBox({10, 20, 30}), 6000, 2 * (200 + 300 + 600), 1e-12});
    cases.push_back({"cylinder", makeCylinder(r, h, 256), kPi * r * r * h, 2 * kPi * r * r + 2 * kPi * r * h, 1e-3});
    cases.push_back({"cone", makeCone(r, h, 256), kPi * r * r * h / 3, kPi * r * r + kPi * r * std::sqrt(r * r + h * h), 1e-3});
    cases.push_back({"capsule", makeCapsule(r, h, 256), kPi * r * r * h + 4.0 / 3.0 * kPi * r * r * r, 2 * kPi * r * h + 4 * kPi * r * r, 2e-3});
    cases.push_back({"torus", makeTorus(R, rt, 256, 128), 2 * kPi * kPi * R * rt * rt, 4 * kPi * kPi * R * rt, 1e-3});
    for (const Case& c : cases) {
        EXPECT_NO_THROW(validateClosed(c.mesh)) << c.name;
        EXPECT_GT(c.mesh.signedVolume(), 0.0) << c.name << " faces outwards";
        EXPECT_NEAR(c.mesh.signedVolume(), c.volume, c.tolerance * c.volume) << c.name;
        EXPECT_NEAR(c.mesh.surfaceArea(), c.area, c.tolerance * c.area) << c.name;
    }
    EXPECT_EQ(makeBox({10, 20, 30}).boundsMax(), glm::dvec3(5, 10, 15));
}

// The winding-number test against each primitive's analytic inside test, away from a band at the surface as
// wide as the tessellation error (the sphere's flat faces sit at most r (1 - cos(edge angle / 2)) inside).
TEST(Primitives, ContainsPointAgreesWithTheAnalyticShapes) {
    std::mt19937 random(3);
    std::uniform_real_distribution<double> u(-25, 25);
    TriangleMesh sphere = makeSphere(10, 4), torus = makeTorus(15, 5, 128, 64), box = makeBox({20, 10, 30});
    auto sphereDistance = [](glm::dvec3 p) { return glm::length(p) - 10; };
    auto torusDistance = [](glm::dvec3 p) { return glm::length(glm::dvec2(glm::length(glm::dvec2(p)) - 15, p.z)) - 5; };
    auto boxDistance = [](glm::dvec3 p) {
        glm::dvec3 d = glm::abs(p) - glm::dvec3(10, 5, 15);
        return glm::length(glm::max(d, 0.0)) + std::min(std::max({d.x, d.y, d.z}), 0.0);
    };
    int checked = 0;
    for (int i = 0; i < 3000; ++i) {
        glm::dvec3 p(u(random), u(random), u(random));
        for (auto [mesh, distance, band] : {std::tuple{&sphere, +sphereDistance, 0.05}, {&torus, +torusDistance, 0.05}, {&box, +boxDistance, 1e-9}}) {
            double d = distance(p);
            if (std::abs(d) < band) continue;
            ASSERT_EQ(containsPoint(*mesh, p), d < 0) << "point " << p.x << "," << p.y << "," << p.z << " distance " << d;
            ++checked;
        }
    }
    EXPECT_GT(checked, 8900);
}

TEST(Primitives, BadParametersNameTheParameter) {
    auto expectField = [](auto make, const std::string& field) {
        try {
            make();
            FAIL() << field;
        } catch (const InputError& e) {
            EXPECT_EQ(e.field(), field) << e.what();
        }
    };
    expectField([] { return makeSphere(-1); }, "radius_mm");
    expectField([] { return makeSphere(std::nan("")); }, "radius_mm");
    expectField([] { return makeBox({1, 0, 1}); }, "size_mm");
    expectField([] { return makeCylinder(1, 2, 2); }, "resolution");
    expectField([] { return makeTorus(5, 6); }, "minor_radius_mm");
    expectField([] { return makeCapsule(1, -2); }, "length_mm");
}

TEST(Validation, HolesNonManifoldEdgesAndFlippedTrianglesAreRejected) {
    TriangleMesh box = makeBox({1, 1, 1});
    box.source = "box";
    TriangleMesh hole = box;
    hole.triangles.pop_back();
    EXPECT_THROW(validateClosed(hole), InputError);
    TriangleMesh flipped = box;
    std::swap(flipped.triangles[0].y, flipped.triangles[0].z);
    try {
        validateClosed(flipped);
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("oriented"), std::string::npos) << e.what();
    }
    TriangleMesh doubled = box;
    for (std::size_t i = 0; i < 2; ++i) doubled.triangles.push_back(box.triangles[i]);
    EXPECT_THROW(validateClosed(doubled), InputError);
    EXPECT_THROW(validateClosed(TriangleMesh{}), InputError);
    TriangleMesh inside = box;
    for (glm::uvec3& t : inside.triangles) std::swap(t.y, t.z);
    EXPECT_LT(inside.signedVolume(), 0);
    orientOutward(inside);
    EXPECT_GT(inside.signedVolume(), 0);
    // Split vertices along seams are welded back into a closed mesh.
    TriangleMesh split;
    for (const glm::uvec3& t : box.triangles)
        for (std::uint32_t i : {t.x, t.y, t.z}) split.positions.push_back(box.positions[i]);
    for (std::uint32_t i = 0; i < split.positions.size(); i += 3) split.triangles.emplace_back(i, i + 1, i + 2);
    EXPECT_THROW(validateClosed(split), InputError);
    weldVertices(split, 1e-9);
    EXPECT_NO_THROW(validateClosed(split));
    EXPECT_EQ(split.positions.size(), 8u);
}

// --- glTF files written by hand ------------------------------------------------------------------------

std::string base64(const std::vector<std::uint8_t>& bytes) {
    static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        std::uint32_t n = static_cast<std::uint32_t>(bytes[i]) << 16;
        if (i + 1 < bytes.size()) n |= static_cast<std::uint32_t>(bytes[i + 1]) << 8;
        if (i + 2 < bytes.size()) n |= bytes[i + 2];
        out += table[(n >> 18) & 63];
        out += table[(n >> 12) & 63];
        out += i + 1 < bytes.size() ? table[(n >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? table[n & 63] : '=';
    }
    return out;
}

// A glTF document holding `mesh` (positions in metres) under one node with the given node JSON fields.
std::string gltfDocument(const TriangleMesh& mesh, const std::string& nodeFields, int mode = 4) {
    std::vector<std::uint8_t> buffer(mesh.positions.size() * 12 + mesh.triangles.size() * 12);
    std::memcpy(buffer.data(), mesh.positions.data(), mesh.positions.size() * 12);
    std::memcpy(buffer.data() + mesh.positions.size() * 12, mesh.triangles.data(), mesh.triangles.size() * 12);
    glm::dvec3 lo = mesh.boundsMin(), hi = mesh.boundsMax();
    std::size_t positionBytes = mesh.positions.size() * 12, indexBytes = mesh.triangles.size() * 12;
    char text[4096];
    std::snprintf(text, sizeof text,
                  R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0 %s}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": %d}]}],
  "buffers": [{"byteLength": %zu, "uri": "data:application/octet-stream;base64,%s"}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": %zu}, {"buffer": 0, "byteOffset": %zu, "byteLength": %zu}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": %zu, "type": "VEC3", "min": [%g, %g, %g], "max": [%g, %g, %g]},
                {"bufferView": 1, "componentType": 5125, "count": %zu, "type": "SCALAR"}]})",
                  nodeFields.c_str(), mode, buffer.size(), "%s", positionBytes, positionBytes, indexBytes, mesh.positions.size(),
                  lo.x, lo.y, lo.z, hi.x, hi.y, hi.z, 3 * mesh.triangles.size());
    std::string document = text;
    document.replace(document.find("%s"), 2, base64(buffer));
    return document;
}

std::vector<std::uint8_t> bytes(const std::string& s) { return std::vector<std::uint8_t>(s.begin(), s.end()); }

TEST(Gltf, NodeTransformsUnitsAndBinaryContainer) {
    TriangleMesh box = makeBox({0.02, 0.04, 0.06});  // metres, as glTF says
    // Translate by (0.1, 0, 0) m, then scale by 2: TRS order in glTF is T * R * S.
    TriangleMesh moved = loadGltfFromMemory(bytes(gltfDocument(box, R"(, "translation": [0.1, 0, 0], "scale": [2, 2, 2])")), "moved.gltf", 1000.0);
    EXPECT_NEAR(moved.boundsMin().x, 100 - 20, 1e-3);
    EXPECT_NEAR(moved.boundsMax().z, 60, 1e-3);
    EXPECT_NEAR(moved.signedVolume(), 8 * 20 * 40 * 60, 1e-2);
    // A mirroring matrix flips the winding; the loader keeps the mesh outward.
    TriangleMesh mirrored = loadGltfFromMemory(
        bytes(gltfDocument(box, R"(, "matrix": [-1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1])")), "mirror.gltf", 1.0);
    EXPECT_GT(mirrored.signedVolume(), 0);
    // Millimetre units.
    TriangleMesh mm = loadGltfFromMemory(bytes(gltfDocument(makeBox({20, 40, 60}), "")), "mm.gltf", 1.0);
    EXPECT_NEAR(mm.boundsMax().y, 20, 1e-4);
    // The same document in a .glb container (JSON chunk, and the buffer still as a data URI).
    std::string json = gltfDocument(box, "");
    while (json.size() % 4) json += ' ';
    std::vector<std::uint8_t> glb = bytes("glTF");
    auto put32 = [&](std::uint32_t v) { for (int b = 0; b < 4; ++b) glb.push_back(static_cast<std::uint8_t>(v >> (8 * b))); };
    put32(2);
    put32(static_cast<std::uint32_t>(12 + 8 + json.size()));
    put32(static_cast<std::uint32_t>(json.size()));
    put32(0x4E4F534A);  // "JSON"
    glb.insert(glb.end(), json.begin(), json.end());
    TriangleMesh fromGlb = loadGltfFromMemory(glb, "box.glb", 1000.0);
    EXPECT_NEAR(fromGlb.signedVolume(), 20 * 40 * 60, 1e-2);
}

TEST(Gltf, NonTriangleOpenAndBrokenFilesAreClearErrors) {
    TriangleMesh box = makeBox({1, 1, 1});
    try {
        loadGltfFromMemory(bytes(gltfDocument(box, "", 1)), "lines.gltf", 1.0);
        FAIL();
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), "meshes[0].primitives[0].mode") << e.what();
    }
    TriangleMesh open = box;
    open.triangles.pop_back();
    try {
        loadGltfFromMemory(bytes(gltfDocument(open, "")), "open.gltf", 1.0);
        FAIL();
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), "mesh") << e.what();
        EXPECT_NE(std::string(e.what()).find("boundary edges"), std::string::npos);
    }
    EXPECT_THROW(loadGltfFromMemory(bytes("{not json"), "broken.gltf", 1.0), InputError);
    EXPECT_THROW(loadGltf("/nonexistent/probe.glb", 1000.0), InputError);
}

TEST(MeshDescription, ShapesFromJsonAndErrors) {
    auto parse = [](const std::string& text) {
        nlohmann::json j = parseJson(text, "scene.json");
        return meshFromJson(JsonReader(j, "scene.json", "mesh"), ".");
    };
    EXPECT_NO_THROW(validateClosed(parse(R"({"shape": "capsule", "radius_mm": 4, "length_mm": 20})")));
    EXPECT_NO_THROW(validateClosed(parse(R"({"shape": "torus", "major_radius_mm": 20, "minor_radius_mm": 6, "resolution": 32})")));
    EXPECT_THROW(parse(R"({"shape": "sphere", "radius_mm": 4, "radius": 3})"), InputError);
    EXPECT_THROW(parse(R"({"shape": "cube", "size_mm": [1, 1, 1]})"), InputError);
    EXPECT_THROW(parse(R"({"shape": "gltf", "path": "missing.glb"})"), InputError);
}

}  // namespace
}  // namespace curette::clip
