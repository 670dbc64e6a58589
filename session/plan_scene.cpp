#include "session/plan_scene.h"

#include "base/atomic_file.h"
#include "base/error.h"
#include "session/removal_file.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

namespace curette {

namespace fs = std::filesystem;

namespace {

void makeAbsolute(nlohmann::json& value, const fs::path& directory) {
    if (!value.is_string()) return;
    fs::path p = value.get<std::string>();
    if (p.is_relative()) value = (directory / p).lexically_normal().string();
}

// A mesh description with its glTF path (relative to the scene file) made absolute.
nlohmann::json absoluteMesh(nlohmann::json mesh, const fs::path& directory) {
    if (mesh.is_object() && mesh.value("shape", "") == "gltf" && mesh.contains("path")) makeAbsolute(mesh["path"], directory);
    return mesh;
}

}  // namespace

glm::dvec3 rotationDegrees(const glm::dquat& q) {
    // The scene composes R = Rz(c) Ry(b) Rx(a); with m[col][row], m[0][2] = -sin b, m[1][2] = sin a cos b,
    // m[2][2] = cos a cos b, m[0][1] = cos b sin c, m[0][0] = cos b cos c.
    glm::dmat3 m = glm::mat3_cast(glm::normalize(q));
    double b = std::asin(std::clamp(-m[0][2], -1.0, 1.0));
    double a, c;
    if (std::abs(std::cos(b)) > 1e-9) {
        a = std::atan2(m[1][2], m[2][2]);
        c = std::atan2(m[0][1], m[0][0]);
    } else {  // gimbal lock: only a - c (or a + c) is defined; put it all in a
        c = 0;
        a = std::atan2(-m[2][1], m[1][1]);
    }
    return glm::degrees(glm::dvec3(a, b, c));
}

std::string planSceneJson(const Scene& scene, const std::string& sceneText, const InteractionState& state, const OrbitCamera* camera) {
    nlohmann::json root;
    try {
        root = nlohmann::json::parse(sceneText);
    } catch (const nlohmann::json::exception& e) {
        throw InputError(scene.file.string(), "(scene)", "the scene's JSON", e.what());
    }
    fs::path directory = fs::absolute(scene.file).parent_path();
    if (root.contains("volume")) makeAbsolute(root["volume"]["path"], directory);
    if (root.contains("transfer_function")) makeAbsolute(root["transfer_function"], directory);
    if (root.contains("tubes"))
        for (nlohmann::json& t : root["tubes"]) makeAbsolute(t["path"], directory);
    if (root.contains("labels"))
        for (nlohmann::json& l : root["labels"])
            for (const char* key : {"path", "table", "colors"})
                if (l.contains(key)) makeAbsolute(l[key], directory);
    nlohmann::json originals = root.contains("clip_meshes") ? root["clip_meshes"] : nlohmann::json::array();
    nlohmann::json meshes = nlohmann::json::array();
    for (const MeshState& m : state.meshes) {
        nlohmann::json entry;
        entry["name"] = m.name;
        if (!m.description.empty()) {
            entry["mesh"] = absoluteMesh(nlohmann::json::parse(m.description), directory);
        } else if (m.id >= 0 && static_cast<std::size_t>(m.id) < originals.size()) {
            entry["mesh"] = absoluteMesh(originals[static_cast<std::size_t>(m.id)]["mesh"], directory);
        } else {
            throw std::logic_error("planSceneJson: mesh " + std::to_string(m.id) + " has neither a description nor a scene entry");
        }
        entry["position_mm"] = {m.pose.position.x, m.pose.position.y, m.pose.position.z};
        glm::dvec3 r = rotationDegrees(m.pose.orientation);
        entry["rotation_deg"] = {r.x, r.y, r.z};
        entry["scale"] = {m.scale.x, m.scale.y, m.scale.z};
        entry["clips_tubes"] = m.clipsTubes;
        meshes.push_back(entry);
    }
    root["clip_meshes"] = meshes;
    root.erase("removal");
    root["shading"] = shadingModeName(state.shading);
    // Edited settings: the value of the last edit of each key (lights and tubes below).
    for (const auto& [key, value] : state.editedKeys)
        if (key.find('[') == std::string::npos) root[key] = value;
    if (!state.tubes.empty()) {
        for (std::size_t i = 0; i < state.tubes.size(); ++i) {
            auto edited = state.editedKeys.find("tubes[" + std::to_string(i) + "]");
            if (edited == state.editedKeys.end()) continue;
            nlohmann::json entry = edited->second;   // every key but the path
            entry["path"] = state.tubes[i].path.lexically_normal().string();
            makeAbsolute(entry["path"], directory);
            root["tubes"][i] = entry;
        }
    }
    // The lights as they are now: each one's JSON (edited or the scene's) with its current direction.
    nlohmann::json lights = nlohmann::json::array();
    for (std::size_t i = 0; i < state.lights.size(); ++i) {
        nlohmann::json entry = state.keyJson(scene, "lights[" + std::to_string(i) + "]");
        if (!entry.is_object()) entry = nlohmann::json::object();   // the default light of a scene without "lights"
        const glm::dvec3& d = state.lights[i].direction;
        entry["direction"] = {d.x, d.y, d.z};
        lights.push_back(entry);
    }
    root["lights"] = lights;
    if (camera) {
        root["camera"] = {{"target", {camera->target.x, camera->target.y, camera->target.z}},
                          {"distance_mm", camera->distanceMm},
                          {"azimuth_deg", camera->azimuthDeg},
                          {"elevation_deg", camera->elevationDeg},
                          {"fov_deg", camera->fovYDeg},
                          {"near_mm", camera->nearMm},
                          {"far_mm", camera->farMm}};
    }
    return root.dump(2) + "\n";
}

void saveScene(const fs::path& path, const Scene& scene, const std::string& sceneText, const InteractionState& state, const OrbitCamera* camera) {
    std::string json = planSceneJson(scene, sceneText, state, camera);
    if (state.removal && !state.removal->empty()) {
        fs::path removal = removalFileBeside(path);
        writeRemovalFile(removal, *state.removal);   // before the scene that names it
        nlohmann::ordered_json root = nlohmann::ordered_json::parse(json);
        root["removal"] = removal.filename().string();
        json = root.dump(2) + "\n";
    }
    writeFileAtomically(path, json);
}

}  // namespace curette
