#pragma once
// Applying input actions to the scene: the one place where device or keyboard motion becomes clip-mesh
// poses and light directions. Plain data, no GL: the session step (app/session_step.h) runs it for the live viewer, `curette
// record`, `curette replay` and the benches, so poses re-derived from recorded reports equal the recorded
// ones bit for bit.

#include "app/scene.h"
#include "app/session.h"
#include "clip/limits.h"
#include "clip/rigid_pose.h"
#include "clip/triangle_mesh.h"
#include "input/actions.h"
#include "render/camera.h"
#include "render/frame.h"

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
};

struct InteractionState {
    std::vector<MeshState> meshes;
    ShadingMode shading = ShadingMode::Phong;
    // The frame's lights (the scene's, as MoveLight turns them; empty: SessionStep adopts its frame's) and the
    // one MoveLight{-1} turns.
    std::vector<Light> lights;
    int selectedLight = 0;
    int nextMeshId = 0;
    // One-shot requests the frame loop handles (and clears).
    bool toggleRecording = false, screenshot = false;
    std::vector<int> addedMeshIds, removedMeshIds;   // this frame's, for the session's mesh events

    static InteractionState fromScene(const Scene& scene);
    // The state a session starts from (its header), with geometry from the scene or the meshes' descriptions.
    static InteractionState fromSessionStart(const SessionHeader& header, const Scene& scene,
                                             const std::filesystem::path& sceneDirectory, const std::string& source);
    std::vector<SessionMeshStart> sessionMeshes() const;   // for a session header
    std::vector<SessionMesh> sessionPoses() const;         // for a session frame
    std::vector<SessionLight> sessionLights() const;       // for a session header
    std::vector<glm::dvec3> lightDirections() const;       // for a session frame
    int indexOf(int meshId) const;  // -1 when absent
    // Applies `actions` for a frame seen through `camera` at `viewportHeight` pixels (for drags).
    void apply(const std::vector<input::Action>& actions, const OrbitCamera& camera, int viewportHeight);
    // The mesh AddMesh creates: a 15 mm sphere at the camera's target.
    static const char* addedMeshDescription();
};

// MoveLight's motion (input/actions.h): the light's direction in camera coordinates (right, up, towards the
// viewer) as azimuth atan2(x, z) and elevation asin(y); yaw adds to the azimuth, pitch to the elevation, which
// stays within +-89 degrees (a light does not flip over the pole). A world-space light is turned in the
// frame of `camera` and stays in world space; its length is kept. The one definition, for live input and
// for poses re-derived from a session's keys.
Light turnedLight(const Light& light, glm::dvec2 yawPitchRad, const OrbitCamera& camera);

// A clip mesh's geometry from its scene JSON (clip/mesh_description.h); `source` names it in errors.
std::shared_ptr<const clip::TriangleMesh> meshFromDescription(const std::string& json, const std::string& source,
                                                              const std::filesystem::path& baseDirectory);

}  // namespace curette
