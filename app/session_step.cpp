#include "app/session_step.h"

#include "base/error.h"

namespace curette {

bool samePoses(const std::vector<SessionMesh>& a, const std::vector<SessionMesh>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (a[i].id != b[i].id || a[i].position != b[i].position || a[i].orientation != b[i].orientation || a[i].scale != b[i].scale)
            return false;
    return true;
}

SessionStep::SessionStep(InteractionState state, FrameDescription frame) : state_(std::move(state)), frame_(std::move(frame)) {
    frame_.shading = state_.shading;
    if (state_.lights.empty()) state_.lights = frame_.lights;
    frame_.lights = state_.lights;
}

StepChanges SessionStep::compare(const std::vector<SessionMesh>& before, ShadingMode shadingBefore, const std::vector<Light>& lightsBefore,
                                 bool meshesChanged) {
    StepChanges c;
    c.meshes = meshesChanged;
    c.poses = !samePoses(before, state_.sessionPoses());
    c.shading = state_.shading != shadingBefore;
    c.lights = state_.lights != lightsBefore;
    frame_.shading = state_.shading;
    frame_.lights = state_.lights;
    return c;
}

StepChanges SessionStep::apply(const std::vector<input::Action>& actions, int viewportHeight) {
    std::vector<SessionMesh> before = state_.sessionPoses();
    ShadingMode shadingBefore = state_.shading;
    std::vector<Light> lightsBefore = state_.lights;
    state_.addedMeshIds.clear();
    state_.removedMeshIds.clear();
    state_.apply(actions, frame_.camera, viewportHeight);
    return compare(before, shadingBefore, lightsBefore, !state_.addedMeshIds.empty() || !state_.removedMeshIds.empty());
}

StepChanges SessionStep::follow(const SessionFrame& f, const std::filesystem::path& sceneDirectory, const std::string& where) {
    std::vector<SessionMesh> before = state_.sessionPoses();
    ShadingMode shadingBefore = state_.shading;
    std::vector<Light> lightsBefore = state_.lights;
    if (f.lights) {
        if (f.lights->size() != state_.lights.size())
            throw InputError(where, "lights", "one direction per light of the session (" + std::to_string(state_.lights.size()) + ")",
                             std::to_string(f.lights->size()));
        for (std::size_t i = 0; i < f.lights->size(); ++i) state_.lights[i].direction = (*f.lights)[i];
    }
    for (const SessionAddedMesh& a : f.meshesAdded) {
        MeshState m;
        m.id = a.id;
        m.name = a.name;
        m.description = a.description;
        m.geometry = meshFromDescription(a.description, where + ": meshes_added.mesh", sceneDirectory);
        state_.meshes.push_back(m);
    }
    for (int id : f.meshesRemoved)
        if (int i = state_.indexOf(id); i >= 0) state_.meshes.erase(state_.meshes.begin() + i);
    for (const SessionMesh& r : f.meshes) {
        int i = state_.indexOf(r.id);
        if (i < 0) throw InputError(where, "meshes", "ids of meshes present at that frame", std::to_string(r.id));
        state_.meshes[static_cast<std::size_t>(i)].pose = {r.position, r.orientation};
        state_.meshes[static_cast<std::size_t>(i)].scale = r.scale;
    }
    state_.shading = f.shading;
    frame_.camera = f.camera;
    frame_.size = f.size;
    return compare(before, shadingBefore, lightsBefore, !f.meshesAdded.empty() || !f.meshesRemoved.empty());
}

void SessionStep::syncTo(clip::ClipMeshSet& set) const { syncClipMeshes(state_, set); }

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
