#include "mesh/gltf_mesh.h"

#include "base/error.h"

#include <tiny_gltf.h>

#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>

namespace curette::clip {

namespace {

// File access for external buffers and images. TinyGLTF's defaults expand shell words in URIs and trust
// the stream size of whatever they open (a directory reports 2^63 bytes); ours read regular files only,
// up to a size no clip mesh needs, and never write.
constexpr std::uintmax_t kMaxExternalBufferBytes = std::uintmax_t(1) << 30;

bool regularFileExists(const std::string& path, void*) {
    std::error_code ec;
    return std::filesystem::is_regular_file(path, ec);
}

std::string pathAsIs(const std::string& path, void*) { return path; }

bool readRegularFile(std::vector<unsigned char>* out, std::string* error, const std::string& path, void*) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) {
        if (error) *error += "external buffer \"" + path + "\" is not a regular file\n";
        return false;
    }
    std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec || size > kMaxExternalBufferBytes) {
        if (error) *error += "external buffer \"" + path + "\" is larger than 1 GiB or unreadable\n";
        return false;
    }
    std::ifstream in(path, std::ios::binary);
    out->resize(static_cast<std::size_t>(size));
    if (size > 0 && !in.read(reinterpret_cast<char*>(out->data()), static_cast<std::streamsize>(size))) {
        if (error) *error += "could not read external buffer \"" + path + "\"\n";
        return false;
    }
    return true;
}

bool refuseWrite(std::string* error, const std::string&, const std::vector<unsigned char>&, void*) {
    if (error) *error += "curette never writes glTF files\n";
    return false;
}

void useSafeFileAccess(tinygltf::TinyGLTF& loader) {
    loader.SetFsCallbacks(tinygltf::FsCallbacks{&regularFileExists, &pathAsIs, &readRegularFile, &refuseWrite, nullptr});
}

glm::dmat4 nodeTransform(const tinygltf::Node& node) {
    if (node.matrix.size() == 16) return glm::make_mat4(node.matrix.data());  // column-major, as glTF
    glm::dmat4 t(1.0), r(1.0), s(1.0);
    if (node.translation.size() == 3) t[3] = glm::dvec4(node.translation[0], node.translation[1], node.translation[2], 1.0);
    if (node.rotation.size() == 4)  // glTF quaternions are (x, y, z, w)
        r = glm::mat4_cast(glm::dquat(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]));
    if (node.scale.size() == 3) s = glm::dmat4(glm::dvec4(node.scale[0], 0, 0, 0), glm::dvec4(0, node.scale[1], 0, 0),
                                               glm::dvec4(0, 0, node.scale[2], 0), glm::dvec4(0, 0, 0, 1));
    return t * r * s;
}

// The bytes of accessor `index`, element by element, checked against its buffer view and buffer.
struct AccessorView {
    const std::uint8_t* data = nullptr;
    std::size_t count = 0, stride = 0;
    int componentType = 0, type = 0;
};

AccessorView view(const tinygltf::Model& model, int index, const std::string& source, const std::string& field) {
    if (index < 0 || index >= static_cast<int>(model.accessors.size()))
        throw InputError(source, field, "a valid accessor index", std::to_string(index));
    const tinygltf::Accessor& a = model.accessors[static_cast<std::size_t>(index)];
    if (a.bufferView < 0 || a.bufferView >= static_cast<int>(model.bufferViews.size()))
        throw InputError(source, field + " bufferView", "a valid buffer view (sparse accessors are not supported)", std::to_string(a.bufferView));
    const tinygltf::BufferView& bv = model.bufferViews[static_cast<std::size_t>(a.bufferView)];
    if (bv.buffer < 0 || bv.buffer >= static_cast<int>(model.buffers.size()))
        throw InputError(source, field + " buffer", "a valid buffer", std::to_string(bv.buffer));
    const tinygltf::Buffer& buffer = model.buffers[static_cast<std::size_t>(bv.buffer)];
    int componentSize = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType));
    int components = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type));
    if (componentSize <= 0 || components <= 0) throw InputError(source, field, "a known component type");
    std::size_t elementSize = static_cast<std::size_t>(componentSize * components);
    std::size_t stride = bv.byteStride ? bv.byteStride : elementSize;
    std::size_t begin = bv.byteOffset + a.byteOffset;
    std::size_t needed = a.count ? begin + stride * (a.count - 1) + elementSize : begin;
    if (needed > buffer.data.size() || a.byteOffset + (a.count ? stride * (a.count - 1) + elementSize : 0) > bv.byteLength)
        throw InputError(source, field, "an accessor inside its buffer view and buffer", "one that runs past the end");
    return {buffer.data.data() + begin, a.count, stride, a.componentType, a.type};
}

TriangleMesh fromModel(const tinygltf::Model& model, const std::string& source, double unitsToMm) {
    TriangleMesh mesh;
    mesh.source = source;
    auto addMesh = [&](int meshIndex, const glm::dmat4& transform) {
        if (meshIndex < 0 || meshIndex >= static_cast<int>(model.meshes.size()))
            throw InputError(source, "nodes[].mesh", "a valid mesh index", std::to_string(meshIndex));
        const tinygltf::Mesh& m = model.meshes[static_cast<std::size_t>(meshIndex)];
        for (std::size_t p = 0; p < m.primitives.size(); ++p) {
            const tinygltf::Primitive& prim = m.primitives[p];
            std::string where = "meshes[" + std::to_string(meshIndex) + "].primitives[" + std::to_string(p) + "]";
            int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
            if (mode != TINYGLTF_MODE_TRIANGLES)
                throw InputError(source, where + ".mode", "4 (TRIANGLES): clip meshes are closed triangle surfaces",
                                 std::to_string(mode) + (mode <= 3 ? " (points or lines)" : " (strips or fans)"));
            auto position = prim.attributes.find("POSITION");
            if (position == prim.attributes.end()) throw InputError(source, where + ".attributes", "a POSITION attribute", "none");
            AccessorView pv = view(model, position->second, source, where + ".attributes.POSITION");
            if (pv.type != TINYGLTF_TYPE_VEC3 || pv.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
                throw InputError(source, where + ".attributes.POSITION", "VEC3 of FLOAT");
            std::uint32_t base = static_cast<std::uint32_t>(mesh.positions.size());
            for (std::size_t i = 0; i < pv.count; ++i) {
                float xyz[3];
                std::memcpy(xyz, pv.data + i * pv.stride, sizeof xyz);
                glm::dvec3 world = glm::dvec3(transform * glm::dvec4(xyz[0], xyz[1], xyz[2], 1.0)) * unitsToMm;
                // Finite and within a kilometre: a clip mesh works at the scale of a body, and the welding grid
                // below must not overflow.
                if (!(std::abs(world.x) <= 1e6 && std::abs(world.y) <= 1e6 && std::abs(world.z) <= 1e6))
                    throw InputError(source, where + ".attributes.POSITION", "finite coordinates within +-1e6 mm after the node transforms",
                                     std::to_string(world.x) + ", " + std::to_string(world.y) + ", " + std::to_string(world.z));
                mesh.positions.emplace_back(glm::vec3(world));
            }
            std::vector<std::uint32_t> indices;
            if (prim.indices >= 0) {
                AccessorView iv = view(model, prim.indices, source, where + ".indices");
                if (iv.type != TINYGLTF_TYPE_SCALAR) throw InputError(source, where + ".indices", "SCALAR indices");
                for (std::size_t i = 0; i < iv.count; ++i) {
                    const std::uint8_t* e = iv.data + i * iv.stride;
                    std::uint32_t v = 0;
                    if (iv.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) v = *e;
                    else if (iv.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) { std::uint16_t s; std::memcpy(&s, e, 2); v = s; }
                    else if (iv.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) std::memcpy(&v, e, 4);
                    else throw InputError(source, where + ".indices", "UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT components");
                    if (v >= pv.count) throw InputError(source, where + ".indices", "indices below the vertex count " + std::to_string(pv.count), std::to_string(v));
                    indices.push_back(base + v);
                }
            } else {
                for (std::size_t i = 0; i < pv.count; ++i) indices.push_back(base + static_cast<std::uint32_t>(i));
            }
            if (indices.size() % 3 != 0) throw InputError(source, where, "a multiple of three indices", std::to_string(indices.size()));
            // A node transform with negative determinant mirrors the winding.
            bool mirrored = glm::determinant(glm::dmat3(transform)) < 0;
            for (std::size_t i = 0; i + 2 < indices.size(); i += 3)
                mesh.triangles.push_back(mirrored ? glm::uvec3(indices[i], indices[i + 2], indices[i + 1])
                                                  : glm::uvec3(indices[i], indices[i + 1], indices[i + 2]));
        }
    };
    std::function<void(int, const glm::dmat4&, int)> visit = [&](int nodeIndex, const glm::dmat4& parent, int depth) {
        if (depth > 64) throw InputError(source, "nodes", "a node hierarchy without cycles", "more than 64 levels");
        if (nodeIndex < 0 || nodeIndex >= static_cast<int>(model.nodes.size()))
            throw InputError(source, "nodes", "valid node indices", std::to_string(nodeIndex));
        const tinygltf::Node& node = model.nodes[static_cast<std::size_t>(nodeIndex)];
        glm::dmat4 transform = parent * nodeTransform(node);
        if (node.mesh >= 0) addMesh(node.mesh, transform);
        for (int child : node.children) visit(child, transform, depth + 1);
    };
    if (!model.scenes.empty()) {
        int scene = model.defaultScene >= 0 && model.defaultScene < static_cast<int>(model.scenes.size()) ? model.defaultScene : 0;
        for (int root : model.scenes[static_cast<std::size_t>(scene)].nodes) visit(root, glm::dmat4(1.0), 0);
    } else {
        for (std::size_t i = 0; i < model.meshes.size(); ++i) addMesh(static_cast<int>(i), glm::dmat4(1.0));
    }
    if (mesh.triangles.empty()) throw InputError(source, "meshes", "at least one triangle", "none");
    glm::dvec3 extent = mesh.boundsMax() - mesh.boundsMin();
    weldVertices(mesh, 1e-6 * std::max({extent.x, extent.y, extent.z, 1e-3}));
    validateClosed(mesh);
    orientOutward(mesh);
    return mesh;
}

}  // namespace

TriangleMesh loadGltfFromMemory(std::span<const std::uint8_t> bytes, const std::string& source, double unitsToMm) {
    tinygltf::TinyGLTF loader;
    useSafeFileAccess(loader);
    tinygltf::Model model;
    std::string error, warning;
    bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
    bool ok = binary ? loader.LoadBinaryFromMemory(&model, &error, &warning, bytes.data(), static_cast<unsigned>(bytes.size()), "")
                     : loader.LoadASCIIFromString(&model, &error, &warning, reinterpret_cast<const char*>(bytes.data()),
                                                  static_cast<unsigned>(bytes.size()), "");
    if (!ok) throw InputError(source, binary ? "glb" : "gltf", "a valid glTF 2.0 file", error.empty() ? "unreadable" : error);
    return fromModel(model, source, unitsToMm);
}

TriangleMesh loadGltf(const std::filesystem::path& path, double unitsToMm) {
    std::string source = path.string();
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) throw InputError(source, "", "an existing glTF file (.gltf or .glb)", "no such file");
    tinygltf::TinyGLTF loader;
    useSafeFileAccess(loader);
    tinygltf::Model model;
    std::string error, warning;
    bool glb = path.extension() == ".glb";
    bool ok = glb ? loader.LoadBinaryFromFile(&model, &error, &warning, source) : loader.LoadASCIIFromFile(&model, &error, &warning, source);
    if (!ok) throw InputError(source, glb ? "glb" : "gltf", "a valid glTF 2.0 file", error.empty() ? "unreadable" : error);
    return fromModel(model, source, unitsToMm);
}

}  // namespace curette::clip
