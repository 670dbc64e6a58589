#include "session/session_step.h"

#include "session/loaded_scene.h"
#include "base/error.h"

#include <set>

namespace curette {

bool samePoses(const std::vector<SessionMesh>& a, const std::vector<SessionMesh>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (a[i].id != b[i].id || a[i].position != b[i].position || a[i].orientation != b[i].orientation || a[i].scale != b[i].scale)
            return false;
    return true;
}

namespace {

// The frame's settings that come from the state (the rest, camera and size, the callers own).
void frameFromState(const InteractionState& state, FrameDescription& frame) {
    frame.shading = state.shading;
    frame.lights = state.lights;
    frame.raycast = state.raycast;
    frame.dos = state.dos;
    frame.ismos = state.ismos;
}

}  // namespace

SessionStep::SessionStep(InteractionState state, FrameDescription frame) : state_(std::move(state)), frame_(std::move(frame)) {
    if (state_.lights.empty()) state_.lights = frame_.lights;
    if (!state_.fromSceneSettings) {   // a state made by hand (tests, benches): the frame's settings
        state_.raycast = frame_.raycast;
        state_.dos = frame_.dos;
        state_.ismos = frame_.ismos;
        state_.fromSceneSettings = true;
    }
    frameFromState(state_, frame_);
}

SessionStep::Before SessionStep::begin() {
    Before before{state_.sessionPoses(), state_.shading, state_.lights};
    state_.addedMeshIds.clear();
    state_.removedMeshIds.clear();
    state_.appliedEdits.clear();
    state_.appliedHistoryEdits.clear();
    return before;
}

StepChanges SessionStep::compare(const Before& before, bool meshesChanged, bool removalChanged) {
    StepChanges c;
    c.removal = removalChanged;
    c.meshes = meshesChanged;
    c.poses = !samePoses(before.poses, state_.sessionPoses());
    c.shading = state_.shading != before.shading;
    c.lights = state_.lights != before.lights;
    c.settings = !state_.appliedEdits.empty() || !state_.appliedHistoryEdits.empty();
    for (const auto* edits : {&state_.appliedEdits, &state_.appliedHistoryEdits})
        for (const SettingEdit& e : *edits) c.meshes = c.meshes || e.setting == Setting::MeshShape;
    frameFromState(state_, frame_);
    return c;
}

StepChanges SessionStep::apply(const std::vector<input::Action>& actions, int viewportHeight, const std::vector<SettingEdit>& edits,
                               const std::string& source, const DrillInput& drill) {
    Before before = begin();
    state_.apply(actions, frame_.camera, viewportHeight);
    applyUndoableEdits(state_, edits, source);
    // Drilling from the caller (a version-5 session's recorded drilling) and from the actions (keys, devices).
    DrillInput all = drill;
    for (const SessionDrill& d : state_.heldDrills) addDrill(all.drills, d);
    all.history.insert(all.history.end(), state_.historyPresses.begin(), state_.historyPresses.end());
    bool removal = applyDrilling(state_, before.poses, all);
    return compare(before, !state_.addedMeshIds.empty() || !state_.removedMeshIds.empty(), removal);
}

void SessionStep::attachRemoval(glm::ivec3 dims, const glm::dmat4& indexToWorld, const plan::RemovalVolume* start) {
    if (state_.removal) return;
    state_.removal = start ? std::make_shared<plan::RemovalVolume>(*start) : std::make_shared<plan::RemovalVolume>(dims, indexToWorld);
    state_.undoHistory = std::make_shared<plan::UndoHistory>();
}

StepChanges SessionStep::follow(const SessionFrame& f, const std::filesystem::path& sceneDirectory, const std::string& where) {
    Before before = begin();
    // Meshes an edit adds or removes are also in meshes_added/meshes_removed: the edit makes them (it
    // carries every key of the mesh), after the ones the frame's actions made, as live.
    // The same for the edits an undo or redo makes (version 7), which the history applies below.
    std::set<int> addedByEdits, removedByEdits;
    for (const auto* edits : {&f.edits, &f.historyEdits})
        for (const SettingEdit& e : *edits) {
            if (e.setting == Setting::MeshAdd) addedByEdits.insert(e.target);
            if (e.setting == Setting::MeshRemove) removedByEdits.insert(e.target);
        }
    for (const SessionAddedMesh& a : f.meshesAdded) {
        if (addedByEdits.count(a.id)) continue;
        SceneClipMesh added{.name = a.name, .geometry = meshFromDescription(a.description, where + ": meshes_added.mesh", sceneDirectory)};
        state_.meshes.push_back(MeshState::make(a.id, added, a.description));
    }
    for (int id : f.meshesRemoved)
        if (int i = state_.indexOf(id); i >= 0 && !removedByEdits.count(id)) state_.meshes.erase(state_.meshes.begin() + i);
    applyUndoableEdits(state_, f.edits, where);
    // Every recorded pose and scale; `everyId`: each recorded id must be a mesh present now.
    auto placeAsRecorded = [&](bool everyId) {
        for (const SessionMesh& r : f.meshes) {
            int i = state_.indexOf(r.id);
            if (i < 0 && everyId) throw InputError(where, "meshes", "ids of meshes present at that frame", std::to_string(r.id));
            if (i < 0) continue;
            state_.meshes[static_cast<std::size_t>(i)].pose = {r.position, r.orientation};
            state_.meshes[static_cast<std::size_t>(i)].scale = r.scale;
        }
    };
    // An undo or redo of a setting edit (version 7) changes settings, lights and meshes: the history applies it
    // here, re-derived from the recorded presses, before the recorded lights and poses (which are after it);
    // the drilling's sweeps too, from the poses before the frame to the recorded ones.
    placeAsRecorded(false);
    bool removal = applyDrilling(state_, before.poses, DrillInput{f.drills, f.historyCommands});
    if (state_.appliedHistoryEdits != f.historyEdits)
        throw InputError(where, "history_edits", "the edits the frame's undo/redo applies (" + std::to_string(state_.appliedHistoryEdits.size()) + ")",
                         std::to_string(f.historyEdits.size()) + " others");
    // The lights' directions as recorded, after the edits (which may add or remove lights; a light edit
    // carries the direction the light had then).
    if (f.lights) {
        if (f.lights->size() != state_.lights.size())
            throw InputError(where, "lights", "one direction per light of the session at that frame (" + std::to_string(state_.lights.size()) + ")",
                             std::to_string(f.lights->size()));
        for (std::size_t i = 0; i < f.lights->size(); ++i) state_.lights[i].direction = (*f.lights)[i];
    }
    placeAsRecorded(true);
    state_.shading = f.shading;
    frame_.camera = f.camera;
    frame_.size = f.size;
    return compare(before, !f.meshesAdded.empty() || !f.meshesRemoved.empty(), removal);
}

void SessionStep::syncTo(clip::ClipMeshSet& set) const { syncClipMeshes(state_, set); }

void SessionStep::syncTo(Renderer& renderer, const std::vector<Tractogram>& tracts) {
    syncRenderer(state_, renderer, tracts, synced_);
    renderer.setRemoval(state_.removal);
}

void syncRenderer(const InteractionState& state, Renderer& renderer, const std::vector<Tractogram>& tracts, RendererSync& synced) {
    syncClipMeshes(state, renderer.clipMeshes());
    if (synced.transferFunction != state.transferFunctionVersion) {
        renderer.setTransferFunction(state.transferFunction);
        synced.transferFunction = state.transferFunctionVersion;
    }
    renderer.setLaoSettings(state.lao);   // changes nothing when equal
    if (synced.tubes != state.tubesVersion || synced.tubeShading != state.tubeShadingVersion) {
        if (state.tubes.empty() || synced.tubes != state.tubesVersion) {
            setSceneTubes(renderer, state.tubes, state.tubeRendering, tracts);
        } else {
            renderer.setTubeShading(sceneTubeShading(state.tubes, state.tubeRendering.shading));
        }
        synced.tubes = state.tubesVersion;
        synced.tubeShading = state.tubeShadingVersion;
    }
}

void syncClipMeshes(const InteractionState& state, clip::ClipMeshSet& set) {
    const std::vector<MeshState>& meshes = state.meshes;
    bool same = set.count() == static_cast<int>(meshes.size());
    for (std::size_t i = 0; same && i < meshes.size(); ++i)
        same = set.name(static_cast<int>(i)) == meshes[i].name && set.geometry(static_cast<int>(i)) == meshes[i].geometry.get();
    if (!same) {
        set.clear();
        for (const MeshState& m : meshes) set.add(m.geometry, m.scale, m.pose, m.name);
    }
    for (std::size_t i = 0; i < meshes.size(); ++i) {
        int index = static_cast<int>(i);
        set.setPose(index, meshes[i].pose);
        set.setScale(index, meshes[i].scale);
        set.setClipsTubes(index, meshes[i].clipsTubes);
    }
}

}  // namespace curette
