#include "session/session.h"

#include "base/atomic_file.h"
#include "base/error.h"
#include "base/json_reader.h"
#include "base/log.h"
#include "mesh/limits.h"
#include "input/mapping.h"
#include "input/raw_reports.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

namespace curette {

namespace {

nlohmann::ordered_json vec(glm::dvec3 v) { return {v.x, v.y, v.z}; }

nlohmann::ordered_json device(const SessionDevice& d) {
    return {{"id", d.id}, {"family", d.family}, {"path", d.path}, {"product", d.product}, {"bus", d.bus},
            {"vendor_id", d.vendorId}, {"product_id", d.productId}};
}

SessionDevice readDevice(const JsonReader& r) {
    SessionDevice d;
    d.id = r.at("id").integer(0, 1 << 30);
    d.family = r.at("family").oneOf({"dualshock4", "dualsense", "switch_pro", "xbox_bt", "spacemouse"});
    if (auto v = r.find("path")) d.path = v->string();
    if (auto v = r.find("product")) d.product = v->string();
    if (auto v = r.find("bus")) d.bus = v->string();
    if (auto v = r.find("vendor_id")) d.vendorId = v->integer(0, 65535);
    if (auto v = r.find("product_id")) d.productId = v->integer(0, 65535);
    r.finish();
    return d;
}

nlohmann::ordered_json quaternion(const glm::dquat& q) { return {q.w, q.x, q.y, q.z}; }

glm::dquat readQuaternion(const JsonReader& r) {
    glm::dvec4 q = r.vec4(-1e3, 1e3);
    if (!(glm::length(q) > 1e-6)) r.fail("a quaternion [w, x, y, z] of non-zero length");
    return glm::dquat(q.x, q.y, q.z, q.w);
}

// A light's direction (version 2 records): three finite numbers, not all zero.
glm::dvec3 readLightDirection(const JsonReader& r) {
    glm::dvec3 d = r.vec3(-1e6, 1e6);
    if (!(glm::length(d) > 1e-9)) r.fail("a light direction [x, y, z] of non-zero length");
    return d;
}

// Keys a version 1 session cannot have (they came with version 2).
void requireVersion2(const JsonReader& r, int version) {
    if (version < 2) r.fail("nothing: session version " + std::to_string(version) + " has no lights (they came with version 2)");
}

// Keys of version 3 (setting edits).
void requireVersion3(const JsonReader& r, int version) {
    if (version < 3) r.fail("nothing: session version " + std::to_string(version) + " has no setting edits (they came with version 3)");
}

// Keys of version 4 (hold requests).
void requireVersion4(const JsonReader& r, int version) {
    if (version < 4) r.fail("nothing: session version " + std::to_string(version) + " has no hold requests (they came with version 4)");
}

// Adding and removing lights came with version 4 too.
void requireVersion4Lights(const JsonReader& r, int version) {
    if (version < 4) r.fail("a setting of session version " + std::to_string(version) + " (adding and removing lights came with version 4)");
}

// Keys of version 6 (head-mounted display sessions).
void requireVersion6(const JsonReader& r, int version) {
    if (version < 6) r.fail("nothing: session version " + std::to_string(version) + " has no head-mounted display (it came with version 6)");
}

// A pose in the room (metres) and, for an eye, its field of view [left, right, up, down] in radians.
nlohmann::ordered_json roomPoseJson(const TrackedView& v, bool withFov) {
    nlohmann::ordered_json j = {{"position_m", vec(v.positionM)}, {"orientation", quaternion(v.orientation)}};
    if (withFov) j["fov_rad"] = {v.fov.angleLeft, v.fov.angleRight, v.fov.angleUp, v.fov.angleDown};
    return j;
}

// Reads the keys roomPoseJson writes (the caller finishes the object).
TrackedView readRoomPose(const JsonReader& r, bool withFov) {
    TrackedView v;
    v.positionM = r.at("position_m").vec3(-1e4, 1e4);
    v.orientation = readQuaternion(r.at("orientation"));
    if (withFov) {
        std::vector<double> a = r.at("fov_rad").numbers(4, -1.57, 1.57);
        v.fov = {a[0], a[1], a[2], a[3]};
        if (!(v.fov.angleLeft < v.fov.angleRight && v.fov.angleDown < v.fov.angleUp))
            r.at("fov_rad").fail("[left, right, up, down] in radians with left < right and down < up");
    }
    return v;
}

nlohmann::ordered_json xrHeaderJson(const SessionXr& xr) {
    return {{"space", xr.space == RoomSpace::Stage ? "stage" : "local"},
            {"recommended_size", {{xr.recommendedSize[0].x, xr.recommendedSize[0].y}, {xr.recommendedSize[1].x, xr.recommendedSize[1].y}}},
            {"runtime", xr.runtime},
            {"system", xr.system}};
}

SessionXr readXrHeader(const JsonReader& r, int version) {
    requireVersion6(r, version);
    SessionXr xr;
    xr.space = r.at("space").oneOf({"stage", "local"}) == "stage" ? RoomSpace::Stage : RoomSpace::Local;
    std::vector<JsonReader> sizes = r.at("recommended_size").elements(2, 2);
    for (std::size_t eye = 0; eye < 2; ++eye) xr.recommendedSize[eye] = glm::ivec2(sizes[eye].vec2(1, 16384));
    for (std::size_t eye = 0; eye < 2; ++eye)
        if (glm::dvec2(xr.recommendedSize[eye]) != sizes[eye].vec2(1, 16384)) sizes[eye].fail("[width, height] in whole pixels");
    if (auto v = r.find("runtime")) xr.runtime = v->string();
    if (auto v = r.find("system")) xr.system = v->string();
    r.finish();
    return xr;
}

nlohmann::ordered_json xrFrameJson(const SessionXrFrame& f) {
    nlohmann::ordered_json j;
    j["display_time_ns"] = f.displayTimeNs;
    if (f.head) j["head"] = roomPoseJson(*f.head, false);
    if (f.views) j["views"] = {roomPoseJson((*f.views)[0], true), roomPoseJson((*f.views)[1], true)};
    j["hands"] = nlohmann::ordered_json::array();
    for (const SessionXrHand& h : f.hands) {
        nlohmann::ordered_json hand = {{"tracked", h.tracked}};
        if (h.tracked) hand.update(roomPoseJson(h.grip, false));
        hand["squeeze"] = h.squeeze;
        hand["trigger"] = h.trigger;
        hand["thumbstick"] = {h.thumbstick.x, h.thumbstick.y};
        hand["shading"] = h.shadingPressed;
        hand["volume"] = h.moveVolume;
        hand["erase"] = h.erase;
        j["hands"].push_back(hand);
    }
    if (f.anchor)
        j["anchor"] = {{"volume_centre_m", vec(f.anchor->volumeCentreRoomM)}, {"volume_turn", quaternion(f.anchor->volumeTurnRoom)},
                       {"volume_scale", f.anchor->volumeScale}};
    return j;
}

// Keys of version 7 (moving the volume, erasing and undo/redo on the controllers).
void requireVersion7(const JsonReader& r, int version) {
    if (version < kXrVolumeVersion)
        r.fail("nothing: session version " + std::to_string(version) + " has no volume moved by hand (it came with version 7)");
}

SessionXrFrame readXrFrame(const JsonReader& r, int version) {
    SessionXrFrame f;
    f.displayTimeNs = static_cast<std::int64_t>(r.at("display_time_ns").unsignedInteger(std::uint64_t(1) << 62));
    if (auto head = r.find("head")) {
        f.head = readRoomPose(*head, false);
        head->finish();
    }
    if (auto views = r.find("views")) {
        std::vector<JsonReader> list = views->elements(2, 2);
        f.views.emplace();
        for (std::size_t eye = 0; eye < 2; ++eye) {
            (*f.views)[eye] = readRoomPose(list[eye], true);
            list[eye].finish();
        }
    }
    std::vector<JsonReader> hands = r.at("hands").elements(2, 2);
    for (std::size_t i = 0; i < 2; ++i) {
        const JsonReader& h = hands[i];
        SessionXrHand& hand = f.hands[i];
        hand.tracked = h.at("tracked").boolean();
        if (hand.tracked) hand.grip = readRoomPose(h, false);
        hand.squeeze = h.at("squeeze").number(0, 1);
        hand.trigger = h.at("trigger").number(0, 1);
        hand.thumbstick = h.at("thumbstick").vec2(-1, 1);
        hand.shadingPressed = h.at("shading").boolean();
        if (auto v = h.find("volume")) {
            requireVersion7(*v, version);
            hand.moveVolume = v->boolean();
        }
        if (auto v = h.find("erase")) {
            requireVersion7(*v, version);
            hand.erase = v->boolean();
        }
        h.finish();
    }
    if (auto a = r.find("anchor")) {
        requireVersion7(*a, version);
        f.anchor.emplace();
        f.anchor->volumeCentreRoomM = a->at("volume_centre_m").vec3(-1e4, 1e4);
        f.anchor->volumeTurnRoom = readQuaternion(a->at("volume_turn"));
        if (auto scale = a->find("volume_scale")) {
            if (version < kXrTwoHandVersion)
                scale->fail("nothing: session version " + std::to_string(version) + " has no volume scaled by two hands (it came with version 8)");
            f.anchor->volumeScale = scale->number(1e-3, 1e3);
        }
        a->finish();
    }
    r.finish();
    return f;
}

nlohmann::ordered_json editsJson(const std::vector<SettingEdit>& edits) {
    nlohmann::ordered_json j = nlohmann::ordered_json::array();
    for (const SettingEdit& e : edits) j.push_back(settingEditJson(e));
    return j;
}

nlohmann::ordered_json inputStateJson(const input::InputPipelineState& s) {
    nlohmann::ordered_json j;
    j["devices"] = nlohmann::ordered_json::array();
    for (const auto& [id, d] : s.devices) {
        nlohmann::ordered_json axes = nlohmann::ordered_json::array();
        for (float a : d.state.axes) axes.push_back(a);
        j["devices"].push_back({{"id", id}, {"family", input::familyName(d.family)}, {"axes", axes}, {"buttons", d.state.buttons}});
    }
    j["mapper"] = {{"held_meshes", s.mapper.heldMeshes}, {"bound_devices", s.mapper.boundDevices}, {"previous_buttons", s.mapper.previousButtons}};
    j["keyboard"] = {{"previous_keys", s.keyboard.previousKeys}, {"selected_mesh", s.keyboard.selectedMesh}};
    return j;
}

// The largest keys word of a version: 32 bits before version 6, then one bit per input::Key.
std::uint64_t maxKeys(int version) {
    return version < kDrillFromInputVersion ? 0xFFFFFFFFu : (std::uint64_t{1} << static_cast<int>(input::Key::Count)) - 1;
}

input::InputPipelineState readInputState(const JsonReader& r, std::size_t bindings, int version) {
    input::InputPipelineState s;
    for (const JsonReader& d : r.at("devices").elements(0, 64)) {
        input::DeviceSnapshot snapshot{};
        snapshot.id = d.at("id").integer(0, 1 << 30);
        auto family = input::familyFromName(d.at("family").oneOf({"dualshock4", "dualsense", "switch_pro", "xbox_bt", "spacemouse"}));
        snapshot.family = *family;
        std::vector<JsonReader> axes = d.at("axes").elements(input::AxisCount, input::AxisCount);
        for (std::size_t i = 0; i < axes.size(); ++i) snapshot.state.axes[i] = static_cast<float>(axes[i].number(-1, 1));
        snapshot.state.buttons = static_cast<std::uint32_t>(d.at("buttons").unsignedInteger(0xFFFFFFFFu));
        d.finish();
        s.devices[snapshot.id] = snapshot;
    }
    JsonReader m = r.at("mapper");
    auto list = [&](const char* key, int min, std::int64_t max) {
        std::vector<std::int64_t> values;
        for (const JsonReader& v : m.at(key).elements(bindings, bindings))
            values.push_back(min < 0 ? v.integer(min, static_cast<int>(max)) : static_cast<std::int64_t>(v.unsignedInteger(static_cast<std::uint64_t>(max))));
        return values;
    };
    for (std::int64_t v : list("held_meshes", 0, 1 << 20)) s.mapper.heldMeshes.push_back(static_cast<int>(v));
    for (std::int64_t v : list("bound_devices", -1, 1 << 30)) s.mapper.boundDevices.push_back(static_cast<int>(v));
    for (std::int64_t v : list("previous_buttons", 0, 0xFFFFFFFFll)) s.mapper.previousButtons.push_back(static_cast<std::uint32_t>(v));
    m.finish();
    JsonReader k = r.at("keyboard");
    s.keyboard.previousKeys = k.at("previous_keys").unsignedInteger(maxKeys(version));
    s.keyboard.selectedMesh = k.at("selected_mesh").integer(0, 1 << 20);
    k.finish();
    r.finish();
    return s;
}

// JSON of one session line; a syntax error names the session line (not the line within the JSON text).
nlohmann::json parseLine(std::string_view text, const std::string& file, std::size_t line) {
    try {
        return parseJson(text, file);
    } catch (const InputError& e) {
        std::string field = e.field();
        if (auto comma = field.find(", column"); comma != std::string::npos) field = field.substr(comma + 2);
        throw InputError(file, "line " + std::to_string(line) + " (" + field + ")", e.expected(), e.got());
    }
}

}  // namespace

std::string sessionHeaderLine(const SessionHeader& h) {
    nlohmann::ordered_json j;
    j["format"] = "curette-session";
    j["version"] = h.version;
    j["scene"] = h.scene;
    j["created"] = h.created;
    j["devices"] = nlohmann::ordered_json::array();
    for (const SessionDevice& d : h.devices) j["devices"].push_back(device(d));
    j["mapping"] = nlohmann::ordered_json::parse(h.mappingJson.empty() ? R"({"bindings": []})" : h.mappingJson);
    j["shading"] = shadingModeName(h.shading);
    j["meshes"] = nlohmann::ordered_json::array();
    for (const SessionMeshStart& m : h.meshes) {
        nlohmann::ordered_json e = {{"id", m.id}, {"name", m.name}};
        if (!m.description.empty()) e["mesh"] = nlohmann::ordered_json::parse(m.description);
        e["position_mm"] = vec(m.pose.position);
        e["orientation"] = quaternion(m.pose.orientation);
        e["initial_position_mm"] = vec(m.initialPose.position);
        e["initial_orientation"] = quaternion(m.initialPose.orientation);
        e["scale"] = vec(m.scale);
        if (m.clipsTubes) e["clips_tubes"] = *m.clipsTubes;
        j["meshes"].push_back(e);
    }
    j["next_mesh_id"] = h.nextMeshId;
    if (h.lights) {
        j["lights"] = nlohmann::ordered_json::array();
        for (const SessionLight& l : *h.lights) j["lights"].push_back({{"direction", vec(l.direction)}, {"space", l.cameraSpace ? "camera" : "world"}});
        j["selected_light"] = h.selectedLight;
    }
    if (!h.edits.empty()) j["edits"] = editsJson(h.edits);
    j["input_state"] = inputStateJson(h.inputState);
    j["keyboard"] = {{"mm_per_s", h.keyboardMmPerSecond}, {"deg_per_s", h.keyboardDegPerSecond}};
    if (!h.removal.empty()) j["removal"] = {{"file", h.removal}, {"digest", h.removalDigest}};
    if (h.xr) j["xr"] = xrHeaderJson(*h.xr);
    return j.dump();
}

std::string sessionFrameLine(const SessionFrame& f) {
    nlohmann::ordered_json j;
    j["frame"] = f.index;
    j["time"] = f.time;
    j["dt"] = f.dt;
    j["size"] = {f.size.x, f.size.y};
    j["camera"] = {{"target", vec(f.camera.target)}, {"distance_mm", f.camera.distanceMm}, {"azimuth_deg", f.camera.azimuthDeg},
                   {"elevation_deg", f.camera.elevationDeg}, {"fov_deg", f.camera.fovYDeg}, {"near_mm", f.camera.nearMm},
                   {"far_mm", f.camera.farMm}};
    j["shading"] = shadingModeName(f.shading);
    j["meshes"] = nlohmann::ordered_json::array();
    for (const SessionMesh& m : f.meshes)
        j["meshes"].push_back({{"id", m.id}, {"position_mm", vec(m.position)},
                               {"orientation", quaternion(m.orientation)},
                               {"scale", vec(m.scale)}});
    if (f.lights) {
        j["lights"] = nlohmann::ordered_json::array();
        for (glm::dvec3 d : *f.lights) j["lights"].push_back(vec(d));
    }
    j["keys"] = f.keys;
    j["drag"] = {f.drag.x, f.drag.y};
    if (f.lightDrag != glm::dvec2(0.0)) j["light_drag"] = {f.lightDrag.x, f.lightDrag.y};
    if (!f.devicesAdded.empty()) {
        j["devices_added"] = nlohmann::ordered_json::array();
        for (const SessionDevice& d : f.devicesAdded) j["devices_added"].push_back(device(d));
    }
    if (!f.devicesRemoved.empty()) j["devices_removed"] = f.devicesRemoved;
    if (!f.meshesAdded.empty()) {
        j["meshes_added"] = nlohmann::ordered_json::array();
        for (const SessionAddedMesh& m : f.meshesAdded)
            j["meshes_added"].push_back({{"id", m.id}, {"name", m.name}, {"mesh", nlohmann::ordered_json::parse(m.description)}});
    }
    if (!f.meshesRemoved.empty()) j["meshes_removed"] = f.meshesRemoved;
    if (!f.edits.empty()) j["edits"] = editsJson(f.edits);
    if (!f.drills.empty()) {
        j["drill"] = nlohmann::ordered_json::array();
        for (const SessionDrill& d : f.drills) j["drill"].push_back({{"mesh", d.mesh}, {"erase", d.erase}});
    }
    if (!f.historyEdits.empty()) j["history_edits"] = editsJson(f.historyEdits);
    if (!f.historyCommands.empty()) {
        j["drill_history"] = nlohmann::ordered_json::array();
        for (HistoryCommand c : f.historyCommands) j["drill_history"].push_back(c == HistoryCommand::Undo ? "undo" : "redo");
    }
    if (!f.holds.empty()) {
        j["holds"] = nlohmann::ordered_json::array();
        for (const input::HoldRequest& h : f.holds)
            j["holds"].push_back({{"binding", h.binding == input::kKeyboardBinding ? nlohmann::ordered_json("keyboard") : nlohmann::ordered_json(h.binding)},
                                  {"mesh", h.mesh}});
    }
    if (f.xr) j["xr"] = xrFrameJson(*f.xr);
    j["reports"] = nlohmann::ordered_json::array();
    for (const SessionReport& r : f.reports) j["reports"].push_back({{"device", r.device}, {"time", r.time}, {"bytes", input::toHex(r.bytes)}});
    return j.dump();
}

namespace {

// The lines of a session, without their line ends; trailing empty lines dropped.
std::vector<std::string_view> sessionLines(std::string_view text) {
    std::vector<std::string_view> lines;
    std::size_t start = 0;
    while (start < text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string_view::npos) end = text.size();
        std::string_view line = text.substr(start, end - start);
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        lines.push_back(line);
        start = end + 1;
    }
    while (!lines.empty() && lines.back().empty()) lines.pop_back();
    return lines;
}

// What the frames need of the header, and what they change as they are read.
struct FrameContext {
    std::string file;
    std::filesystem::path directory;  // the scene's folder: glTF paths in edits are relative to it
    int version = 0;
    std::size_t bindings = 0;         // the mapping's, for the frames' hold requests
    std::optional<std::size_t> headerLights;  // how many lights line 1 lists, when it lists them
    std::set<int> meshIds, deviceIds;  // of the header and the frames so far
    std::size_t lightCount = 0;        // after each frame's edits
    bool xr = false;                   // the header has "xr": its frames may have theirs
};

SessionMeshStart readMeshStart(const JsonReader& m, int version) {
    SessionMeshStart mesh;
    mesh.id = m.at("id").integer(0, 1 << 20);
    mesh.name = m.at("name").string();
    if (auto d = m.find("mesh")) mesh.description = d->json().dump();
    mesh.pose = {m.at("position_mm").vec3(-1e6, 1e6), readQuaternion(m.at("orientation"))};
    mesh.initialPose = {m.at("initial_position_mm").vec3(-1e6, 1e6), readQuaternion(m.at("initial_orientation"))};
    mesh.scale = m.at("scale").vec3(1e-9, 1e6);
    if (auto c = m.find("clips_tubes")) {
        requireVersion3(*c, version);
        mesh.clipsTubes = c->boolean();
    }
    m.finish();
    return mesh;
}

void readHeaderLights(const JsonReader& r, const JsonReader& lights, SessionHeader& header) {
    requireVersion2(lights, header.version);
    std::vector<SessionLight> list;
    for (const JsonReader& l : lights.elements(0, 64)) {
        SessionLight light;
        light.direction = readLightDirection(l.at("direction"));
        light.cameraSpace = l.at("space").oneOf({"camera", "world"}) == "camera";
        l.finish();
        list.push_back(light);
    }
    header.selectedLight = r.at("selected_light").integer(0, std::max(0, static_cast<int>(list.size()) - 1));
    header.lights = std::move(list);
}

void readHeaderEdits(const JsonReader& edits, const std::filesystem::path& directory, SessionHeader& header) {
    requireVersion3(edits, header.version);
    for (const JsonReader& e : edits.elements(0, 1024)) {
        SettingEdit edit = readSettingEdit(e, directory);
        if (settingInfo(edit.setting).target == SettingTarget::Mesh)
            e.at("setting").fail("a setting that is not a clip mesh's (the header's \"meshes\" hold those)");
        if (edit.setting == Setting::LightAdd || edit.setting == Setting::LightRemove) requireVersion4Lights(e.at("setting"), header.version);
        header.edits.push_back(std::move(edit));
    }
}

// Line 1 (always strict): the scene, devices, mapping and meshes the frames start from.
FrameContext readHeader(std::string_view line, const std::string& file, const std::filesystem::path& path, SessionHeader& header) {
    FrameContext context;
    context.file = file;
    nlohmann::json json = parseLine(line, file, 1);
    JsonReader r(json, file, "line 1:");
    if (!r.isObject() || !r.has("format") || r.at("format").string() != "curette-session")
        throw InputError(file, "line 1: format", "\"curette-session\" (is this a curette session?)");
    int version = r.at("version").integer(0, 1 << 20);
    if (version < kOldestSessionVersion || version > kSessionVersion)
        throw InputError(file, "line 1: version",
                         std::to_string(kOldestSessionVersion) + " to " + std::to_string(kSessionVersion) + " (this curette reads session versions " +
                             std::to_string(kOldestSessionVersion) + " to " + std::to_string(kSessionVersion) + ")",
                         std::to_string(version));
    header.version = context.version = version;
    header.scene = r.at("scene").string();
    // Where the scene is: glTF paths in edits are relative to its folder (checked when read).
    std::filesystem::path scenePath = header.scene;
    if (scenePath.is_relative()) scenePath = path.parent_path() / scenePath;
    context.directory = scenePath.parent_path();
    if (auto c = r.find("created")) header.created = c->string();
    for (const JsonReader& d : r.at("devices").elements(0, 64)) header.devices.push_back(readDevice(d));
    header.mappingJson = r.at("mapping").json().dump();
    context.bindings = input::parseMapping(header.mappingJson, file + " line 1: mapping").bindings.size();
    auto mode = parseShadingMode(r.at("shading").string());
    if (!mode) r.at("shading").fail("one of " + shadingModeList());
    header.shading = *mode;
    for (const JsonReader& m : r.at("meshes").elements(0, 64)) header.meshes.push_back(readMeshStart(m, version));
    header.nextMeshId = r.at("next_mesh_id").integer(0, 1 << 20);
    for (const SessionMeshStart& m : header.meshes)
        if (m.id >= header.nextMeshId) r.at("next_mesh_id").fail("an id above every mesh id in \"meshes\"");
    if (auto lights = r.find("lights")) readHeaderLights(r, *lights, header);
    if (auto edits = r.find("edits")) readHeaderEdits(*edits, context.directory, header);
    header.inputState = readInputState(r.at("input_state"), context.bindings, version);
    if (auto removal = r.find("removal")) {
        if (version < kDrillFromInputVersion)
            removal->fail("nothing: session version " + std::to_string(version) + " has no removal at the start (it came with version 6)");
        header.removal = removal->at("file").string();
        if (header.removal.empty()) removal->at("file").fail("a file name (relative to the session file's folder)");
        header.removalDigest = removal->at("digest").string();
        if (header.removalDigest.size() != 64 || header.removalDigest.find_first_not_of("0123456789abcdef") != std::string::npos)
            removal->at("digest").fail("64 lower-case hex digits (the removal's SHA-256 digest)");
        removal->finish();
    }
    for (const auto& entry : header.inputState.devices) {
        int id = entry.first;
        if (std::none_of(header.devices.begin(), header.devices.end(), [id](const SessionDevice& h) { return h.id == id; }))
            r.at("input_state").fail("device ids listed in \"devices\" (found " + std::to_string(id) + ")");
    }
    if (auto k = r.find("keyboard")) {
        header.keyboardMmPerSecond = k->at("mm_per_s").number(0, 1e4);
        header.keyboardDegPerSecond = k->at("deg_per_s").number(0, 1e4);
        k->finish();
    }
    if (auto xr = r.find("xr")) header.xr = readXrHeader(*xr, version);
    r.finish();
    context.xr = header.xr.has_value();

    if (header.lights) context.headerLights = context.lightCount = header.lights->size();
    for (const SessionMeshStart& m : header.meshes) context.meshIds.insert(m.id);
    for (const SessionDevice& d : header.devices) context.deviceIds.insert(d.id);
    return context;
}

OrbitCamera readCamera(const JsonReader& c) {
    OrbitCamera camera;
    camera.target = c.at("target").vec3(-1e6, 1e6);
    camera.distanceMm = c.at("distance_mm").number(1e-3, 1e6);
    camera.azimuthDeg = c.at("azimuth_deg").number(-1e6, 1e6);
    camera.elevationDeg = c.at("elevation_deg").number(-90, 90);
    camera.fovYDeg = c.at("fov_deg").number(1, 170);
    camera.nearMm = c.at("near_mm").number(1e-6, 1e7);
    camera.farMm = c.at("far_mm").number(1e-6, 1e8);
    c.finish();
    return camera;
}

// meshes_added, meshes_removed and every mesh's pose.
void readFrameMeshes(const JsonReader& r, SessionFrame& f, FrameContext& context) {
    if (auto added = r.find("meshes_added"))
        for (const JsonReader& m : added->elements(0, 64)) {
            SessionAddedMesh a{m.at("id").integer(0, 1 << 20), m.at("name").string(), m.at("mesh").json().dump()};
            m.finish();
            context.meshIds.insert(a.id);
            f.meshesAdded.push_back(a);
        }
    if (auto removed = r.find("meshes_removed"))
        for (const JsonReader& m : removed->elements(0, 64)) f.meshesRemoved.push_back(m.integer(0, 1 << 20));
    for (const JsonReader& m : r.at("meshes").elements(0, 64)) {
        SessionMesh mesh;
        mesh.id = m.at("id").integer(0, 1 << 20);
        if (!context.meshIds.count(mesh.id)) m.at("id").fail("the id of a mesh in the header or in an earlier meshes_added");
        mesh.position = m.at("position_mm").vec3(-1e6, 1e6);
        mesh.orientation = readQuaternion(m.at("orientation"));
        mesh.scale = m.at("scale").vec3(1e-9, 1e6);
        m.finish();
        f.meshes.push_back(mesh);
    }
}

// A frame's "edits", or its "history_edits" (version 7), into `out`.
void readFrameEdits(const JsonReader& edits, std::vector<SettingEdit>& out, FrameContext& context) {
    requireVersion3(edits, context.version);
    for (const JsonReader& e : edits.elements(0, 1024)) {
        out.push_back(readSettingEdit(e, context.directory));
        Setting setting = out.back().setting;
        if (setting == Setting::MeshAdd && !context.meshIds.count(out.back().target))
            e.at("mesh").fail("the id of a mesh in this frame's meshes_added (where an added mesh is listed too)");
        if (setting == Setting::LightAdd || setting == Setting::LightRemove) {
            requireVersion4Lights(e.at("setting"), context.version);
            context.lightCount = setting == Setting::LightAdd ? context.lightCount + 1 : std::max<std::size_t>(context.lightCount, 1) - 1;
        }
    }
}

// Every light's direction after the frame's edits (which may add or remove lights).
std::vector<glm::dvec3> readFrameLights(const JsonReader& lights, const FrameContext& context) {
    requireVersion2(lights, context.version);
    if (!context.headerLights) lights.fail("nothing (line 1 lists no lights)");
    const std::size_t lightCount = context.lightCount;
    if (!lights.isArray() || lights.size() != lightCount)
        lights.fail("an array of " + std::to_string(lightCount) + " light directions [x, y, z], one per light of line 1" +
                    (lightCount != *context.headerLights ? " and the lights added and removed since" : ""));
    std::vector<glm::dvec3> directions;
    for (const JsonReader& l : lights.elements(lightCount, lightCount)) directions.push_back(readLightDirection(l));
    return directions;
}

std::vector<input::HoldRequest> readHolds(const JsonReader& holds, const FrameContext& context) {
    requireVersion4(holds, context.version);
    std::vector<input::HoldRequest> requests;
    for (const JsonReader& h : holds.elements(0, 64)) {
        input::HoldRequest hold;
        JsonReader binding = h.at("binding");
        const nlohmann::json& b = binding.json();
        if (b.is_number_integer() && b.get<std::int64_t>() >= 0 && b.get<std::int64_t>() < static_cast<std::int64_t>(context.bindings))
            hold.binding = b.get<int>();
        else if (!(b.is_string() && b.get<std::string>() == "keyboard"))
            binding.fail("\"keyboard\" or the index of one of the " + std::to_string(context.bindings) + " bindings of line 1's mapping");
        hold.mesh = h.at("mesh").integer(0, clip::kMaxClipMeshes - 1);
        h.finish();
        requests.push_back(hold);
    }
    return requests;
}

// devices_added, devices_removed and the raw reports of known devices.
void readFrameDevices(const JsonReader& r, SessionFrame& f, FrameContext& context) {
    if (auto added = r.find("devices_added"))
        for (const JsonReader& d : added->elements(0, 64)) {
            f.devicesAdded.push_back(readDevice(d));
            context.deviceIds.insert(f.devicesAdded.back().id);
        }
    if (auto removed = r.find("devices_removed"))
        for (const JsonReader& d : removed->elements(0, 64)) f.devicesRemoved.push_back(d.integer(0, 1 << 30));
    for (const JsonReader& rep : r.at("reports").elements(0, 100000)) {
        SessionReport report;
        report.device = rep.at("device").integer(0, 1 << 30);
        if (!context.deviceIds.count(report.device)) rep.at("device").fail("the id of a device in the header or in an earlier devices_added");
        report.time = rep.at("time").number(0, 1e9);
        report.bytes = input::fromHex(rep.at("bytes").string(), context.file, rep.path() + ".bytes");
        if (report.bytes.empty()) rep.at("bytes").fail("at least one byte (the report ID)");
        rep.finish();
        f.reports.push_back(std::move(report));
    }
}

// Session line `number` (from 2): one frame. Its fields are read in the order of their errors' precedence.
SessionFrame readFrame(std::string_view line, std::size_t number, FrameContext& context) {
    const std::string where = "line " + std::to_string(number);
    nlohmann::json json = parseLine(line, context.file, number);
    JsonReader r(json, context.file, where + ":");
    SessionFrame f;
    f.index = r.at("frame").unsignedInteger(1u << 31);
    f.time = r.at("time").number(0, 1e9);
    f.dt = r.at("dt").number(0, 10);
    glm::dvec2 size = r.at("size").vec2(1, 16384);
    f.size = glm::ivec2(size);
    f.camera = readCamera(r.at("camera"));
    auto mode = parseShadingMode(r.at("shading").string());
    if (!mode) r.at("shading").fail("one of " + shadingModeList());
    f.shading = *mode;
    readFrameMeshes(r, f, context);
    if (auto edits = r.find("edits")) readFrameEdits(*edits, f.edits, context);
    if (auto edits = r.find("history_edits")) {
        if (context.version < kUndoEditsVersion)
            edits->fail("nothing: session version " + std::to_string(context.version) + " undoes strokes only (edits came with version 7)");
        readFrameEdits(*edits, f.historyEdits, context);
    }
    if (auto lights = r.find("lights")) f.lights = readFrameLights(*lights, context);
    if (auto holds = r.find("holds")) f.holds = readHolds(*holds, context);
    if (auto drills = r.find("drill")) {
        if (context.version < 5) drills->fail("nothing: session version " + std::to_string(context.version) + " has no drilling (it came with version 5)");
        for (const JsonReader& d : drills->elements(0, clip::kMaxClipMeshes)) {
            SessionDrill drill;
            drill.mesh = d.at("mesh").integer(0, 1 << 30);
            drill.erase = d.at("erase").boolean();
            d.finish();
            f.drills.push_back(drill);
        }
    }
    if (auto history = r.find("drill_history")) {
        if (context.version < 5) history->fail("nothing: session version " + std::to_string(context.version) + " has no drilling (it came with version 5)");
        for (const JsonReader& c : history->elements(0, 64))
            f.historyCommands.push_back(c.oneOf({"undo", "redo"}) == "undo" ? HistoryCommand::Undo : HistoryCommand::Redo);
    }
    f.keys = r.at("keys").unsignedInteger(maxKeys(context.version));
    f.drag = r.at("drag").vec2(-1e5, 1e5);
    if (auto drag = r.find("light_drag")) {
        requireVersion2(*drag, context.version);
        f.lightDrag = drag->vec2(-1e5, 1e5);
    }
    if (auto xr = r.find("xr")) {
        requireVersion6(*xr, context.version);
        if (!context.xr) xr->fail("nothing (line 1 has no \"xr\": this is not a head-mounted display session)");
        f.xr = readXrFrame(*xr, context.version);
    }
    readFrameDevices(r, f, context);
    r.finish();
    return f;
}

}  // namespace

Session parseSession(std::string_view text, const std::filesystem::path& path, bool lenient) {
    Session session;
    session.file = path;
    const std::vector<std::string_view> lines = sessionLines(text);
    const std::string file = path.string();
    if (lines.empty()) throw InputError(file, "line 1", "a session header", "an empty file");
    FrameContext context = readHeader(lines[0], file, path, session.header);
    for (std::size_t n = 1; n < lines.size(); ++n) {
        try {
            session.frames.push_back(readFrame(lines[n], n + 1, context));
        } catch (const InputError& e) {
            if (!lenient) throw;
            session.warning = std::string(e.what()) + "; replaying the " + std::to_string(session.frames.size()) + " frames before it";
            log::warn(session.warning);
            break;
        }
    }
    return session;
}

std::filesystem::path sessionScenePath(const Session& session) {
    std::filesystem::path scene = session.header.scene;
    return scene.is_relative() ? session.file.parent_path() / scene : scene;
}

Session readSession(const std::filesystem::path& path, bool lenient) {
    std::vector<std::uint8_t> bytes = readFileBytes(path);
    return parseSession(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), path, lenient);
}

SessionRecorder::SessionRecorder(std::filesystem::path path, SessionHeader header, double checkpointSeconds)
    : path_(std::move(path)), header_(sessionHeaderLine(header)), checkpointSeconds_(checkpointSeconds) {
    write();  // an empty session at once: the path is writable, or we learn now
}

SessionRecorder::~SessionRecorder() {
    try {
        finish();
    } catch (const std::exception& e) {
        log::error(std::string("could not write the session: ") + e.what());
    }
}

void SessionRecorder::add(const SessionFrame& frame) {
    lines_.push_back(sessionFrameLine(frame));
    if (frame.time - lastCheckpoint_ >= checkpointSeconds_) {
        lastCheckpoint_ = frame.time;
        write();
    }
}

void SessionRecorder::finish() {
    if (finished_) return;
    finished_ = true;
    write();
}

void SessionRecorder::write() {
    std::string text = header_ + "\n";
    for (const std::string& line : lines_) text += line + "\n";
    writeFileAtomically(path_, text);
}

}  // namespace curette
