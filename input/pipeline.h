#pragma once
// Raw reports in, actions out: the parse-and-map step shared by the live viewer (reports from hidapi) and by
// replays re-deriving poses from recorded reports, so both compute exactly the same thing. Devices come and go
// by id; each report is parsed with its device's family parser into that device's state, then the mapping and
// the keyboard produce the frame's actions.

#include "input/devices/parsers.h"
#include "input/hid/device_manager.h"
#include "input/keyboard_mouse.h"
#include "input/mapping.h"

#include <map>

namespace curette::input {

// A request from outside the devices (the viewer's mesh panel) that a binding hold another mesh: `binding`
// indexes the mapping's bindings, -1 is the keyboard; `mesh` is an index into the current meshes, as the
// mapper's held meshes are. InputPipeline::step applies it before that frame's reports are mapped, and a
// session records it with that frame ("holds"), so a replay that re-derives poses from the reports runs the
// same step and the binding moves the same mesh from the same frame on.
inline constexpr int kKeyboardBinding = -1;   // as SelectMesh names the keyboard
struct HoldRequest {
    int binding = kKeyboardBinding;
    int mesh = 0;
    bool operator==(const HoldRequest&) const = default;
};

// Everything an InputPipeline carries from frame to frame; a session started mid-run records it in its header
// so that re-deriving poses from its reports starts where the live pipeline was.
struct InputPipelineState {
    std::map<int, DeviceSnapshot> devices;
    MapperState mapper;
    KeyboardMapperState keyboard;
};

class InputPipeline {
public:
    InputPipeline(MappingConfig mapping, double keyboardMmPerSecond, double keyboardDegPerSecond);
    void addDevice(int id, DeviceFamily family);
    void removeDevice(int id);
    // One frame: the hold requests (each a SelectMesh action; the mesh clamped to the meshes there are, none
    // when there are none), reports in arrival order (unknown device ids are ignored), then mapping and
    // keyboard. A request for a binding the mapping does not have throws std::invalid_argument.
    std::vector<Action> step(const std::vector<RawReport>& reports, const KeyboardMouseState& keys, double dt, int meshCount,
                             const std::vector<HoldRequest>& holds = {});
    const Mapper& mapper() const { return mapper_; }
    int keyboardSelection() const { return keyboard_.selectedMesh(); }
    const std::map<int, DeviceSnapshot>& devices() const { return devices_; }
    InputPipelineState state() const { return {devices_, mapper_.state(), keyboard_.state()}; }
    void restore(const InputPipelineState& state);

private:
    Mapper mapper_;
    KeyboardMapper keyboard_;
    std::map<int, DeviceSnapshot> devices_;  // ascending id, as the mapper expects
};

}  // namespace curette::input
