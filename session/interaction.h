#pragma once
// Applying input actions to the scene: the one place where device or keyboard motion becomes clip-mesh
// poses and light directions. Plain data, no GL: the session step (session/session_step.h) runs it for the live viewer, `curette
// record`, `curette replay` and the benches, so poses re-derived from recorded reports equal the recorded
// ones bit for bit.

#include "scene/scene.h"
#include "session/session.h"
#include "scene/setting_edit.h"
#include "mesh/limits.h"
#include "mesh/rigid_pose.h"
#include "mesh/triangle_mesh.h"
#include "plan/undo_history.h"
#include "plan/removal_field.h"
#include "plan/removal_volume.h"
#include "input/actions.h"
#include "render/model/camera.h"
#include "render/model/frame.h"

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace curette {

struct MeshState {
    int id = 0;                  // stable for the session (meshes can be added and removed); scene meshes: scene index
    std::string name;
    std::string description;     // JSON of the mesh (as in a scene) for added meshes, so a replay can rebuild it;
                                 // empty for scene meshes
    std::shared_ptr<const clip::TriangleMesh> geometry;
    clip::RigidPose pose, initialPose;
    glm::dvec3 scale{1.0};
    bool clipsTubes = false;     // the mesh also cuts tubes (scene key clips_tubes)

    // The one way to make one (scene, edits, devices, session files, benches, tests), so none forgets a field:
    // mesh `id` with a scene mesh's keys (its pose is also where reset_pose puts it) and, for a mesh added in
    // the session, its JSON description.
    static MeshState make(int id, const SceneClipMesh& mesh, std::string description = {});
};

struct InteractionState {
    std::vector<MeshState> meshes;
    ShadingMode shading = ShadingMode::Phong;
    // The frame's lights (the scene's, as MoveLight turns them; empty: SessionStep adopts its frame's) and the
    // one MoveLight{-1} turns.
    std::vector<Light> lights;
    int selectedLight = 0;
    int nextMeshId = 0;
    // The scene's settings the panels edit (scene/setting_edit.h), from the scene and then its edits; the session
    // step hands them to the frame (raycast, dos, ismos, lights) and the renderer (SessionStep::syncTo).
    TransferFunction transferFunction;
    LaoSettings lao;
    RaycastSettings raycast;
    DosSettings dos;
    IsmosSettings ismos;                 // lightShapes: one per light
    std::vector<SceneTubes> tubes;
    TubeRendering tubeRendering;
    // How the viewer draws the clip meshes over the image (render/clip_mesh_overlay.h): presentation only, no
    // renderer input; `show` absent is the viewer's default (shown).
    ClipMeshDisplaySpec clipMeshDisplay;
    // Counted per edit from 0, the scene's (RendererSync::sceneSettings).
    std::uint64_t transferFunctionVersion = 0, tubesVersion = 0, tubeShadingVersion = 0;
    // The value of every key an edit has set, latest first wins, by the key's name in the scene file
    // ("transfer_function", "lights[1]", "tubes[0]", ...; mesh settings live in the meshes, the shading in
    // `shading`, which input changes too): what the scene
    // writer (session/plan_scene.h) writes, what the panels start from and what a session header carries.
    // Lights added and removed: an added light's key is set as an edit sets it; a removal first sets every
    // light's key (the scene's own JSON where no edit set one), so the lights after it move down a key.
    std::map<std::string, nlohmann::json> editedKeys;
    // The scene's "lights" entries as its file has them (an empty object for its default light): what a
    // removal sets for a light no edit has set, and what settingEdits() compares the lights with.
    std::vector<nlohmann::json> sceneLightKeys;
    std::filesystem::path sceneDirectory = ".";   // glTF paths of edited meshes are relative to it
    nlohmann::json sceneJson;                     // the scene's file (its keys, for inverseOf)
    bool fromSceneSettings = false;   // the settings above are a scene's (else SessionStep adopts its frame's)
    // One-shot requests the frame loop handles (and clears).
    bool toggleRecording = false, screenshot = false;
    std::vector<int> addedMeshIds, removedMeshIds;   // this frame's, for the session's mesh events
    // This frame's, as applied (an added mesh with its id): the panels' (or a session's "edits"); those its undo
    // and redo applied are appliedHistoryEdits (a session's "history_edits").
    std::vector<SettingEdit> appliedEdits;
    // Drilling (session/drilling.h): the accumulated removal on the scan grid and the undo history of strokes and
    // setting edits, made when the session's scan is known (SessionStep::attachRemoval; null before); shared by
    // copies of the state. And this frame's drilling meshes and undo/redo commands, as applied, for the
    // session's frame.
    std::shared_ptr<plan::RemovalVolume> removal;
    std::shared_ptr<plan::UndoHistory> undoHistory;
    // Whether setting edits are undo steps: live, and sessions from version 7 (kUndoEditsVersion); an older
    // session's undo presses undid strokes only, and its replay must too.
    bool historyHoldsEdits = true;
    std::vector<SessionDrill> appliedDrills;
    std::vector<HistoryCommand> appliedHistory;
    std::vector<SettingEdit> appliedHistoryEdits;
    // This frame's drilling asked by actions (HoldDrill by mesh id, Undo, Redo), for applyDrilling.
    std::vector<SessionDrill> heldDrills;
    std::vector<HistoryCommand> historyPresses;

    static InteractionState fromScene(const Scene& scene);
    // The state a session starts from (its header), with geometry from the scene or the meshes' descriptions.
    static InteractionState fromSessionStart(const SessionHeader& header, const Scene& scene,
                                             const std::filesystem::path& sceneDirectory, const std::string& source);
    std::vector<SessionMeshStart> sessionMeshes() const;   // for a session header
    std::vector<SessionMesh> sessionPoses() const;         // for a session frame
    std::vector<plan::PosedMesh> posedMeshes() const;      // for the CPU clip test, picks and slices
    std::vector<SessionLight> sessionLights() const;       // for a session header
    std::vector<glm::dvec3> lightDirections() const;       // for a session frame
    int indexOf(int meshId) const;  // -1 when absent
    // Applies `actions` for a frame seen through `camera` at `viewportHeight` pixels (for drags).
    void apply(const std::vector<input::Action>& actions, const OrbitCamera& camera, int viewportHeight);
    // Applies setting edits (after the frame's actions): each value read by the scene reader's function for
    // its key (scene/setting_edit.h), then set where the scene's value was. `source` names them in errors
    // (a session line, or "<panel>"). Appends each, as applied, to appliedEdits. With `undo`, puts before its
    // contents the edits that undo them (inverseOf each, the last edit's first; an added mesh's removal).
    void applyEdits(const std::vector<SettingEdit>& edits, const std::string& source, std::vector<SettingEdit>* undo = nullptr);
    // The edits that would set back what `edit` changes, made from this state before it is applied: the
    // setting's value now, as the JSON such an edit carries (an edited key's last value, else the scene's, else
    // {} for a key the scene lacks: its defaults; a transfer function the scene names by path, written out).
    // A removed mesh comes back with its id, name, shape, pose, scale and clips_tubes (added last; its rotation
    // through rotation_deg, exact to double rounding); a removed light is added back and the lights after it
    // set back on their keys. Empty when the edit would fail (applyEdits reports that).
    std::vector<SettingEdit> inverseOf(const SettingEdit& edit) const;
    // The edits that turn the scene's settings into this state's (for a session header: a recording that
    // starts after edits), one per edited key; meshes are not among them (the header lists the meshes).
    std::vector<SettingEdit> settingEdits() const;
    // The scene file's current JSON of a key ("ambient_occlusion", "lights[0]", ...): the last edit's value,
    // else the scene's own (null when the scene does not have the key).
    nlohmann::json keyJson(const Scene& scene, const std::string& key) const;
    nlohmann::json keyJson(const std::string& key) const;   // against the scene the state was made from
    nlohmann::json keyJson(const std::string& key, const nlohmann::json& sceneJson) const;
    // The mesh AddMesh creates: a 15 mm sphere at the camera's target.
    static const char* addedMeshDescription();
};

// MoveLight's motion (input/actions.h): the light's direction in camera coordinates (right, up, towards the
// viewer) as azimuth atan2(x, z) and elevation asin(y); yaw adds to the azimuth, pitch to the elevation, which
// stays within +-89 degrees (a light does not flip over the pole). A world-space light is turned in the
// frame of `camera` and stays in world space; its length is kept. The one definition, for live input and
// for poses re-derived from a session's keys.
Light turnedLight(const Light& light, glm::dvec2 yawPitchRad, const OrbitCamera& camera);

// A clip mesh's geometry from its scene JSON (mesh/mesh_description.h); `source` names it in errors.
std::shared_ptr<const clip::TriangleMesh> meshFromDescription(const std::string& json, const std::string& source,
                                                              const std::filesystem::path& baseDirectory);

}  // namespace curette
