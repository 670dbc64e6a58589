#include "io/mesh_writers.h"

#include "base/atomic_file.h"
#include "base/base64.h"
#include "base/error.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

namespace curette::io {

namespace {

constexpr std::size_t kStlHeaderBytes = 80;
constexpr std::uint32_t kGlbMagic = 0x46546C67;  // "glTF"
constexpr std::uint32_t kGlbJsonChunk = 0x4E4F534A, kGlbBinChunk = 0x004E4942;
constexpr int kFloat = 5126, kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;
constexpr double kMetresPerMm = 0.001;

template <typename T>
void append(std::vector<std::uint8_t>& bytes, T value) {
    std::uint8_t raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    if constexpr (std::endian::native == std::endian::big) std::reverse(raw, raw + sizeof(T));
    bytes.insert(bytes.end(), raw, raw + sizeof(T));
}

void appendVec3(std::vector<std::uint8_t>& bytes, glm::vec3 v) {
    append(bytes, v.x), append(bytes, v.y), append(bytes, v.z);
}

const char* spaceName(MeshSpace space) { return space == MeshSpace::Lps ? "LPS" : "RAS"; }

glm::vec3 toSpace(glm::vec3 ras, MeshSpace space) { return space == MeshSpace::Lps ? glm::vec3(-ras.x, -ras.y, ras.z) : ras; }

// The mesh checked and moved into the output space.
clip::TriangleMesh prepared(const std::filesystem::path& path, const clip::TriangleMesh& mesh, MeshSpace space) {
    const std::string source = path.string();
    if (mesh.triangles.empty()) throw InputError(source, "mesh", "at least one triangle", "none");
    const std::size_t n = mesh.positions.size();
    for (const glm::uvec3& t : mesh.triangles)
        if (t.x >= n || t.y >= n || t.z >= n)
            throw InputError(source, "mesh", "triangle indices below the vertex count " + std::to_string(n),
                             std::to_string(t.x) + " " + std::to_string(t.y) + " " + std::to_string(t.z));
    clip::TriangleMesh out;
    out.source = mesh.source;
    out.triangles = mesh.triangles;
    out.positions.reserve(n);
    for (const glm::vec3& p : mesh.positions) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw InputError(source, "mesh", "finite vertex coordinates", "NaN or Inf");
        out.positions.push_back(toSpace(p, space));
    }
    return out;
}

// (v1 - v0) x (v2 - v0): twice the area times the unit normal.
glm::dvec3 areaNormal(const clip::TriangleMesh& mesh, const glm::uvec3& t) {
    glm::dvec3 a(mesh.positions[t.x]), b(mesh.positions[t.y]), c(mesh.positions[t.z]);
    return glm::cross(b - a, c - a);
}

glm::vec3 unitOr(glm::dvec3 v, glm::vec3 fallback) {
    double length = glm::length(v);
    return length > 0 && std::isfinite(length) ? glm::vec3(v / length) : fallback;
}

}  // namespace

void writeStl(const std::filesystem::path& path, const clip::TriangleMesh& meshInRasMm, MeshSpace space) {
    const clip::TriangleMesh mesh = prepared(path, meshInRasMm, space);
    if (mesh.triangles.size() > 0xffffffffu) throw InputError(path.string(), "mesh", "at most 2^32 - 1 triangles (STL's count)");
    std::vector<std::uint8_t> bytes(kStlHeaderBytes, ' ');
    // Not starting with "solid": readers take that for ASCII STL.
    const std::string header = std::string("curette binary STL, SPACE=") + spaceName(space);
    std::memcpy(bytes.data(), header.data(), header.size());
    bytes.reserve(kStlHeaderBytes + 4 + 50 * mesh.triangles.size());
    append(bytes, static_cast<std::uint32_t>(mesh.triangles.size()));
    for (const glm::uvec3& t : mesh.triangles) {
        appendVec3(bytes, unitOr(areaNormal(mesh, t), glm::vec3(0.0f)));
        appendVec3(bytes, mesh.positions[t.x]);
        appendVec3(bytes, mesh.positions[t.y]);
        appendVec3(bytes, mesh.positions[t.z]);
        append(bytes, std::uint16_t{0});
    }
    writeFileAtomically(path, bytes);
}

void writeGltf(const std::filesystem::path& path, const clip::TriangleMesh& meshInRasMm, MeshSpace space) {
    const std::string source = path.string();
    const std::string extension = path.extension().string();
    if (extension != ".gltf" && extension != ".glb")
        throw InputError(source, "extension", ".gltf (JSON, embedded buffer) or .glb (binary)", "\"" + extension + "\"");
    const bool binary = extension == ".glb";
    const clip::TriangleMesh mesh = prepared(path, meshInRasMm, space);
    const std::size_t vertexCount = mesh.positions.size();

    std::vector<glm::dvec3> normalSums(vertexCount, glm::dvec3(0.0));
    for (const glm::uvec3& t : mesh.triangles) {
        glm::dvec3 n = areaNormal(mesh, t);  // weighted by area
        normalSums[t.x] += n, normalSums[t.y] += n, normalSums[t.z] += n;
    }
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const glm::vec3& p : mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);

    // One buffer: positions, normals, indices (every part a multiple of 4 bytes).
    std::vector<std::uint8_t> buffer;
    buffer.reserve(24 * vertexCount + 12 * mesh.triangles.size());
    for (const glm::vec3& p : mesh.positions) appendVec3(buffer, p);
    for (const glm::dvec3& n : normalSums) appendVec3(buffer, unitOr(n, glm::vec3(0.0f, 0.0f, 1.0f)));
    for (const glm::uvec3& t : mesh.triangles) append(buffer, t.x), append(buffer, t.y), append(buffer, t.z);
    const std::size_t vec3Bytes = 12 * vertexCount;

    using nlohmann::json;
    json gltf;
    gltf["asset"] = {{"version", "2.0"}, {"generator", "curette"}};
    gltf["scene"] = 0;
    gltf["scenes"] = json::array({{{"nodes", json::array({0})}}});
    gltf["nodes"] = json::array({{{"name", std::string("curette export, ") + spaceName(space) + " millimetres scaled to metres"},
                                  {"mesh", 0},
                                  {"scale", json::array({kMetresPerMm, kMetresPerMm, kMetresPerMm})}}});
    gltf["meshes"] = json::array(
        {{{"name", mesh.source.empty() ? std::string("mesh") : mesh.source},
          {"primitives", json::array({{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}}}, {"indices", 2}, {"mode", 4}}})}}});
    gltf["accessors"] = json::array(
        {{{"bufferView", 0}, {"componentType", kFloat}, {"count", vertexCount}, {"type", "VEC3"},
          {"min", json::array({lo.x, lo.y, lo.z})}, {"max", json::array({hi.x, hi.y, hi.z})}},
         {{"bufferView", 1}, {"componentType", kFloat}, {"count", vertexCount}, {"type", "VEC3"}},
         {{"bufferView", 2}, {"componentType", kUnsignedInt}, {"count", 3 * mesh.triangles.size()}, {"type", "SCALAR"}}});
    gltf["bufferViews"] = json::array(
        {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", vec3Bytes}, {"target", kArrayBuffer}},
         {{"buffer", 0}, {"byteOffset", vec3Bytes}, {"byteLength", vec3Bytes}, {"target", kArrayBuffer}},
         {{"buffer", 0}, {"byteOffset", 2 * vec3Bytes}, {"byteLength", buffer.size() - 2 * vec3Bytes}, {"target", kElementArrayBuffer}}});
    json bufferEntry = {{"byteLength", buffer.size()}};
    if (!binary) bufferEntry["uri"] = "data:application/octet-stream;base64," + base64(buffer);
    gltf["buffers"] = json::array({bufferEntry});

    if (!binary) {
        writeFileAtomically(path, gltf.dump(1) + "\n");
        return;
    }
    // GLB: 12-byte header, a JSON chunk padded with spaces, a BIN chunk padded with zeros (4-byte aligned).
    std::string text = gltf.dump();
    text.append((4 - text.size() % 4) % 4, ' ');
    buffer.resize(buffer.size() + (4 - buffer.size() % 4) % 4, 0);
    const std::size_t total = 12 + 8 + text.size() + 8 + buffer.size();
    if (total > 0xffffffffu) throw InputError(source, "mesh", "a mesh small enough for a .glb (under 4 GiB)");
    std::vector<std::uint8_t> glb;
    glb.reserve(total);
    append(glb, kGlbMagic), append(glb, std::uint32_t{2}), append(glb, static_cast<std::uint32_t>(total));
    append(glb, static_cast<std::uint32_t>(text.size())), append(glb, kGlbJsonChunk);
    glb.insert(glb.end(), text.begin(), text.end());
    append(glb, static_cast<std::uint32_t>(buffer.size())), append(glb, kGlbBinChunk);
    glb.insert(glb.end(), buffer.begin(), buffer.end());
    writeFileAtomically(path, glb);
}

}  // namespace curette::io
