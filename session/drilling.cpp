#include "session/drilling.h"

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
    state.appliedDrillHistory.clear();
    if (!state.removal || !state.drillHistory) {
        if (!input.empty()) log::warn("drilling needs the session's scan grid; this frame's drilling is ignored");
        return false;
    }
    plan::RemovalVolume& removal = *state.removal;
    plan::DrillHistory& history = *state.drillHistory;
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
    for (DrillHistoryCommand c : input.history) {
        bool done = c == DrillHistoryCommand::Undo ? history.undo(removal) : history.redo(removal);
        if (done) state.appliedDrillHistory.push_back(c);
    }
    return removal.version() != version;
}

}  // namespace curette
