#pragma once
// A panel's change of a setting, as data (Dear ImGui's one place per setting; Inviwo's and Filament's flow
// of settings as values): which setting, which light, bundle or clip mesh it is about, and its new value as
// the scene file's JSON for that key. The value is read by the scene reader's own functions
// (scene/scene_keys.h), so an edit and a scene cannot disagree about a key. The viewer's panels
// (viewer/view_panels.h) produce edits; the session step (session/session_step.h) applies them where device actions
// are applied; sessions record them per frame ("edits", version 3) and replay applies them again.
//
// In a session an edit is {"setting": KEY, "light" | "tube" | "mesh": N (the settings that need one),
// "value": JSON}:
//   shading                 "phong"                                  (as the scene's "shading")
//   transfer_function       {inline TF, assets/tf/README.md}
//   ambient_occlusion       {"rays": "26", "samples": 20, ...}       (the whole object, as in a scene)
//   raycast, dos, ismos, tube_rendering                              (the whole object, as in a scene)
//   lights                  light N's object {"direction", "color", "intensity", "space", "disk_radius", "spot"}
//   lights.add              a new light's object (as above), after the others (at most kMaxSceneLights)
//   lights.remove           null (light N; the lights after it move down one, and at least one light stays)
//   tubes                   bundle N's object without "path" (radius_mm, color, sides, ...)
//   clip_meshes.add         a "clip_meshes" entry {"name", "mesh", "position_mm", "rotation_deg", "scale",
//                           "clips_tubes"}; recorded with the id it was given ("mesh")
//   clip_meshes.remove      null (mesh N: a mesh id, as in the session's poses)
//   clip_meshes.mesh        a mesh description (mesh/mesh_description.h): the shape and its size
//   clip_meshes.scale       a number or [sx, sy, sz]
//   clip_meshes.clips_tubes true | false
//   clip_meshes.pose        {"position_mm": [x, y, z], "rotation_deg": [rx, ry, rz]} (RAS mm; typed in the panel)
//   clip_mesh_display       {"show": true, "opacity": 0.22, "outline_opacity": 0.9}  (the whole object, as in a scene:
//                           the meshes drawn over the image, render/clip_mesh_overlay.h; no image of the renderer's reads it)

#include "scene/scene_keys.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace curette {

enum class Setting {
    Shading,
    TransferFunction,
    AmbientOcclusion,
    Raycast,
    Dos,
    Ismos,
    Light,
    LightAdd,
    LightRemove,
    TubeRendering,
    Tubes,
    MeshAdd,
    MeshRemove,
    MeshShape,
    MeshScale,
    MeshClipsTubes,
    MeshPose,
    ClipMeshDisplay,
    Count
};

// What an edit's target index means.
enum class SettingTarget { None, Light, Tubes, Mesh };

struct SettingInfo {
    Setting setting;
    const char* key;          // the scene file's key ("clip_meshes.scale": the "scale" of a "clip_meshes" entry)
    SettingTarget target;
    const char* targetKey;    // the session's key for the target ("light", "tube", "mesh"), or nullptr
};

const SettingInfo& settingInfo(Setting setting);
std::optional<Setting> settingFromKey(std::string_view key);
std::string settingKeyList();   // for messages

struct SettingEdit {
    Setting setting = Setting::Shading;
    int target = -1;          // light index, tube index or mesh id; -1 for settings without one (and an
                              // added mesh before it has its id)
    nlohmann::json value;
    bool operator==(const SettingEdit&) const = default;
};

// The value an edit carries, read by the scene reader's function for its key.
struct MeshGeometry {
    std::shared_ptr<const clip::TriangleMesh> mesh;
};
struct LightValue {
    Light light;
    IsmosLightShape shape;
};
using SettingValue = std::variant<std::monostate, ShadingMode, TransferFunction, LaoSettings, RaycastSettings, DosSettings,
                                  IsmosSettings, LightValue, TubeRendering, SceneTubes, SceneClipMesh, MeshGeometry, glm::dvec3, bool,
                                  clip::RigidPose, ClipMeshDisplaySpec>;

// Reads `edit.value` as its setting's scene key (InputError naming `source` and `keyPath`, e.g.
// "line 4: edits[0].value"). glTF paths are relative to `directory`. A "tubes" value becomes the SceneTubes
// keys over `tubeDefaults` (its path and default name).
SettingValue readSettingValue(const SettingEdit& edit, const std::string& source, const std::string& keyPath,
                              const std::filesystem::path& directory, const SceneTubes& tubeDefaults = {});

// Session JSON of an edit, and back (strict: the setting, its target key, the value read as above).
nlohmann::ordered_json settingEditJson(const SettingEdit& edit);
SettingEdit readSettingEdit(const JsonReader& r, const std::filesystem::path& directory);

}  // namespace curette
