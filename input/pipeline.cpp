#include "input/pipeline.h"

#include <algorithm>

namespace curette::input {

InputPipeline::InputPipeline(MappingConfig mapping, double keyboardMmPerSecond, double keyboardDegPerSecond)
    : mapper_(std::move(mapping)), keyboard_(keyboardMmPerSecond, keyboardDegPerSecond) {}

void InputPipeline::addDevice(int id, DeviceFamily family) { devices_[id] = DeviceSnapshot{id, family, DeviceState{}}; }
void InputPipeline::removeDevice(int id) { devices_.erase(id); }

void InputPipeline::restore(const InputPipelineState& state) {
    mapper_.restore(state.mapper);
    keyboard_.restore(state.keyboard);
    devices_ = state.devices;
}

std::vector<Action> InputPipeline::step(const std::vector<RawReport>& reports, const KeyboardMouseState& keys, double dt, int meshCount,
                                        const std::vector<HoldRequest>& holds) {
    std::vector<Action> actions;
    for (const HoldRequest& h : holds) {
        if (meshCount <= 0) break;
        int mesh = std::clamp(h.mesh, 0, meshCount - 1);
        if (h.binding == kKeyboardBinding) keyboard_.select(mesh);
        else mapper_.hold(h.binding, mesh);
        actions.push_back(SelectMesh{h.binding, mesh});
    }
    for (const RawReport& r : reports) {
        auto it = devices_.find(r.deviceId);
        if (it == devices_.end()) continue;
        parseReport(it->second.family, r.bytes, it->second.state);  // rejected reports leave the state as it was
    }
    std::vector<DeviceSnapshot> snapshot;
    for (const auto& [id, d] : devices_) snapshot.push_back(d);
    std::vector<Action> fromDevices = mapper_.update(snapshot, dt, meshCount);
    actions.insert(actions.end(), fromDevices.begin(), fromDevices.end());
    std::vector<Action> fromKeys = keyboard_.update(keys, dt, meshCount);
    actions.insert(actions.end(), fromKeys.begin(), fromKeys.end());
    if (keys.down(Key::Fine))
        for (Action& a : actions) {
            if (auto* move = std::get_if<MoveMesh>(&a)) move->translationMm *= kFineStepFactor, move->rotationRad *= kFineStepFactor;
            if (auto* drag = std::get_if<DragMesh>(&a)) drag->pixels *= kFineStepFactor;
        }
    return actions;
}

}  // namespace curette::input
