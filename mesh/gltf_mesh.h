#pragma once
// Closed clip meshes from glTF 2.0 (.gltf with external or data-URI buffers, and .glb) through Debian's
// tinygltf: the default scene's node hierarchy with its transforms, every TRIANGLES primitive merged, then
// welded, oriented outwards and checked closed.

#include "mesh/triangle_mesh.h"

#include <cstdint>
#include <filesystem>
#include <span>

namespace curette::clip {

// glTF positions are in metres by the specification; unitsToMm scales them (1000 for "m", 1 for "mm").
TriangleMesh loadGltf(const std::filesystem::path& path, double unitsToMm);
// From memory (the fuzzing entry point): .glb when the bytes start with "glTF", else .gltf JSON.
TriangleMesh loadGltfFromMemory(std::span<const std::uint8_t> bytes, const std::string& source, double unitsToMm);

}  // namespace curette::clip
