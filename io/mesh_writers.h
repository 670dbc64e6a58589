#pragma once
// Surface exports of the removed region (clip::TriangleMesh, world RAS millimetres, counter-clockwise seen
// from outside) for other planning tools.
//
// Binary STL (vtkSTLWriter): an 80-byte header, a uint32 triangle count, then
// 50-byte records (normal, three vertices as float32, a zero uint16), little-endian. The header reads
// `curette binary STL, SPACE=RAS` or `... SPACE=LPS`, the tag 3D Slicer looks for (vtkMRMLModelStorageNode).
// The normal of each record is the unit normal of its vertices ((v1 - v0) x (v2 - v0); 0 0 0 when the
// triangle is degenerate).
//
// glTF 2.0 (https://registry.khronos.org/glTF/specs/2.0/glTF-2.0.html): `.gltf` (JSON, the buffer embedded
// as a base64 data URI) or `.glb` (binary container), by extension. One scene, one node, one mesh with one
// TRIANGLES primitive: POSITION (float32 VEC3 with min/max), NORMAL (per vertex, the area-weighted mean of
// its triangles' normals, unit length) and uint32 indices.
// Units: glTF's unit is the metre. The positions in the buffer are the millimetre coordinates themselves
// and the node carries `scale: [0.001, 0.001, 0.001]`, so the scene is in metres as the specification wants
// while the buffer holds the values curette had. Curette reads such a file back as a clip mesh with the scene
// key `"units": "m"` (the default; mesh/gltf_mesh.cpp applies the node transform, then x1000), giving the
// millimetres again. The axes are RAS (or LPS) as they are: no turn to glTF's +Y-up convention.
//
// MeshSpace::Lps writes (-x, -y, z): a rotation by 180 degrees about z, so the triangles keep their winding.

#include "mesh/triangle_mesh.h"

#include <filesystem>

namespace curette::io {

enum class MeshSpace { Ras, Lps };

// Both atomic (base/atomic_file.h). InputError(path, "mesh", ...) for a mesh without triangles, an index past
// the vertices or a coordinate that is not finite; writeGltf: InputError(path, "extension", ...) unless the
// name ends in .gltf or .glb.
void writeStl(const std::filesystem::path& path, const clip::TriangleMesh& meshInRasMm, MeshSpace space);
void writeGltf(const std::filesystem::path& path, const clip::TriangleMesh& meshInRasMm, MeshSpace space);

}  // namespace curette::io
