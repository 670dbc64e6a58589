#pragma once
// A clip mesh as a scene describes it:
//   {"shape": "sphere",   "radius_mm": 20, "resolution": 4}         (icosphere level)
//   {"shape": "box",      "size_mm": [40, 30, 20]}
//   {"shape": "cylinder", "radius_mm": 10, "height_mm": 40, "resolution": 64}
//   {"shape": "cone",     "radius_mm": 10, "height_mm": 40, "resolution": 64}
//   {"shape": "capsule",  "radius_mm": 6, "length_mm": 30, "resolution": 48}
//   {"shape": "torus",    "major_radius_mm": 25, "minor_radius_mm": 8, "resolution": 96}
//   {"shape": "gltf",     "path": "probe.glb", "units": "m" | "mm"}   (relative to the scene file)

#include "base/json_reader.h"
#include "mesh/triangle_mesh.h"

#include <filesystem>

namespace curette::clip {

TriangleMesh meshFromJson(const JsonReader& r, const std::filesystem::path& sceneDirectory);

}  // namespace curette::clip
