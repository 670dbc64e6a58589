#include "session/live_input.h"

#include "session/removal_file.h"

#include <algorithm>
#include <ctime>
#include <set>

namespace curette {

SessionDevice sessionDevice(const input::DeviceInfo& info) {
    const char* bus = info.bus == input::Bus::Usb ? "usb" : info.bus == input::Bus::Bluetooth ? "bluetooth" : "unknown";
    return {info.id, input::familyName(info.family), info.path, info.product, bus, info.vendorId, info.productId};
}

LiveInput::LiveInput(std::unique_ptr<input::HidBackend> backend, input::MappingConfig mapping, double keyboardMmPerSecond,
                     double keyboardDegPerSecond)
    : devices_(std::move(backend)),
      pipeline_(mapping, keyboardMmPerSecond, keyboardDegPerSecond),
      mappingJson_(input::mappingToJson(mapping)),
      keyboardMm_(keyboardMmPerSecond),
      keyboardDeg_(keyboardDegPerSecond) {}

InputFrame LiveInput::step(double nowSeconds, const input::KeyboardMouseState& keys, double dt, int meshCount,
                           std::vector<input::HoldRequest> holds) {
    InputFrame frame;
    devices_.poll(nowSeconds);
    // Connections first (a replay applies them in the same order: added, removed, then the reports).
    std::set<int> present;
    for (const auto& device : devices_.devices()) {
        present.insert(device->info.id);
        if (!pipeline_.devices().count(device->info.id)) {
            pipeline_.addDevice(device->info.id, device->info.family);
            frame.devicesAdded.push_back(sessionDevice(device->info));
        }
    }
    std::vector<int> gone;
    for (const auto& [id, snapshot] : pipeline_.devices())
        if (!present.count(id)) gone.push_back(id);
    for (int id : gone) {
        pipeline_.removeDevice(id);
        frame.devicesRemoved.push_back(id);
    }
    frame.reports = devices_.takeReports();
    frame.holds = std::move(holds);
    frame.actions = pipeline_.step(frame.reports, keys, dt, meshCount, frame.holds);
    return frame;
}

std::vector<SessionDevice> LiveInput::connectedDevices() const {
    std::vector<SessionDevice> out;
    for (const auto& device : devices_.devices())
        if (pipeline_.devices().count(device->info.id)) out.push_back(sessionDevice(device->info));
    return out;
}

namespace {

// The header of a recording starting now at `path`; a removal drilled before it is written beside it, so the
// replay starts from it (session/removal_file.h).
SessionHeader headerNow(const std::filesystem::path& path, const std::string& scene, const InteractionState& state, const LiveInput& input,
                        std::optional<SessionXr> xr) {
    SessionHeader h;
    h.scene = scene;
    h.created = currentTimeIso8601();
    h.devices = input.connectedDevices();
    h.mappingJson = input.mappingJson();
    h.shading = state.shading;
    h.meshes = state.sessionMeshes();
    h.nextMeshId = state.nextMeshId;
    h.lights = state.sessionLights();
    h.selectedLight = state.selectedLight;
    h.edits = state.settingEdits();
    h.inputState = input.pipeline().state();
    h.keyboardMmPerSecond = input.keyboardMmPerSecond();
    h.keyboardDegPerSecond = input.keyboardDegPerSecond();
    if (state.removal && !state.removal->empty()) {
        std::filesystem::path file = removalFileBeside(path);
        writeRemovalFile(file, *state.removal);
        h.removal = file.filename().string();
        h.removalDigest = state.removal->digest();
    }
    // A recording starts a new undo history: a replay starts from the removal above and could not undo the
    // strokes made before it, so neither can the live run from here on.
    if (state.undoHistory) *state.undoHistory = plan::UndoHistory(state.undoHistory->budgetBytes());
    h.xr = std::move(xr);
    return h;
}

}  // namespace

LiveRecording::LiveRecording(const std::filesystem::path& path, const std::string& scene, const InteractionState& state,
                             const LiveInput& input, double startSeconds, double checkpointSeconds, std::optional<SessionXr> xr)
    : recorder_(path, headerNow(path, scene, state, input, std::move(xr)), checkpointSeconds), start_(startSeconds) {}

void LiveRecording::addFrame(double now, double dt, glm::ivec2 size, const OrbitCamera& camera, const InteractionState& state,
                             const input::KeyboardMouseState& keys, const InputFrame& input, std::optional<SessionXrFrame> xr) {
    SessionFrame f;
    f.index = index_++;
    f.time = std::max(0.0, now - start_);
    f.dt = dt;
    f.size = size;
    f.camera = camera;
    f.shading = state.shading;
    f.meshes = state.sessionPoses();
    f.lights = state.lightDirections();
    f.keys = keys.keys;
    f.drag = keys.rightDragPixels;
    f.lightDrag = keys.lightDragPixels;
    f.devicesAdded = input.devicesAdded;
    f.devicesRemoved = input.devicesRemoved;
    for (int id : state.addedMeshIds) {
        int i = state.indexOf(id);
        if (i >= 0) f.meshesAdded.push_back({id, state.meshes[static_cast<std::size_t>(i)].name, state.meshes[static_cast<std::size_t>(i)].description});
    }
    for (int id : state.removedMeshIds) {
        bool addedThisFrame = std::count(state.addedMeshIds.begin(), state.addedMeshIds.end(), id) > 0;
        if (!addedThisFrame) f.meshesRemoved.push_back(id);
    }
    f.edits = state.appliedEdits;
    f.holds = input.holds;
    f.drills = state.appliedDrills;
    f.historyCommands = state.appliedHistory;
    f.historyEdits = state.appliedHistoryEdits;
    f.xr = std::move(xr);
    for (const input::RawReport& r : input.reports) f.reports.push_back({r.deviceId, std::max(0.0, r.timeSeconds - start_), r.bytes});
    recorder_.add(f);
}

std::string currentTimeIso8601() {
    std::time_t now = std::time(nullptr);
    std::tm utc{};
    gmtime_r(&now, &utc);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
    return text;
}

}  // namespace curette
