#include "input/pipeline.h"

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

std::vector<Action> InputPipeline::step(const std::vector<RawReport>& reports, const KeyboardMouseState& keys, double dt, int meshCount) {
    for (const RawReport& r : reports) {
        auto it = devices_.find(r.deviceId);
        if (it == devices_.end()) continue;
        parseReport(it->second.family, r.bytes, it->second.state);  // rejected reports leave the state as it was
    }
    std::vector<DeviceSnapshot> snapshot;
    for (const auto& [id, d] : devices_) snapshot.push_back(d);
    std::vector<Action> actions = mapper_.update(snapshot, dt, meshCount);
    std::vector<Action> fromKeys = keyboard_.update(keys, dt, meshCount);
    actions.insert(actions.end(), fromKeys.begin(), fromKeys.end());
    return actions;
}

}  // namespace curette::input
