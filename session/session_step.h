#pragma once
// One step of a session, the same for `view`, `record`, `replay` and the benches: a frame's input (live
// actions, actions re-derived from recorded reports, or recorded poses) -> the interaction state -> the
// FrameDescription and, through syncTo, the renderer's clip-mesh set. The only path by which meshes reach a
// renderer, so every per-mesh setting (geometry, scale, pose, clips_tubes) arrives by every command alike;
// and the only definition of "the poses changed".

#include "session/drilling.h"
#include "session/interaction.h"
#include "session/session.h"
#include "base/tractogram.h"
#include "render/passes/clip_mesh_set.h"
#include "input/actions.h"
#include "render/model/frame.h"
#include "render/renderer.h"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace curette {

struct StepChanges {
    bool poses = false;    // a position, an orientation or a scale
    bool meshes = false;   // a mesh added or removed
    bool shading = false;
    bool lights = false;   // a light (MoveLight, a recorded frame's lights, a light edit)
    bool settings = false; // a setting edit (scene/setting_edit.h)
    bool removal = false;  // drilling or its undo/redo changed the removal (session/drilling.h)
    bool any() const { return poses || meshes || shading || lights || settings || removal; }
};

// SessionStep::syncTo for a state without a step (a scene's first frame: render, bench raycast/dos).
void syncClipMeshes(const InteractionState& state, clip::ClipMeshSet& set);

// The versions of a state's settings a renderer was last handed (nullopt: never).
struct RendererSync {
    std::optional<std::uint64_t> transferFunction{}, tubes{}, tubeShading{};
    // A renderer configureRenderer set up holds the scene's settings: those of a state made from the scene,
    // whose versions start at 0 (InteractionState counts them up per edit).
    static RendererSync sceneSettings() { return {0, 0, 0}; }
};
// The one path by which a state's settings reach a renderer (configureRenderer for a scene's first frame,
// SessionStep::syncTo after edits): the clip meshes and LAO settings (cheap when unchanged), and the transfer
// function and tubes (rebuilt from `tracts`, one per scene bundle) when their versions differ from `synced`,
// which it then updates.
void syncRenderer(const InteractionState& state, Renderer& renderer, const std::vector<Tractogram>& tracts, RendererSync& synced);

// Pose equality, for every command: same ids in the same order, positions, orientations and scales.
bool samePoses(const std::vector<SessionMesh>& a, const std::vector<SessionMesh>& b);

class SessionStep {
public:
    SessionStep(InteractionState state, FrameDescription frame);

    InteractionState& state() { return state_; }
    const InteractionState& state() const { return state_; }
    // The frame to render: the camera, size, shading and lights of the last step (callers move the camera and
    // size). A state without lights adopts the frame's (a scene's first frame has the scene's).
    FrameDescription& frame() { return frame_; }
    const FrameDescription& frame() const { return frame_; }

    // Live input, or input re-derived from recorded reports: the actions applied through the interaction
    // state with the frame's camera, for a viewport `viewportHeight` pixels high (drags).
    // Then the frame's setting edits (the panels', or a session's recorded ones), `source` naming them in errors.
    // Then the frame's drilling (session/drilling.h): the actions' (HoldDrill, Undo, Redo) with
    // `drill`, drilling given as input instead (a version 5 session replayed from its reports).
    StepChanges apply(const std::vector<input::Action>& actions, int viewportHeight, const std::vector<SettingEdit>& edits = {},
                      const std::string& source = "<panel>", const DrillInput& drill = {});
    // Makes the state's drilled removal on the scan grid (a copy of `start`, the scene's or a session's removal
    // at its start, or empty; with an empty undo history) unless it has one: every command that steps a session
    // on a scan calls it, so drilling works alike in each.
    void attachRemoval(glm::ivec3 dims, const glm::dmat4& indexToWorld, const plan::RemovalVolume* start = nullptr);
    // A recorded frame followed as recorded (replay without --from-reports): meshes added and removed, every
    // pose and scale, the lights' directions, the setting edits, the shading, camera and image size. `where`
    // names the line in errors.
    StepChanges follow(const SessionFrame& recorded, const std::filesystem::path& sceneDirectory, const std::string& where);

    // Makes `set` match the state's meshes (index i = state().meshes[i]). Poses, scales and clips_tubes are set
    // (cheap: a rigid motion only changes a camera matrix); meshes are re-added only when the list changed.
    void syncTo(clip::ClipMeshSet& set) const;
    // Makes a renderer match the state through syncRenderer (the frame's raycast, dos, ismos and lights reach
    // it in frame()), and hands it the drilled removal.
    void syncTo(Renderer& renderer, const std::vector<Tractogram>& tracts);

private:
    // What a step compares against (the poses, shading and lights before it); begin() also clears the last
    // step's lists of added and removed meshes and applied edits.
    struct Before {
        std::vector<SessionMesh> poses;
        ShadingMode shading;
        std::vector<Light> lights;
    };
    Before begin();
    StepChanges compare(const Before& before, bool meshesChanged, bool removalChanged = false);

    InteractionState state_;
    FrameDescription frame_;
    // The state's setting versions the renderer was last given: at first the scene's (configureRenderer), not
    // the state's, so edits the state starts with (a session header's) reach the renderer at the first syncTo.
    RendererSync synced_ = RendererSync::sceneSettings();
};

}  // namespace curette
