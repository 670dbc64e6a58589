#pragma once
// The scene reader's parsing of the keys a panel edit can set (scene/setting_edit.h): one definition, so a
// scene file and an edit of the same key cannot disagree. scene/scene.cpp reads a scene file through these;
// scene/setting_edit.cpp reads an edit's value through the same functions. Each takes the reader positioned at
// the key's value and throws InputError naming the full key path (JsonReader).

#include "base/json_reader.h"
#include "base/transfer_function.h"
#include "mesh/rigid_pose.h"
#include "mesh/triangle_mesh.h"
#include "render/model/clip_mesh_display.h"
#include "render/model/frame.h"
#include "render/model/lao_settings.h"
#include "render/model/tube_geometry.h"
#include "render/model/tube_vertices.h"

#include <filesystem>
#include <memory>
#include <optional>
#include <string>

namespace curette {

struct SceneClipMesh {
    std::string name;
    std::shared_ptr<const clip::TriangleMesh> geometry;
    clip::RigidPose pose{};
    glm::dvec3 scale{1.0};
    bool clipsTubes = false;
};

struct SceneTubes {
    std::filesystem::path path;
    TubeSettings settings;
    std::string name;            // the bundle's name in the report
    bool protectedBundle = false;
};

// "tube_rendering"."build": where tube geometry is made: triangles on the CPU, triangles expanded from their
// rings on the GPU (render/passes/gpu_tube_builder.h), or no triangles: impostors ray-cast from the swept
// points (render/model/tube_impostors.h).
enum class TubeBuild { Cpu, Gpu, Impostor };

// "tube_rendering": whether tubes are drawn as illuminated lines, and their shading.
struct TubeRendering {
    bool lines = false;
    TubeShading shading;
    TubeBuild build = TubeBuild::Cpu;
    bool operator==(const TubeRendering&) const = default;
};

// A scene has at most as many lights as the shaders take.
inline constexpr std::size_t kMaxSceneLights = kMaxLights;

// "shading": "solid" | "phong" | ...
ShadingMode readShading(const JsonReader& r);
// An inline transfer function (assets/tf/README.md), as "transfer_function": {...}.
TransferFunction readInlineTransferFunction(const JsonReader& r);
// One entry of "lights" (its ISMOS keys into `shape`).
Light readLight(const JsonReader& r, IsmosLightShape& shape);
LaoSettings readLao(const JsonReader& r);            // "ambient_occlusion"
RaycastSettings readRaycast(const JsonReader& r);    // "raycast"
DosSettings readDos(const JsonReader& r);            // "dos"
IsmosSettings readIsmos(const JsonReader& r);        // "ismos" (without the per-light shapes)
TubeRendering readTubeRendering(const JsonReader& r);  // "tube_rendering"
// The keys of a "tubes" entry other than "path" into `tubes` (whose path and default name the caller set);
// finishes the object, so a "path" the caller did not read is an unknown key.
void readTubeKeys(const JsonReader& r, SceneTubes& tubes, const std::string& where);
// One entry of "clip_meshes"; `index` names it by default ("mesh 2"); glTF paths relative to `directory`.
SceneClipMesh readClipMesh(const JsonReader& r, const std::filesystem::path& directory, std::size_t index);
// A clip mesh's "mesh" description (mesh/mesh_description.h).
std::shared_ptr<const clip::TriangleMesh> readMeshGeometry(const JsonReader& r, const std::filesystem::path& directory);
// "clip_mesh_display": whether the clip meshes are drawn over the image (`show`, absent: the command's default,
// off in `render` and exports, on in the viewer) and how (render/model/clip_mesh_display.h).
struct ClipMeshDisplaySpec {
    std::optional<bool> show;
    ClipMeshDisplay display;
    bool operator==(const ClipMeshDisplaySpec&) const = default;
};
ClipMeshDisplaySpec readClipMeshDisplay(const JsonReader& r);
// A clip mesh's "scale": a number or [sx, sy, sz].
glm::dvec3 readMeshScale(const JsonReader& r);
// A clip mesh entry's "position_mm" and "rotation_deg" (degrees about x, y, z: clip::orientationFromDegrees)
// into `pose` (keys absent: left as they are); readMeshPose reads an object of just those two.
void readMeshPoseKeys(const JsonReader& r, clip::RigidPose& pose);
clip::RigidPose readMeshPose(const JsonReader& r);

}  // namespace curette
