#include "session/interaction.h"

#include "base/error.h"
#include "base/json_reader.h"
#include "mesh/mesh_description.h"
#include "io/transfer_function_file.h"
#include "session/drilling.h"

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>

namespace curette {

const char* InteractionState::addedMeshDescription() { return R"({"shape": "sphere", "radius_mm": 15})"; }

std::shared_ptr<const clip::TriangleMesh> meshFromDescription(const std::string& json, const std::string& source,
                                                              const std::filesystem::path& baseDirectory) {
    nlohmann::json parsed = parseJson(json, source);
    return std::make_shared<const clip::TriangleMesh>(clip::meshFromJson(JsonReader(parsed, source), baseDirectory));
}

Light turnedLight(const Light& light, glm::dvec2 yawPitchRad, const OrbitCamera& camera) {
    const glm::dvec3 right = camera.right(), up = camera.up(), back = -camera.forward();
    double length = glm::length(light.direction);
    if (!(length > 0)) return light;
    glm::dvec3 d = light.direction / length;
    if (!light.cameraSpace) d = glm::dvec3(glm::dot(d, right), glm::dot(d, up), glm::dot(d, back));
    constexpr double limit = glm::radians(89.0);
    double azimuth = std::atan2(d.x, d.z) + yawPitchRad.x;
    double elevation = std::clamp(std::asin(std::clamp(d.y, -1.0, 1.0)) + yawPitchRad.y, -limit, limit);
    glm::dvec3 turned(std::cos(elevation) * std::sin(azimuth), std::sin(elevation), std::cos(elevation) * std::cos(azimuth));
    if (!light.cameraSpace) turned = turned.x * right + turned.y * up + turned.z * back;
    Light out = light;
    out.direction = length * turned;
    return out;
}

namespace {

// The state's copy of the scene's editable settings (InteractionState, scene/setting_edit.h).
void adoptSceneSettings(const Scene& scene, InteractionState& s) {
    s.transferFunction = scene.transferFunction;
    s.lao = scene.lao;
    s.raycast = scene.raycast;
    s.dos = scene.dos;
    s.ismos = scene.ismos;
    s.tubes = scene.tubes;
    s.tubeRendering = {scene.tubesAsLines, scene.tubeShading, scene.tubeBuild};
    s.clipMeshDisplay = scene.clipMeshDisplay;
    s.sceneLightKeys.clear();
    const nlohmann::json* lights = scene.json.is_object() && scene.json.contains("lights") ? &scene.json.at("lights") : nullptr;
    for (std::size_t i = 0; i < scene.lights.size(); ++i) {
        nlohmann::json key = lights && lights->is_array() && i < lights->size() ? (*lights)[i] : nlohmann::json::object();
        if (!key.contains("direction")) key["direction"] = {scene.lights[i].direction.x, scene.lights[i].direction.y, scene.lights[i].direction.z};
        s.sceneLightKeys.push_back(key);
    }
    s.sceneDirectory = scene.file.parent_path().empty() ? std::filesystem::path(".") : scene.file.parent_path();
    s.sceneJson = scene.json;
    s.fromSceneSettings = true;
}

std::string lightKey(std::size_t index) { return "lights[" + std::to_string(index) + "]"; }

// A light's scene JSON when no scene gave one (a state made without a scene, as tests and benches make):
// its direction, space and colour (its intensity folded in by the largest channel above 1).
nlohmann::json lightJson(const Light& light) {
    double intensity = std::max({1.0, light.color.r, light.color.g, light.color.b});
    glm::dvec3 c = light.color / intensity;
    return {{"direction", {light.direction.x, light.direction.y, light.direction.z}}, {"color", {c.r, c.g, c.b}}, {"intensity", intensity},
            {"space", light.cameraSpace ? "camera" : "world"}};
}

// The scene-file name of the key an edit sets ("lights[1]"); empty for mesh settings, for adding and
// removing lights (which set the lights' keys themselves, InteractionState::editedKeys) and for the shading,
// which keys and buttons change too: the state's `shading` is its value.
std::string editedKeyName(const SettingEdit& edit) {
    if (edit.setting == Setting::LightAdd || edit.setting == Setting::LightRemove || edit.setting == Setting::Shading) return {};
    const SettingInfo& info = settingInfo(edit.setting);
    switch (info.target) {
        case SettingTarget::None: return info.key;
        case SettingTarget::Light:
        case SettingTarget::Tubes: return std::string(info.key) + "[" + std::to_string(edit.target) + "]";
        case SettingTarget::Mesh: return {};
    }
    return {};
}

}  // namespace

MeshState MeshState::make(int id, const SceneClipMesh& mesh, std::string description) {
    MeshState m;
    m.id = id;
    m.name = mesh.name;
    m.description = std::move(description);
    m.geometry = mesh.geometry;
    m.pose = m.initialPose = mesh.pose;
    m.scale = mesh.scale;
    m.clipsTubes = mesh.clipsTubes;
    return m;
}

InteractionState InteractionState::fromScene(const Scene& scene) {
    InteractionState s;
    s.shading = scene.shading;
    s.lights = scene.lights;
    adoptSceneSettings(scene, s);
    for (const SceneClipMesh& m : scene.clipMeshes) s.meshes.push_back(MeshState::make(s.nextMeshId++, m));
    return s;
}

InteractionState InteractionState::fromSessionStart(const SessionHeader& header, const Scene& scene,
                                                    const std::filesystem::path& sceneDirectory, const std::string& source) {
    InteractionState s;
    // The scene's lights (their colours), turned as they were when recording started (version 2; a version 1
    // session has none: the scene's, as they were then).
    s.lights = scene.lights;
    adoptSceneSettings(scene, s);
    // The settings edited before recording started (version 3), before the lights' directions; then the
    // shading at the start (a header may carry a shading edit that a key overrode later).
    s.applyEdits(header.edits, source + " line 1: edits");
    s.appliedEdits.clear();
    s.historyHoldsEdits = header.version >= kUndoEditsVersion;
    s.shading = header.shading;
    if (header.lights) {
        if (header.lights->size() != s.lights.size())
            throw InputError(source, "line 1: lights",
                             "as many lights as the scene " + scene.file.string() + " and the header's edits make (" + std::to_string(s.lights.size()) + ")",
                             std::to_string(header.lights->size()));
        for (std::size_t i = 0; i < s.lights.size(); ++i) {
            const SessionLight& l = (*header.lights)[i];
            if (l.cameraSpace != s.lights[i].cameraSpace)
                throw InputError(source, "line 1: lights[" + std::to_string(i) + "].space",
                                 std::string("the scene's space for this light (\"") + (s.lights[i].cameraSpace ? "camera" : "world") + "\")");
            s.lights[i].direction = l.direction;
        }
        s.selectedLight = std::clamp(header.selectedLight, 0, std::max(0, static_cast<int>(s.lights.size()) - 1));
    }
    s.nextMeshId = header.nextMeshId;
    for (const SessionMeshStart& start : header.meshes) {
        // The scene mesh's geometry and clips_tubes, or an added mesh's own; the rest as recorded.
        SceneClipMesh mesh;
        if (!start.description.empty()) {
            mesh.geometry = meshFromDescription(start.description, source + " line 1: meshes[id " + std::to_string(start.id) + "].mesh", sceneDirectory);
        } else if (start.id < static_cast<int>(scene.clipMeshes.size())) {
            mesh = scene.clipMeshes[static_cast<std::size_t>(start.id)];
        } else {
            throw InputError(source, "line 1: meshes[id " + std::to_string(start.id) + "]",
                             "a scene mesh index (the scene has " + std::to_string(scene.clipMeshes.size()) + ") or a \"mesh\" description");
        }
        mesh.name = start.name;
        mesh.pose = start.pose;
        mesh.scale = start.scale;
        if (start.clipsTubes) mesh.clipsTubes = *start.clipsTubes;   // version 3
        MeshState m = MeshState::make(start.id, mesh, start.description);
        m.initialPose = start.initialPose;
        s.meshes.push_back(std::move(m));
    }
    return s;
}

std::vector<SessionMeshStart> InteractionState::sessionMeshes() const {
    std::vector<SessionMeshStart> out;
    for (const MeshState& m : meshes) out.push_back({m.id, m.name, m.description, m.pose, m.initialPose, m.scale, m.clipsTubes});
    return out;
}

std::vector<SessionMesh> InteractionState::sessionPoses() const {
    std::vector<SessionMesh> out;
    for (const MeshState& m : meshes) out.push_back({m.id, m.pose.position, m.pose.orientation, m.scale});
    return out;
}

std::vector<plan::PosedMesh> InteractionState::posedMeshes() const {
    std::vector<plan::PosedMesh> out;
    for (const MeshState& m : meshes) out.push_back({m.geometry, m.pose, m.scale});
    return out;
}

std::vector<SessionLight> InteractionState::sessionLights() const {
    std::vector<SessionLight> out;
    for (const Light& l : lights) out.push_back({l.direction, l.cameraSpace});
    return out;
}

std::vector<glm::dvec3> InteractionState::lightDirections() const {
    std::vector<glm::dvec3> out;
    for (const Light& l : lights) out.push_back(l.direction);
    return out;
}

int InteractionState::indexOf(int meshId) const {
    for (std::size_t i = 0; i < meshes.size(); ++i)
        if (meshes[i].id == meshId) return static_cast<int>(i);
    return -1;
}

std::vector<SettingEdit> InteractionState::inverseOf(const SettingEdit& edit) const {
    // A light's key as the panel starts from it (its direction now: MoveLight turns it without an edit).
    auto lightEntry = [&](std::size_t i) {
        nlohmann::json key = keyJson(lightKey(i));
        if (key.is_null()) key = i < sceneLightKeys.size() ? sceneLightKeys[i] : lightJson(lights[i]);
        key["direction"] = {lights[i].direction.x, lights[i].direction.y, lights[i].direction.z};
        return key;
    };
    auto object = [&](const std::string& key) {
        nlohmann::json j = keyJson(key);
        return j.is_null() ? nlohmann::json::object() : j;   // a key the scene lacks: its defaults
    };
    auto mesh = [&]() -> const MeshState* {
        int i = indexOf(edit.target);
        return i < 0 ? nullptr : &meshes[static_cast<std::size_t>(i)];
    };
    auto pose = [](const clip::RigidPose& p) {
        glm::dvec3 deg = clip::degreesFromOrientation(p.orientation);
        return nlohmann::json{{"position_mm", {p.position.x, p.position.y, p.position.z}}, {"rotation_deg", {deg.x, deg.y, deg.z}}};
    };
    const int t = edit.target;
    const bool light = t >= 0 && t < static_cast<int>(lights.size());
    switch (edit.setting) {
        case Setting::Shading: return {{Setting::Shading, -1, shadingModeName(shading)}};
        case Setting::TransferFunction: {
            nlohmann::json tf = keyJson("transfer_function");
            if (!tf.is_object()) tf = nlohmann::json::parse(io::writeTransferFunctionJson(transferFunction));   // a path or preset in the scene
            return {{Setting::TransferFunction, -1, tf}};
        }
        case Setting::AmbientOcclusion: return {{edit.setting, -1, object("ambient_occlusion")}};
        case Setting::Raycast: return {{edit.setting, -1, object("raycast")}};
        case Setting::Dos: return {{edit.setting, -1, object("dos")}};
        case Setting::Ismos: return {{edit.setting, -1, object("ismos")}};
        case Setting::TubeRendering: return {{edit.setting, -1, object("tube_rendering")}};
        case Setting::ClipMeshDisplay: return {{edit.setting, -1, object("clip_mesh_display")}};
        case Setting::Tubes: {
            nlohmann::json entry = object("tubes[" + std::to_string(t) + "]");
            entry.erase("path");
            return {{Setting::Tubes, t, entry}};
        }
        case Setting::Light:
            if (!light) return {};
            return {{Setting::Light, t, lightEntry(static_cast<std::size_t>(t))}};
        case Setting::LightAdd: return {{Setting::LightRemove, static_cast<int>(lights.size()), nullptr}};
        case Setting::LightRemove: {
            // Lights only append: add the last one back, then give each from the removed one on its old key.
            if (!light || lights.size() < 2) return {};
            std::vector<SettingEdit> out{{Setting::LightAdd, -1, lightEntry(lights.size() - 1)}};
            for (std::size_t i = static_cast<std::size_t>(t); i + 1 < lights.size(); ++i) out.push_back({Setting::Light, static_cast<int>(i), lightEntry(i)});
            return out;
        }
        case Setting::MeshAdd: return {};   // its id is known once applied: applyEdits makes the removal
        case Setting::MeshRemove: {
            const MeshState* m = mesh();
            if (!m) return {};
            nlohmann::json entry = pose(m->pose);
            entry["name"] = m->name;
            if (!m->description.empty()) {
                entry["mesh"] = nlohmann::json::parse(m->description);
            } else {   // a scene's mesh: its id is its index in the scene's "clip_meshes"
                const nlohmann::json* scene = sceneJson.is_object() && sceneJson.contains("clip_meshes") ? &sceneJson.at("clip_meshes") : nullptr;
                if (!scene || !scene->is_array() || m->id >= static_cast<int>(scene->size())) return {};
                entry["mesh"] = (*scene)[static_cast<std::size_t>(m->id)].at("mesh");
            }
            entry["scale"] = {m->scale.x, m->scale.y, m->scale.z};
            entry["clips_tubes"] = m->clipsTubes;
            return {{Setting::MeshAdd, m->id, entry}};
        }
        case Setting::MeshShape:
            if (const MeshState* m = mesh()) {
                if (!m->description.empty()) return {{edit.setting, t, nlohmann::json::parse(m->description)}};
                if (const auto* scene = sceneJson.is_object() && sceneJson.contains("clip_meshes") ? &sceneJson.at("clip_meshes") : nullptr;
                    scene && scene->is_array() && t < static_cast<int>(scene->size()))
                    return {{edit.setting, t, (*scene)[static_cast<std::size_t>(t)].at("mesh")}};
            }
            return {};
        case Setting::MeshScale:
            if (const MeshState* m = mesh()) return {{edit.setting, t, {m->scale.x, m->scale.y, m->scale.z}}};
            return {};
        case Setting::MeshClipsTubes:
            if (const MeshState* m = mesh()) return {{edit.setting, t, m->clipsTubes}};
            return {};
        case Setting::MeshPose:
            if (const MeshState* m = mesh()) return {{edit.setting, t, pose(m->pose)}};
            return {};
        case Setting::Count: break;
    }
    return {};
}

void InteractionState::applyEdits(const std::vector<SettingEdit>& edits, const std::string& source, std::vector<SettingEdit>* undo) {
    for (std::size_t k = 0; k < edits.size(); ++k) {
        SettingEdit edit = edits[k];
        // What undoes this edit, before it (the last edit's inverse first); an added mesh's once it has its id.
        if (undo) {
            std::vector<SettingEdit> inverse = edit.setting == Setting::MeshAdd ? std::vector<SettingEdit>{} : inverseOf(edit);
            undo->insert(undo->begin(), inverse.begin(), inverse.end());
        }
        const SettingInfo& info = settingInfo(edit.setting);
        const std::string where = "edits[" + std::to_string(k) + "]";
        auto fail = [&](const std::string& expected) -> void {
            throw InputError(source, where + "." + (info.targetKey ? info.targetKey : "setting"), expected, std::to_string(edit.target));
        };
        auto meshById = [&]() -> MeshState& {
            int i = indexOf(edit.target);
            if (i < 0) fail("the id of a clip mesh present at that frame");
            return meshes[static_cast<std::size_t>(i)];
        };
        SceneTubes tubeDefaults;
        if (edit.setting == Setting::Tubes) {
            if (edit.target < 0 || edit.target >= static_cast<int>(tubes.size()))
                fail("a bundle index below " + std::to_string(tubes.size()) + " (the scene's \"tubes\")");
            tubeDefaults = tubes[static_cast<std::size_t>(edit.target)];
            tubeDefaults.name = fileNameStems(tubeDefaults.path).back();
        }
        SettingValue value = readSettingValue(edit, source, where + ".value", sceneDirectory, tubeDefaults);
        switch (edit.setting) {
            case Setting::Shading: shading = std::get<ShadingMode>(value); break;
            case Setting::TransferFunction:
                transferFunction = std::get<TransferFunction>(value);
                ++transferFunctionVersion;
                break;
            case Setting::AmbientOcclusion: lao = std::get<LaoSettings>(value); break;
            case Setting::Raycast: raycast = std::get<RaycastSettings>(value); break;
            case Setting::Dos: dos = std::get<DosSettings>(value); break;
            case Setting::Ismos: {
                std::vector<IsmosLightShape> shapes = ismos.lightShapes;   // the lights' own keys stay
                ismos = std::get<IsmosSettings>(value);
                ismos.lightShapes = shapes;
                break;
            }
            case Setting::Light: {
                if (edit.target < 0 || edit.target >= static_cast<int>(lights.size()))
                    fail("a light index below " + std::to_string(lights.size()));
                const LightValue& v = std::get<LightValue>(value);
                lights[static_cast<std::size_t>(edit.target)] = v.light;
                ismos.lightShapes.resize(lights.size());
                ismos.lightShapes[static_cast<std::size_t>(edit.target)] = v.shape;
                break;
            }
            case Setting::LightAdd: {
                if (lights.size() >= kMaxSceneLights)
                    throw InputError(source, where + ".setting", "at most " + std::to_string(kMaxSceneLights) + " lights (a scene's limit)",
                                     "lights.add with " + std::to_string(lights.size()) + " lights");
                const LightValue& v = std::get<LightValue>(value);
                ismos.lightShapes.resize(lights.size());
                ismos.lightShapes.push_back(v.shape);
                editedKeys[lightKey(lights.size())] = edit.value;
                lights.push_back(v.light);
                break;
            }
            case Setting::LightRemove: {
                if (edit.target < 0 || edit.target >= static_cast<int>(lights.size()))
                    fail("a light index below " + std::to_string(lights.size()));
                if (lights.size() <= 1) fail("a light other than the last one (a scene keeps at least one light)");
                const std::size_t removed = static_cast<std::size_t>(edit.target);
                for (std::size_t i = 0; i < lights.size(); ++i)
                    if (!editedKeys.count(lightKey(i))) editedKeys[lightKey(i)] = i < sceneLightKeys.size() ? sceneLightKeys[i] : lightJson(lights[i]);
                for (std::size_t i = removed; i + 1 < lights.size(); ++i) editedKeys[lightKey(i)] = editedKeys[lightKey(i + 1)];
                editedKeys.erase(lightKey(lights.size() - 1));
                lights.erase(lights.begin() + edit.target);
                ismos.lightShapes.resize(lights.size() + 1);
                ismos.lightShapes.erase(ismos.lightShapes.begin() + edit.target);
                if (selectedLight > edit.target) --selectedLight;
                selectedLight = std::clamp(selectedLight, 0, static_cast<int>(lights.size()) - 1);
                break;
            }
            case Setting::TubeRendering: {
                const TubeRendering& v = std::get<TubeRendering>(value);
                if (v.lines != tubeRendering.lines || v.build != tubeRendering.build)
                    ++tubesVersion;   // lines and tubes, and where tubes are built, are other geometry
                tubeRendering = v;
                ++tubeShadingVersion;
                break;
            }
            case Setting::Tubes:
                tubes[static_cast<std::size_t>(edit.target)] = std::get<SceneTubes>(value);
                ++tubesVersion;
                break;
            case Setting::MeshAdd: {
                if (static_cast<int>(meshes.size()) >= clip::kMaxClipMeshes) fail("at most " + std::to_string(clip::kMaxClipMeshes) + " clip meshes");
                SceneClipMesh added = std::get<SceneClipMesh>(value);
                if (edit.target < 0) edit.target = nextMeshId;   // live: the next id; recorded: the id it had
                if (indexOf(edit.target) >= 0) fail("the id of a mesh not present yet");
                nextMeshId = std::max(nextMeshId, edit.target + 1);
                if (!edit.value.contains("name")) added.name = "added " + std::to_string(edit.target);
                MeshState m = MeshState::make(edit.target, added, edit.value.at("mesh").dump());
                meshes.push_back(m);
                addedMeshIds.push_back(m.id);
                break;
            }
            case Setting::MeshRemove: {
                MeshState& m = meshById();
                removedMeshIds.push_back(m.id);
                meshes.erase(meshes.begin() + indexOf(m.id));
                break;
            }
            case Setting::MeshShape: {
                MeshState& m = meshById();
                m.geometry = std::get<MeshGeometry>(value).mesh;
                m.description = edit.value.dump();
                break;
            }
            case Setting::MeshScale: meshById().scale = std::get<glm::dvec3>(value); break;
            case Setting::MeshClipsTubes: meshById().clipsTubes = std::get<bool>(value); break;
            case Setting::MeshPose: meshById().pose = std::get<clip::RigidPose>(value); break;
            case Setting::ClipMeshDisplay: clipMeshDisplay = std::get<ClipMeshDisplaySpec>(value); break;
            case Setting::Count: break;
        }
        if (std::string key = editedKeyName(edit); !key.empty()) editedKeys[key] = edit.value;
        if (undo && edit.setting == Setting::MeshAdd) undo->insert(undo->begin(), SettingEdit{Setting::MeshRemove, edit.target, nullptr});
        appliedEdits.push_back(edit);
    }
}

std::vector<SettingEdit> InteractionState::settingEdits() const {
    std::vector<SettingEdit> out;
    for (const auto& [key, value] : editedKeys) {
        if (key.rfind("lights[", 0) == 0) continue;   // below
        SettingEdit e;
        std::size_t bracket = key.find('[');
        e.setting = *settingFromKey(key.substr(0, bracket));
        if (bracket != std::string::npos) e.target = std::stoi(key.substr(bracket + 1));
        e.value = value;
        out.push_back(e);
    }
    // The lights: the edited ones among the scene's, then the scene's beyond the current count removed (from
    // the last), then the added ones: never more than the scene or the state has, never none.
    const std::size_t sceneCount = sceneLightKeys.size(), count = lights.size();
    for (std::size_t i = 0; i < std::min(sceneCount, count); ++i)
        if (auto it = editedKeys.find(lightKey(i)); it != editedKeys.end()) out.push_back({Setting::Light, static_cast<int>(i), it->second});
    for (std::size_t i = sceneCount; i-- > count;) out.push_back({Setting::LightRemove, static_cast<int>(i), nullptr});
    for (std::size_t i = sceneCount; i < count; ++i) out.push_back({Setting::LightAdd, -1, editedKeys.at(lightKey(i))});
    return out;
}

nlohmann::json InteractionState::keyJson(const Scene& scene, const std::string& key) const { return keyJson(key, scene.json); }

nlohmann::json InteractionState::keyJson(const std::string& key) const { return keyJson(key, sceneJson); }

nlohmann::json InteractionState::keyJson(const std::string& key, const nlohmann::json& sceneJson) const {
    if (auto it = editedKeys.find(key); it != editedKeys.end()) return it->second;
    std::size_t bracket = key.find('[');
    std::string name = key.substr(0, bracket);
    if (!sceneJson.is_object() || !sceneJson.contains(name)) return nullptr;
    const nlohmann::json& value = sceneJson.at(name);
    if (bracket == std::string::npos) return value;
    std::size_t index = static_cast<std::size_t>(std::stoi(key.substr(bracket + 1)));
    return value.is_array() && index < value.size() ? value[index] : nlohmann::json();
}

void InteractionState::apply(const std::vector<input::Action>& actions, const OrbitCamera& camera, int viewportHeight) {
    const glm::dvec3 right = camera.right(), up = camera.up(), forward = camera.forward();
    auto toWorld = [&](glm::dvec3 v, input::MotionFrame frame) {
        return frame == input::MotionFrame::World ? v : v.x * right + v.y * up + v.z * forward;
    };
    // Actions name meshes by index in the current list (what the mapper sees as "mesh count").
    auto mesh = [&](int index) -> MeshState* {
        return index >= 0 && index < static_cast<int>(meshes.size()) ? &meshes[static_cast<std::size_t>(index)] : nullptr;
    };
    heldDrills.clear();
    historyPresses.clear();
    for (const input::Action& action : actions) {
        if (auto* a = std::get_if<input::MoveMesh>(&action)) {
            if (MeshState* m = mesh(a->mesh)) {
                m->pose.position += toWorld(a->translationMm, a->frame);
                glm::dvec3 axis = toWorld(a->rotationRad, a->frame);
                double angle = glm::length(axis);
                if (angle > 0) m->pose.orientation = glm::normalize(glm::angleAxis(angle, axis / angle) * m->pose.orientation);
            }
        } else if (auto* g = std::get_if<input::GripMesh>(&action)) {
            if (MeshState* m = mesh(g->mesh)) {
                double angle = glm::length(g->rotationRad);
                glm::dquat turn = angle > 0 ? glm::angleAxis(angle, g->rotationRad / angle) : glm::dquat(1, 0, 0, 0);
                m->pose.position = g->pivotMm + turn * (m->pose.position - g->pivotMm) + g->translationMm;
                m->pose.orientation = glm::normalize(turn * m->pose.orientation);
            }
        } else if (auto* sc = std::get_if<input::ScaleMesh>(&action)) {
            // Within the scene reader's bounds on a scale (scene/scene_keys.cpp, readMeshScale).
            if (MeshState* m = mesh(sc->mesh)) m->scale = glm::clamp(m->scale * sc->factor, glm::dvec3(1e-6), glm::dvec3(1e6));
        } else if (auto* d = std::get_if<input::DragMesh>(&action)) {
            if (MeshState* m = mesh(d->mesh)) {
                // The view plane through the mesh: a pixel there spans depth / (pixels per mm at unit depth).
                double depth = std::max(1.0, glm::dot(m->pose.position - camera.position(), forward));
                double mmPerPixel = depth / camera.pixelsPerMmAtUnitDepth(std::max(viewportHeight, 1));
                m->pose.position += mmPerPixel * (d->pixels.x * right - d->pixels.y * up);
            }
        } else if (auto* s = std::get_if<input::SetShading>(&action)) {
            if (auto mode = parseShadingMode(s->mode)) shading = *mode;
        } else if (std::holds_alternative<input::CycleShading>(action)) {
            shading = nextShadingMode(shading);
        } else if (auto* r = std::get_if<input::ResetPose>(&action)) {
            if (MeshState* m = mesh(r->mesh)) m->pose = m->initialPose;
        } else if (std::holds_alternative<input::AddMesh>(action)) {
            if (static_cast<int>(meshes.size()) >= clip::kMaxClipMeshes) continue;  // at the limit: nothing
            const int id = nextMeshId++;
            const std::string description = addedMeshDescription();
            SceneClipMesh added{.name = "added " + std::to_string(id), .geometry = meshFromDescription(description, "<added mesh>", ".")};
            added.pose.position = camera.target;
            MeshState m = MeshState::make(id, added, description);
            meshes.push_back(m);
            addedMeshIds.push_back(m.id);
        } else if (auto* rm = std::get_if<input::RemoveMesh>(&action)) {
            if (MeshState* m = mesh(rm->mesh)) {
                removedMeshIds.push_back(m->id);
                meshes.erase(meshes.begin() + rm->mesh);
            }
        } else if (auto* ml = std::get_if<input::MoveLight>(&action)) {
            int i = ml->light < 0 ? selectedLight : ml->light;
            if (i >= 0 && i < static_cast<int>(lights.size()))
                lights[static_cast<std::size_t>(i)] = turnedLight(lights[static_cast<std::size_t>(i)], ml->yawPitchRad, camera);
        } else if (std::holds_alternative<input::NextLight>(action)) {
            if (!lights.empty()) selectedLight = (selectedLight + 1) % static_cast<int>(lights.size());
        } else if (std::holds_alternative<input::ToggleRecording>(action)) {
            toggleRecording = true;
        } else if (std::holds_alternative<input::Screenshot>(action)) {
            screenshot = true;
        } else if (auto* h = std::get_if<input::HoldDrill>(&action)) {
            if (MeshState* m = mesh(h->mesh)) addDrill(heldDrills, {m->id, h->erase});
        } else if (std::holds_alternative<input::Undo>(action)) {
            historyPresses.push_back(HistoryCommand::Undo);
        } else if (std::holds_alternative<input::Redo>(action)) {
            historyPresses.push_back(HistoryCommand::Redo);
        }
    }
}

}  // namespace curette
