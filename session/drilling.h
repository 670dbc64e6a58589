#pragma once
// Drilling in a session (the drill issue): while a mesh's drill control is held, the volume it sweeps between
// frames is removed (erase: restored) on the scan grid (plan/removal_volume.h, plan/drill_sweep.h); a stroke
// (some mesh drilling, from the frame it starts to the frame none does) is one undo step, and so is a frame's
// setting edits (plan/undo_history.h: one history, Ctrl+Z undoes the last of either).
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
    std::vector<HistoryCommand> history;
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
// appliedHistory; an undo or redo of a setting edit applies its edits (InteractionState::applyEdits) and
// records them in appliedHistoryEdits. Returns whether the removal changed.
bool applyDrilling(InteractionState& state, const std::vector<SessionMesh>& posesBefore, const DrillInput& input);

// Applies a frame's setting edits (the panels', or a session's "edits") and, when the state's history holds
// edits (InteractionState::historyHoldsEdits), makes them one undo step: the frame's edits together, undone
// by their inverses (InteractionState::inverseOf) in reverse order. One edit of the same value setting on
// consecutive frames (a slider dragged) joins the last step (plan::UndoHistory::pushEdit).
void applyUndoableEdits(InteractionState& state, const std::vector<SettingEdit>& edits, const std::string& source);

}  // namespace curette
