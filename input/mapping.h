#pragma once
// From device states to actions: which device drives which mesh, how its axes become translation and
// rotation (dead zone, response curve, sensitivity in mm/s and deg/s, inversion, frame), and which buttons
// fire which actions (on press, once; the drill controls while held). A Mapper is a deterministic function of its inputs (device states in
// device-id order, dt, mesh count) and its own state (previous buttons, held meshes), so a replay that feeds
// it the recorded reports reproduces the recorded poses exactly.
//
// Config (JSON, assets/input/default_mapping.json):
//   {"bindings": [{"device": {"family": "spacemouse" | "gamepad" | "dualshock4" | ..., "index": 0},
//                  "mesh": 0, "frame": "camera" | "world",
//                  "translation": {"axes": ["tx", "-tz", "-ty"], "dead_zone": 0.06,
//                                  "curve": {"type": "linear" | "power", "exponent": 2}, "mm_per_s": 60},
//                  "rotation": {"axes": [...], ..., "deg_per_s": 90},
//                  "buttons": {"south": "cycle_mesh", "button0": "reset_pose", ...},
//                  "drill": {"axis": "right_trigger", "threshold": 0.5}, "erase": {"axis": "left_trigger", "threshold": 0.5}}]}
// Axis names: gamepads left_x, left_y, right_x, right_y, left_trigger, right_trigger, triggers (right minus
// left), shoulders (right minus left shoulder button); 6-DoF tx, ty, tz, rx, ry, rz; "-" inverts; "none".
// Stick pairs take a radial dead zone, other axes a per-axis one. Actions: cycle_mesh, cycle_shading,
// reset_pose, add_mesh, remove_mesh, toggle_recording, screenshot, shading:<mode>, undo, redo (on press: the
// last stroke or setting edit; undo_stroke, redo_stroke are the older names), and drill, erase (HoldDrill for the binding's held mesh every frame the button is down).
// "drill" / "erase" (optional): an axis that drills (erases) while its raw value (no dead zone or curve; "-"
// inverts) is at or past `threshold` (0.05 .. 1), e.g. a gamepad trigger; a button or the axis, drill winning
// over erase when both are held, as the keyboard's B over N.

#include "input/actions.h"
#include "input/device_state.h"

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace curette::input {

struct ResponseCurve {
    enum Kind { Linear, Power } kind = Linear;
    double exponent = 2.0;
    double apply(double v) const;  // odd: sign(v) |v|^exponent
};

struct MotionBinding {
    std::array<std::string, 3> axes{"none", "none", "none"};  // as written (with "-" for inversion)
    double deadZone = 0.1;
    ResponseCurve curve;
    double speed = 0.0;   // mm/s (translation) or deg/s (rotation) at full deflection
};

// An axis that holds a drill control while pulled past a threshold.
struct AxisControl {
    std::string axis;          // an axis name as in MotionBinding ("-" inverts)
    double threshold = 0.5;
    bool operator==(const AxisControl&) const = default;
};

struct DeviceBinding {
    std::string family = "gamepad";  // "gamepad" matches every gamepad family
    int index = 0;                   // the index-th connected device of that family (by device id)
    int mesh = 0;
    MotionFrame frame = MotionFrame::Camera;
    MotionBinding translation, rotation;
    std::map<int, std::string> buttons;  // button bit -> action name
    std::optional<AxisControl> drillAxis, eraseAxis;
};

struct MappingConfig {
    std::vector<DeviceBinding> bindings;
};

MappingConfig parseMapping(std::string_view json, const std::string& source);
MappingConfig loadMapping(const std::string& path);
// assets/input/default_mapping.json, built into the binary.
std::string_view defaultMappingJson();
MappingConfig defaultMapping();
std::string mappingToJson(const MappingConfig& config);  // as recorded in a session header

struct DeviceSnapshot {
    int id;
    DeviceFamily family;
    DeviceState state;
};

// What a Mapper remembers between frames, per binding: the mesh it holds, the device it was bound to, and that
// device's buttons last frame (so presses fire once). A session recorded mid-run starts from this.
struct MapperState {
    std::vector<int> heldMeshes, boundDevices;
    std::vector<std::uint32_t> previousButtons;
    bool operator==(const MapperState&) const = default;
};

class Mapper {
public:
    explicit Mapper(MappingConfig config);
    // One frame. `devices` in ascending id order; `meshCount` bounds cycle_mesh.
    std::vector<Action> update(const std::vector<DeviceSnapshot>& devices, double dt, int meshCount);
    const MappingConfig& config() const { return config_; }
    int heldMesh(int binding) const { return held_[static_cast<std::size_t>(binding)]; }
    // Makes `binding` hold mesh `mesh` (the viewer's mesh panel, through InputPipeline::step); throws
    // std::invalid_argument for a binding the config does not have or a negative mesh.
    void hold(int binding, int mesh);
    // The device id bound to each binding in the last update (-1: none connected).
    int boundDevice(int binding) const { return bound_[static_cast<std::size_t>(binding)]; }
    MapperState state() const { return {held_, bound_, previousButtons_}; }
    // Throws std::invalid_argument when `state` is not for this config's bindings.
    void restore(const MapperState& state);

private:
    MappingConfig config_;
    std::vector<int> held_, bound_;
    std::vector<std::uint32_t> previousButtons_;
};

// The processed value of an axis name for a device state (dead zone and curve applied): exposed for tests.
double processedAxis(const DeviceState& state, DeviceFamily family, const std::string& name, const MotionBinding& binding);

}  // namespace curette::input
