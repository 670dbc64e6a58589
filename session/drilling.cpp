#include "session/drilling.h"

#include "base/json_reader.h"
#include "base/log.h"

#include <algorithm>
#include <set>

namespace curette {

void addDrill(std::vector<SessionDrill>& drills, SessionDrill drill) {
    auto same = std::find_if(drills.begin(), drills.end(), [&](const SessionDrill& d) { return d.mesh == drill.mesh; });
    if (same == drills.end()) drills.push_back(drill);
    else same->erase = same->erase && drill.erase;
}

std::optional<plan::DrillTool> drillToolOf(const MeshState& mesh) {
    if (!mesh.geometry || !mesh.geometry->solid) return std::nullopt;
    return plan::DrillTool{*mesh.geometry->solid, mesh.scale};
}

bool applyDrilling(InteractionState& state, const std::vector<SessionMesh>& posesBefore, const DrillInput& input) {
    state.appliedDrills.clear();
    state.appliedHistory.clear();
    state.appliedHistoryEdits.clear();
    if (!state.removal || !state.undoHistory) {
        if (!input.empty()) log::warn("drilling needs the session's scan grid; this frame's drilling is ignored");
        return false;
    }
    plan::RemovalVolume& removal = *state.removal;
    plan::UndoHistory& history = *state.undoHistory;
    std::uint64_t version = removal.version();
    if (input.drills.empty()) history.endStroke(removal);
    else history.beginStroke();
    for (const SessionDrill& d : input.drills) {
        int i = state.indexOf(d.mesh);
        if (i < 0) continue;
        const MeshState& mesh = state.meshes[static_cast<std::size_t>(i)];
        std::optional<plan::DrillTool> tool = drillToolOf(mesh);
        if (!tool) {
            static std::set<std::string> warned;
            if (warned.insert(mesh.name).second)
                log::warn("mesh \"" + mesh.name + "\" cannot drill: a burr is a sphere, box, cylinder or capsule");
            continue;
        }
        clip::RigidPose from = mesh.pose;
        for (const SessionMesh& p : posesBefore)
            if (p.id == d.mesh) from = {p.position, p.orientation};
        plan::DrillSweep sweep(*tool, from, mesh.pose);
        plan::applySweep(removal, sweep, d.erase, history.before());
        state.appliedDrills.push_back(d);
    }
    for (HistoryCommand c : input.history) {
        plan::UndoResult done = c == HistoryCommand::Undo ? history.undo(removal) : history.redo(removal);
        if (!done) continue;
        state.appliedHistory.push_back(c);
        if (done.edits.is_null()) continue;   // a stroke: its masks are back
        // A setting edit: its stored edits, read back as a session's are, applied as the panels' are, and
        // recorded apart from the frame's own edits.
        std::vector<SettingEdit> edits;
        for (const JsonReader& e : JsonReader(done.edits, "<undo history>", "edits").elements(0, 1 << 20))
            edits.push_back(readSettingEdit(e, state.sceneDirectory));
        std::size_t first = state.appliedEdits.size();
        state.applyEdits(edits, "<undo history>");
        auto applied = state.appliedEdits.begin() + static_cast<std::ptrdiff_t>(first);
        state.appliedHistoryEdits.insert(state.appliedHistoryEdits.end(), applied, state.appliedEdits.end());
        state.appliedEdits.erase(applied, state.appliedEdits.end());
    }
    history.endFrame();
    return removal.version() != version;
}

void applyUndoableEdits(InteractionState& state, const std::vector<SettingEdit>& edits, const std::string& source) {
    // (applyDrilling, once a frame after this, ends the history's frame.)
    if (edits.empty()) return;
    bool undoable = state.historyHoldsEdits && state.undoHistory && state.removal;
    std::vector<SettingEdit> undo;
    std::size_t first = state.appliedEdits.size();
    state.applyEdits(edits, source, undoable ? &undo : nullptr);
    if (!undoable) return;
    nlohmann::json undoJson = nlohmann::json::array(), redoJson = nlohmann::json::array();
    auto session = [](const SettingEdit& e) { return nlohmann::json::parse(settingEditJson(e).dump()); };   // as a session has it
    for (const SettingEdit& e : undo) undoJson.push_back(session(e));
    for (std::size_t i = first; i < state.appliedEdits.size(); ++i) redoJson.push_back(session(state.appliedEdits[i]));
    // A drag: one edit of a value setting (not adding or removing), joined with the last frame's of it.
    std::string mergeKey;
    if (edits.size() == 1 && edits[0].setting != Setting::MeshAdd && edits[0].setting != Setting::MeshRemove &&
        edits[0].setting != Setting::LightAdd && edits[0].setting != Setting::LightRemove)
        mergeKey = std::string(settingInfo(edits[0].setting).key) + "#" + std::to_string(edits[0].target);
    state.undoHistory->pushEdit(*state.removal, std::move(undoJson), std::move(redoJson), mergeKey);
}

}  // namespace curette
