#include "input/mapping.h"

#include "base/atomic_file.h"
#include "base/error.h"
#include "base/json_reader.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace curette::input {

namespace {

const std::vector<std::string> kGamepadAxes = {"left_x", "left_y", "right_x", "right_y", "left_trigger", "right_trigger", "triggers", "shoulders"};
const std::vector<std::string> kSixDofAxes = {"tx", "ty", "tz", "rx", "ry", "rz"};
const std::vector<std::string> kActions = {"cycle_mesh", "cycle_shading", "reset_pose", "add_mesh", "remove_mesh", "toggle_recording",
                                           "screenshot", "shading:solid", "shading:phong", "shading:lao", "shading:cao", "shading:dos", "shading:ismos",
                                           "drill", "erase", "undo", "redo", "undo_stroke", "redo_stroke"};
const std::vector<std::string> kFamilies = {"gamepad", "dualshock4", "dualsense", "switch_pro", "xbox_bt", "spacemouse"};

bool familyMatches(const std::string& wanted, DeviceFamily family) {
    return wanted == familyName(family) || (wanted == "gamepad" && isGamepad(family));
}

// Radial dead zone on a stick, rescaled so the output starts at 0 at the edge of the zone and reaches 1
// at full deflection (continuous, no step).
glm::dvec2 radial(double x, double y, double deadZone) {
    double m = std::sqrt(x * x + y * y);
    if (m <= deadZone || m == 0.0) return {0.0, 0.0};
    double scaled = std::min(1.0, (m - deadZone) / (1.0 - deadZone));
    return glm::dvec2(x, y) * (scaled / m);
}

double axial(double v, double deadZone) {
    double a = std::abs(v);
    if (a <= deadZone) return 0.0;
    return std::copysign(std::min(1.0, (a - deadZone) / (1.0 - deadZone)), v);
}

}  // namespace

double ResponseCurve::apply(double v) const {
    if (kind == Linear) return v;
    return std::copysign(std::pow(std::abs(v), exponent), v);
}

double processedAxis(const DeviceState& s, DeviceFamily family, const std::string& name, const MotionBinding& b) {
    if (name == "none") return 0.0;
    bool invert = !name.empty() && name[0] == '-';
    std::string base = invert ? name.substr(1) : name;
    double v = 0.0;
    if (isGamepad(family)) {
        if (base == "left_x" || base == "left_y") {
            glm::dvec2 stick = radial(s.axes[LeftX], s.axes[LeftY], b.deadZone);
            v = base == "left_x" ? stick.x : stick.y;
        } else if (base == "right_x" || base == "right_y") {
            glm::dvec2 stick = radial(s.axes[RightX], s.axes[RightY], b.deadZone);
            v = base == "right_x" ? stick.x : stick.y;
        } else if (base == "left_trigger") {
            v = axial(s.axes[LeftTrigger], b.deadZone);
        } else if (base == "right_trigger") {
            v = axial(s.axes[RightTrigger], b.deadZone);
        } else if (base == "triggers") {
            v = axial(s.axes[RightTrigger], b.deadZone) - axial(s.axes[LeftTrigger], b.deadZone);
        } else if (base == "shoulders") {
            v = (s.pressed(RightShoulder) ? 1.0 : 0.0) - (s.pressed(LeftShoulder) ? 1.0 : 0.0);
        }
    } else {
        for (std::size_t i = 0; i < kSixDofAxes.size(); ++i)
            if (base == kSixDofAxes[i]) v = axial(s.axes[i], b.deadZone);
    }
    v = b.curve.apply(v);
    return invert ? -v : v;
}

MappingConfig parseMapping(std::string_view text, const std::string& source) {
    nlohmann::json json = parseJson(text, source);
    JsonReader root(json, source);
    MappingConfig config;
    for (const JsonReader& b : root.at("bindings").elements(1, 16)) {
        DeviceBinding binding;
        JsonReader device = b.at("device");
        binding.family = device.at("family").oneOf(kFamilies);
        if (auto i = device.find("index")) binding.index = i->integer(0, 15);
        device.finish();
        if (auto m = b.find("mesh")) binding.mesh = m->integer(0, 15);
        if (auto f = b.find("frame")) binding.frame = f->oneOf({"camera", "world"}) == "world" ? MotionFrame::World : MotionFrame::Camera;
        bool gamepad = binding.family != "spacemouse";
        auto motion = [&](const char* key, const char* speedKey, MotionBinding& m) {
            auto r = b.find(key);
            if (!r) return;
            std::vector<JsonReader> axes = r->at("axes").elements(3, 3);
            std::vector<std::string> allowed = gamepad ? kGamepadAxes : kSixDofAxes;
            std::vector<std::string> names{"none"};
            for (const std::string& a : allowed) names.push_back(a), names.push_back("-" + a);
            for (std::size_t i = 0; i < 3; ++i) m.axes[i] = axes[i].oneOf(names);
            if (auto d = r->find("dead_zone")) m.deadZone = d->number(0.0, 0.95);
            if (auto c = r->find("curve")) {
                m.curve.kind = c->at("type").oneOf({"linear", "power"}) == "power" ? ResponseCurve::Power : ResponseCurve::Linear;
                if (auto e = c->find("exponent")) m.curve.exponent = e->number(0.2, 5.0);
                c->finish();
            }
            m.speed = r->at(speedKey).number(0.0, 10000.0);
            r->finish();
        };
        motion("translation", "mm_per_s", binding.translation);
        motion("rotation", "deg_per_s", binding.rotation);
        if (auto buttons = b.find("buttons")) {
            if (!buttons->isObject()) buttons->fail("an object of button name -> action");
            for (auto it = buttons->json().begin(); it != buttons->json().end(); ++it) {
                int bit = -1;
                if (gamepad) {
                    for (int k = 0; k < ButtonCount; ++k)
                        if (it.key() == buttonName(k)) bit = k;
                } else if (it.key().rfind("button", 0) == 0 && it.key().size() > 6 && it.key().size() <= 8 &&
                           it.key().find_first_not_of("0123456789", 6) == std::string::npos) {
                    bit = std::stoi(it.key().substr(6));
                    if (bit > 31) bit = -1;
                }
                JsonReader action = buttons->at(it.key());
                if (bit < 0)
                    throw InputError(source, action.path(), gamepad ? "a gamepad button name (south, east, west, north, ..., dpad_up)" : "button0 .. button31",
                                     "\"" + it.key() + "\"");
                binding.buttons[bit] = action.oneOf(kActions);
            }
        }
        auto axisControl = [&](const char* key, std::optional<AxisControl>& control) {
            auto c = b.find(key);
            if (!c) return;
            std::vector<std::string> names;
            for (const std::string& a : gamepad ? kGamepadAxes : kSixDofAxes) names.push_back(a), names.push_back("-" + a);
            control = AxisControl{c->at("axis").oneOf(names), 0.5};
            if (auto t = c->find("threshold")) control->threshold = t->number(0.05, 1.0);
            c->finish();
        };
        axisControl("drill", binding.drillAxis);
        axisControl("erase", binding.eraseAxis);
        b.finish();
        config.bindings.push_back(binding);
    }
    root.finish();
    return config;
}

MappingConfig loadMapping(const std::string& path) {
    std::vector<std::uint8_t> bytes = readFileBytes(path);
    return parseMapping(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), path);
}

std::string mappingToJson(const MappingConfig& config) {
    nlohmann::ordered_json j;
    j["bindings"] = nlohmann::ordered_json::array();
    for (const DeviceBinding& b : config.bindings) {
        nlohmann::ordered_json e;
        e["device"] = {{"family", b.family}, {"index", b.index}};
        e["mesh"] = b.mesh;
        e["frame"] = b.frame == MotionFrame::World ? "world" : "camera";
        auto motion = [](const MotionBinding& m, const char* speedKey) {
            nlohmann::ordered_json o;
            o["axes"] = {m.axes[0], m.axes[1], m.axes[2]};
            o["dead_zone"] = m.deadZone;
            o["curve"] = {{"type", m.curve.kind == ResponseCurve::Power ? "power" : "linear"}, {"exponent", m.curve.exponent}};
            o[speedKey] = m.speed;
            return o;
        };
        e["translation"] = motion(b.translation, "mm_per_s");
        e["rotation"] = motion(b.rotation, "deg_per_s");
        bool gamepad = b.family != "spacemouse";
        nlohmann::ordered_json buttons = nlohmann::ordered_json::object();
        for (const auto& [bit, action] : b.buttons) buttons[gamepad ? buttonName(bit) : "button" + std::to_string(bit)] = action;
        e["buttons"] = buttons;
        if (b.drillAxis) e["drill"] = {{"axis", b.drillAxis->axis}, {"threshold", b.drillAxis->threshold}};
        if (b.eraseAxis) e["erase"] = {{"axis", b.eraseAxis->axis}, {"threshold", b.eraseAxis->threshold}};
        j["bindings"].push_back(e);
    }
    return j.dump();
}

Mapper::Mapper(MappingConfig config) : config_(std::move(config)) {
    for (const DeviceBinding& b : config_.bindings) held_.push_back(b.mesh);
    bound_.assign(config_.bindings.size(), -1);
    previousButtons_.assign(config_.bindings.size(), 0);
}

void Mapper::restore(const MapperState& state) {
    std::size_t n = config_.bindings.size();
    if (state.heldMeshes.size() != n || state.boundDevices.size() != n || state.previousButtons.size() != n)
        throw std::invalid_argument("mapper state has " + std::to_string(state.heldMeshes.size()) + " bindings, the mapping " + std::to_string(n));
    held_ = state.heldMeshes;
    bound_ = state.boundDevices;
    previousButtons_ = state.previousButtons;
}

void Mapper::hold(int binding, int mesh) {
    if (binding < 0 || binding >= static_cast<int>(config_.bindings.size()) || mesh < 0)
        throw std::invalid_argument("hold: binding " + std::to_string(binding) + " of " + std::to_string(config_.bindings.size()) + ", mesh " +
                                    std::to_string(mesh));
    held_[static_cast<std::size_t>(binding)] = mesh;
}

std::vector<Action> Mapper::update(const std::vector<DeviceSnapshot>& devices, double dt, int meshCount) {
    std::vector<Action> actions;
    for (std::size_t b = 0; b < config_.bindings.size(); ++b) {
        const DeviceBinding& binding = config_.bindings[b];
        const DeviceSnapshot* device = nullptr;
        int seen = 0;
        for (const DeviceSnapshot& d : devices)
            if (familyMatches(binding.family, d.family) && seen++ == binding.index) device = &d;
        int id = device ? device->id : -1;
        if (id != bound_[b]) previousButtons_[b] = device ? device->state.buttons : 0;  // a new device: no false edges
        bound_[b] = id;
        if (!device || meshCount == 0) continue;
        held_[b] = std::clamp(held_[b], 0, meshCount - 1);
        // Buttons fire once, on press.
        std::uint32_t pressed = device->state.buttons & ~previousButtons_[b];
        previousButtons_[b] = device->state.buttons;
        for (const auto& [bit, action] : binding.buttons) {
            if (!((pressed >> bit) & 1u)) continue;
            if (action == "cycle_mesh") {
                held_[b] = (held_[b] + 1) % meshCount;
                actions.push_back(SelectMesh{static_cast<int>(b), held_[b]});
            } else if (action == "cycle_shading") {
                actions.push_back(CycleShading{});
            } else if (action == "reset_pose") {
                actions.push_back(ResetPose{held_[b]});
            } else if (action == "add_mesh") {
                actions.push_back(AddMesh{});
            } else if (action == "remove_mesh") {
                actions.push_back(RemoveMesh{held_[b]});
            } else if (action == "toggle_recording") {
                actions.push_back(ToggleRecording{});
            } else if (action == "screenshot") {
                actions.push_back(Screenshot{});
            } else if (action.rfind("shading:", 0) == 0) {
                actions.push_back(SetShading{action.substr(8)});
            } else if (action == "undo" || action == "undo_stroke") {
                actions.push_back(Undo{});
            } else if (action == "redo" || action == "redo_stroke") {
                actions.push_back(Redo{});
            }
        }
        // Motion: axes -> rates -> this frame's step.
        glm::dvec3 t(0.0), r(0.0);
        for (int i = 0; i < 3; ++i) {
            t[i] = processedAxis(device->state, device->family, binding.translation.axes[static_cast<std::size_t>(i)], binding.translation);
            r[i] = processedAxis(device->state, device->family, binding.rotation.axes[static_cast<std::size_t>(i)], binding.rotation);
        }
        t *= binding.translation.speed * dt;
        r *= binding.rotation.speed * dt * std::numbers::pi / 180.0;
        if (t != glm::dvec3(0.0) || r != glm::dvec3(0.0)) actions.push_back(MoveMesh{held_[b], binding.frame, t, r});
        // Drill controls act while held (a stroke lasts as long), not on press.
        auto held = [&](const char* name, const std::optional<AxisControl>& axis) {
            for (const auto& [bit, action] : binding.buttons)
                if (action == name && device->state.pressed(bit)) return true;
            return axis && processedAxis(device->state, device->family, axis->axis, MotionBinding{{}, 0.0, {}, 0.0}) >= axis->threshold;
        };
        bool drill = held("drill", binding.drillAxis), erase = held("erase", binding.eraseAxis);
        if (auto d = heldDrill(held_[b], drill, erase)) actions.push_back(*d);
    }
    return actions;
}

}  // namespace curette::input
