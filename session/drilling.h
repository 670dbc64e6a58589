#pragma once
// Drilling in a session (the drill issue): while a mesh's drill control is held, the volume it sweeps between
// frames is removed (erase: restored) on the scan grid (plan/removal_volume.h, plan/drill_sweep.h); a stroke
// (some mesh drilling, from the frame it starts to the frame none does) is one undo step (plan/drill_history.h).
// The burr is the analytic solid of the mesh's primitive (sphere, box, cylinder, capsule), scaled like the mesh;
// other meshes (cone, torus, glTF) do not drill, and say so once in the log.

#include "plan/drill_sweep.h"
#include "session/interaction.h"

#include <optional>
#include <vector>

namespace curette {

// A frame's drilling input: the meshes (by id) whose drill or erase control is held, and undo/redo presses.
struct DrillInput {
    std::vector<SessionDrill> drills;
    std::vector<DrillHistoryCommand> history;
    bool empty() const { return drills.empty() && history.empty(); }
};

// Adds a mesh's drill control to a frame's drilling: one entry per mesh, whichever controls hold it (keys,
// devices, controllers, a script); drill wins over erase.
void addDrill(std::vector<SessionDrill>& drills, SessionDrill drill);

// The burr a mesh drills with, or none when its geometry has no analytic solid.
std::optional<plan::DrillTool> drillToolOf(const MeshState& mesh);

// Applies one frame's drilling to `state` (its removal must be attached): each drilling mesh sweeps from its
// pose in `posesBefore` (where it was before the frame; a mesh added this frame sweeps from where it is) to its
// pose now; a stroke opens at the first drilling frame and closes at the first frame without; then the undo and
// redo commands (which close an open stroke first). Records what it applied in state.appliedDrills and
// appliedDrillHistory. Returns whether the removal changed.
bool applyDrilling(InteractionState& state, const std::vector<SessionMesh>& posesBefore, const DrillInput& input);

}  // namespace curette
