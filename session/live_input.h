#pragma once
// Input for a running session: the device manager (hidapi, or the fake backend for synthetic sessions) feeding
// the input pipeline, and the session recorder's view of both. The viewer and `curette record` run exactly
// this, so what they record is what `curette replay --from-reports` re-derives.

#include "session/interaction.h"
#include "session/session.h"
#include "input/hid/device_manager.h"
#include "input/pipeline.h"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace curette {

struct InputFrame {
    std::vector<input::Action> actions;
    std::vector<SessionDevice> devicesAdded;
    std::vector<int> devicesRemoved;
    std::vector<input::RawReport> reports;   // times in the device manager's clock
    std::vector<input::HoldRequest> holds;   // the hold requests this frame's pipeline step applied
};

SessionDevice sessionDevice(const input::DeviceInfo& info);

class LiveInput {
public:
    LiveInput(std::unique_ptr<input::HidBackend> backend, input::MappingConfig mapping, double keyboardMmPerSecond,
              double keyboardDegPerSecond);
    // One frame: poll the devices (hot-plug, drain reports), follow connections, parse and map, with the
    // hold requests (the mesh panel's, from the frame before) applied first.
    InputFrame step(double nowSeconds, const input::KeyboardMouseState& keys, double dt, int meshCount,
                    std::vector<input::HoldRequest> holds = {});
    std::vector<SessionDevice> connectedDevices() const;
    std::vector<std::string> takeMessages() { return devices_.takeMessages(); }
    const input::DeviceManager& devices() const { return devices_; }
    const input::InputPipeline& pipeline() const { return pipeline_; }
    const std::string& mappingJson() const { return mappingJson_; }
    double keyboardMmPerSecond() const { return keyboardMm_; }
    double keyboardDegPerSecond() const { return keyboardDeg_; }

private:
    input::DeviceManager devices_;
    input::InputPipeline pipeline_;
    std::string mappingJson_;
    double keyboardMm_, keyboardDeg_;
};

// A recording in progress: the header is the state when it started (a drilled removal written beside the session
// file, and the drill undo history started afresh: the state's history is shared, so emptied); each frame adds the
// poses and the lights' directions after the frame's actions, the frame's input and the meshes that came and went.
// A head-mounted display session (`view --xr`) gives its room and eye sizes (`xr`) and each frame its head, eyes
// and hands.
class LiveRecording {
public:
    LiveRecording(const std::filesystem::path& path, const std::string& scene, const InteractionState& state, const LiveInput& input,
                  double startSeconds, double checkpointSeconds = 5.0, std::optional<SessionXr> xr = {});
    void addFrame(double nowSeconds, double dt, glm::ivec2 size, const OrbitCamera& camera, const InteractionState& state,
                  const input::KeyboardMouseState& keys, const InputFrame& input, std::optional<SessionXrFrame> xr = {});
    void finish() { recorder_.finish(); }
    std::size_t frames() const { return recorder_.frames(); }
    const std::filesystem::path& path() const { return recorder_.path(); }

private:
    SessionRecorder recorder_;
    double start_;
    std::size_t index_ = 0;
};

// ISO 8601 UTC, for session headers.
std::string currentTimeIso8601();

}  // namespace curette
