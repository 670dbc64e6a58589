// curette record --scene S --out F.jsonl --synthetic FAMILIES: records a session headless from scripted devices.
// Each synthetic device produces the reports its real counterpart would (input/devices/encoders.h) for a smooth
// scripted motion, and they go through the fake hidapi backend, the device manager, the parsers, the mapping
// and the interaction step exactly as live reports do in the viewer; the session is written the same way.
// It makes demo sessions and test sessions; a person records with `curette view` (F9 or a mapped button).
// --move-lights adds a scripted keyboard and mouse that turn the lights (I/J/K/L held, O to the next light, Shift +
// left drags), recorded as keys and drags like the viewer's.
#include "tools/command_line.h"
#include "tools/commands/commands.h"
#include "session/interaction.h"
#include "session/live_input.h"
#include "session/loaded_scene.h"
#include "session/session_step.h"
#include "base/error.h"
#include "input/devices/encoders.h"
#include "input/hid/fake_backend.h"
#include "render/model/shading_mode.h"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

namespace curette::commands {

namespace {

// A synthetic device: what it claims to be and how it encodes its state.
struct SyntheticKind {
    const char* name;
    input::DeviceFamily family;
    std::uint16_t vendorId, productId;
    input::Bus bus;
    const char* product;
};

const SyntheticKind kKinds[] = {
    {"dualshock4", input::DeviceFamily::DualShock4, 0x054c, 0x09cc, input::Bus::Usb, "Wireless Controller"},
    {"dualshock4_bt", input::DeviceFamily::DualShock4, 0x054c, 0x09cc, input::Bus::Bluetooth, "Wireless Controller"},
    {"dualsense", input::DeviceFamily::DualSense, 0x054c, 0x0ce6, input::Bus::Usb, "DualSense Wireless Controller"},
    {"dualsense_bt", input::DeviceFamily::DualSense, 0x054c, 0x0ce6, input::Bus::Bluetooth, "DualSense Wireless Controller"},
    {"switch_pro", input::DeviceFamily::SwitchPro, 0x057e, 0x2009, input::Bus::Usb, "Pro Controller"},
    {"xbox_bt", input::DeviceFamily::XboxBluetooth, 0x045e, 0x0b13, input::Bus::Bluetooth, "Xbox Wireless Controller"},
    {"spacemouse", input::DeviceFamily::SpaceMouse, 0x046d, 0xc626, input::Bus::Usb, "SpaceNavigator"},
    {"spacemouse_wireless", input::DeviceFamily::SpaceMouse, 0x256f, 0xc62e, input::Bus::Usb, "SpaceMouse Wireless"},
};

std::string kindList() {
    std::string list;
    for (const SyntheticKind& k : kKinds) list += (list.empty() ? "" : ", ") + std::string(k.name);
    return list;
}

// The reports one state becomes on the wire.
std::vector<std::vector<std::uint8_t>> encode(const SyntheticKind& kind, const input::DeviceState& s, const input::DeviceState& previous) {
    using input::DeviceFamily;
    switch (kind.family) {
        case DeviceFamily::DualShock4:
            return {kind.bus == input::Bus::Bluetooth ? input::encodeDualShock4Bluetooth(s) : input::encodeDualShock4Usb(s)};
        case DeviceFamily::DualSense:
            return {kind.bus == input::Bus::Bluetooth ? input::encodeDualSenseBluetooth(s) : input::encodeDualSenseUsb(s)};
        case DeviceFamily::SwitchPro: return {input::encodeSwitchProFull(s)};
        case DeviceFamily::XboxBluetooth: return {input::encodeXboxBluetooth(s)};
        case DeviceFamily::SpaceMouse: {
            std::vector<std::vector<std::uint8_t>> reports;
            if (kind.vendorId == 0x256f) reports.push_back(input::encodeSpaceMouseCombined(s));
            else reports = {input::encodeSpaceMouseTranslation(s), input::encodeSpaceMouseRotation(s)};
            if (s.buttons != previous.buttons) reports.push_back(input::encodeSpaceMouseButtons(s));
            return reports;
        }
    }
    return {};
}

// A hand's slow, smooth exploration: every axis a sum of two sines with random phases (seeded), so the mesh
// sweeps back and forth around where it started; 6-DoF devices use all six axes, gamepads both sticks and the
// triggers. Full deflection is rare, as with a real hand.
struct ScriptedMotion {
    std::array<double, input::AxisCount> phase{}, frequency{};
    ScriptedMotion(std::mt19937& random) {
        std::uniform_real_distribution<double> phaseDistribution(0.0, 2.0 * std::numbers::pi), frequencyDistribution(0.15, 0.45);
        for (int a = 0; a < input::AxisCount; ++a) phase[a] = phaseDistribution(random), frequency[a] = frequencyDistribution(random);
    }
    input::DeviceState at(double t, bool gamepad) const {
        input::DeviceState s;
        for (int a = 0; a < input::AxisCount; ++a) {
            double w = 2.0 * std::numbers::pi * frequency[a];
            double v = 0.75 * std::sin(w * t + phase[a]) + 0.2 * std::sin(2.7 * w * t + 2.0 * phase[a]);
            s.axes[a] = static_cast<float>(std::clamp(v, -1.0, 1.0));
        }
        if (gamepad) {  // triggers are [0, 1]; split the signal between them, below half pull (< 1.9 * 0.25): the
                        // default mapping drills past half pull, and scripted motion drills only with --drill
            double v = s.axes[input::LeftTrigger] - s.axes[input::RightTrigger];
            s.axes[input::LeftTrigger] = static_cast<float>(std::max(0.0, -v) * 0.25);
            s.axes[input::RightTrigger] = static_cast<float>(std::max(0.0, v) * 0.25);
        }
        return s;
    }
};

// The scripted light motion of --move-lights at frame f of `frames`: J/L and I/K held in slow alternation, O
// pressed once a third of the way in (the next light), a Shift + left drag every fifth frame.
input::KeyboardMouseState scriptedLightKeys(int f, int frames, double phase) {
    using input::Key;
    input::KeyboardMouseState k;
    auto hold = [&](Key key) { k.press(key); };
    double t = 2.0 * std::numbers::pi * f / std::max(frames, 1);
    double yaw = std::sin(t + phase), pitch = std::sin(2.0 * t + 2.0 * phase);
    if (yaw > 0.3) hold(Key::L);
    if (yaw < -0.3) hold(Key::J);
    if (pitch > 0.3) hold(Key::I);
    if (pitch < -0.3) hold(Key::K);
    if (f == frames / 3) hold(Key::O);
    if (f % 5 == 2) k.lightDragPixels = {6.0 * std::cos(t + phase), -4.0 * std::sin(t)};
    return k;
}

// The frames of --drill / --erase: "A-B" ranges (inclusive), comma-separated, within the recording.
std::vector<std::pair<int, int>> frameRanges(const std::string& option, const std::string& text, int frames) {
    std::vector<std::pair<int, int>> ranges;
    std::size_t start = 0;
    while (start <= text.size()) {
        std::size_t comma = std::min(text.find(',', start), text.size());
        std::string range = text.substr(start, comma - start);
        std::size_t dash = range.find('-');
        if (dash == std::string::npos) throw InputError("<command line>", "--" + option, "FIRST-LAST frame ranges, comma-separated", range);
        int a = CommandLine::parseInt(option, range.substr(0, dash), 0, frames - 1);
        int b = CommandLine::parseInt(option, range.substr(dash + 1), a, frames - 1);
        ranges.emplace_back(a, b);
        start = comma + 1;
    }
    return ranges;
}

bool inRanges(const std::vector<std::pair<int, int>>& ranges, int f) {
    for (const auto& [a, b] : ranges)
        if (f >= a && f <= b) return true;
    return false;
}

int record(const CommandLine& cl) {
    std::filesystem::path scenePath = cl.required("scene"), out = cl.required("out");
    int frames = CommandLine::parseInt("frames", cl.valueOr("frames", "150"), 1, 1000000);
    double fps = CommandLine::parseDouble("fps", cl.valueOr("fps", "30"), 1, 1000);
    double reportHz = CommandLine::parseDouble("report-hz", cl.valueOr("report-hz", "125"), 1, 8000);
    int seed = CommandLine::parseInt("seed", cl.valueOr("seed", "1"), 0, 1 << 30);
    int unplugFrame = cl.value("unplug") ? CommandLine::parseInt("unplug", *cl.value("unplug"), 0, frames - 1) : -1;
    bool moveLights = cl.flag("move-lights");
    std::vector<const SyntheticKind*> kinds;
    if (cl.value("synthetic")) {   // with --move-lights or --press-shading, devices are optional
        std::string list = cl.required("synthetic");
        std::size_t start = 0;
        while (start <= list.size()) {
            std::size_t comma = std::min(list.find(',', start), list.size());
            std::string name = list.substr(start, comma - start);
            const SyntheticKind* kind = nullptr;
            for (const SyntheticKind& k : kKinds)
                if (name == k.name) kind = &k;
            if (!kind) throw InputError("<command line>", "--synthetic", "a comma-separated list of " + kindList(), name);
            kinds.push_back(kind);
            start = comma + 1;
        }
    }
    if (unplugFrame >= 0 && kinds.empty()) throw InputError("<command line>", "--unplug", "together with --synthetic (a device to unplug)");
    // --press-shading MODE@FRAME: the key of MODE (1-6) pressed at FRAME, as at the window (a scripted mode switch).
    std::optional<std::pair<int, input::Key>> shadingPress;
    if (auto press = cl.value("press-shading")) {
        std::size_t at = press->find('@');
        std::optional<ShadingMode> mode = parseShadingMode(press->substr(0, std::min(at, press->size())));
        if (at == std::string::npos || !mode)
            throw InputError("<command line>", "--press-shading", "MODE@FRAME, MODE one of " + shadingModeList(), "\"" + *press + "\"");
        int frame = CommandLine::parseInt("press-shading", press->substr(at + 1), 0, frames - 1);
        input::Key key = *mode == ShadingMode::Ismos ? input::Key::Digit6 : static_cast<input::Key>(static_cast<int>(input::Key::Digit1) + static_cast<int>(*mode));
        shadingPress = std::make_pair(frame, key);
    }
    // Scripted drilling (session/drilling.h), as keys at the window (input/keyboard_mouse.h), so the session
    // records them as keys and replay --from-reports re-derives the drilling: the keyboard's mesh (--drill-mesh, a
    // hold request at frame 0) drills with B held over the --drill frames and erases with N over the --erase ones;
    // --undo / --redo press Ctrl+Z / Ctrl+Shift+Z at those frames (adjacent frames are one press, as a held key).
    std::vector<std::pair<int, int>> drillFrames, eraseFrames;
    if (auto d = cl.value("drill")) drillFrames = frameRanges("drill", *d, frames);
    if (auto e = cl.value("erase")) eraseFrames = frameRanges("erase", *e, frames);
    std::vector<int> undoFrames = cl.value("undo") ? CommandLine::parseIntList("undo", *cl.value("undo"), 0, frames - 1) : std::vector<int>{};
    std::vector<int> redoFrames = cl.value("redo") ? CommandLine::parseIntList("redo", *cl.value("redo"), 0, frames - 1) : std::vector<int>{};
    int drillMesh = CommandLine::parseInt("drill-mesh", cl.valueOr("drill-mesh", "0"), 0, clip::kMaxClipMeshes - 1);
    if (!moveLights && !shadingPress && !cl.value("synthetic") && drillFrames.empty()) (void)cl.required("synthetic");
    input::MappingConfig mapping = cl.value("mapping") ? input::loadMapping(*cl.value("mapping")) : input::defaultMapping();

    LoadedScene loaded = loadSceneWithVolume(scenePath);
    VolumeGeometry geometry{loaded.volume.dims, loaded.volume.indexToWorld};
    SessionStep step(InteractionState::fromScene(loaded.scene), initialFrame(loaded.scene, geometry));
    step.attachRemoval(loaded.volume.dims, loaded.volume.indexToWorld, loaded.removal.get());
    glm::ivec2 size = cl.value("size") ? CommandLine::parseSize("size", *cl.value("size")) : step.frame().size;
    step.frame().size = size;
    InteractionState& state = step.state();

    auto ports = std::make_shared<input::FakeHidBackend::Ports>();
    std::vector<input::HidDeviceDescription> descriptions;
    std::vector<ScriptedMotion> motions;
    std::mt19937 random(static_cast<std::uint32_t>(seed));
    for (std::size_t i = 0; i < kinds.size(); ++i) {
        const SyntheticKind& k = *kinds[i];
        input::HidDeviceDescription d;
        d.path = "/dev/hidraw-synthetic-" + std::to_string(i);
        d.vendorId = k.vendorId;
        d.productId = k.productId;
        d.product = std::string(k.product) + " (synthetic)";
        d.bus = k.bus;
        d.usagePage = 0x01;  // generic desktop
        d.usage = k.family == input::DeviceFamily::SpaceMouse ? 0x08 : 0x05;   // multi-axis controller / game pad
        input::FakeHidBackend::plug(*ports, d);
        descriptions.push_back(d);
        motions.emplace_back(random);
    }
    LiveInput input(std::make_unique<input::FakeHidBackend>(ports), mapping, 40.0, 60.0);

    // The scene path as seen from the session file, so the pair can move together.
    std::error_code ec;
    std::filesystem::path outDirectory = std::filesystem::absolute(out).parent_path();
    std::filesystem::path sceneFromSession = std::filesystem::relative(std::filesystem::absolute(scenePath), outDirectory, ec);
    if (ec || sceneFromSession.empty()) sceneFromSession = std::filesystem::absolute(scenePath);

    const double dt = 1.0 / fps;
    LiveRecording recording(out, sceneFromSession.string(), state, input, 0.0);
    std::vector<input::DeviceState> previous(kinds.size());
    double nextReport = 0.0;
    std::uniform_real_distribution<double> phaseDistribution(0.0, 2.0 * std::numbers::pi);
    double lightPhase = phaseDistribution(random);
    int replugFrame = unplugFrame >= 0 ? unplugFrame + static_cast<int>(std::ceil(fps)) + 1 : -1;
    for (int f = 0; f < frames; ++f) {
        double now = f * dt;
        if (f == unplugFrame) input::FakeHidBackend::unplug(*ports, descriptions.back().path);
        if (f == replugFrame) input::FakeHidBackend::plug(*ports, descriptions.back());
        // The reports each device sent since the last frame.
        for (; nextReport <= now + 1e-9; nextReport += 1.0 / reportHz)
            for (std::size_t i = 0; i < kinds.size(); ++i) {
                if (!ports->byPath.count(descriptions[i].path)) continue;
                input::DeviceState s = motions[i].at(nextReport, input::isGamepad(kinds[i]->family));
                for (auto& report : encode(*kinds[i], s, previous[i])) input::FakeHidBackend::queue(*ports, descriptions[i].path, std::move(report));
                previous[i] = s;
            }
        double frameDt = f == 0 ? 0.0 : dt;
        input::KeyboardMouseState keys = moveLights ? scriptedLightKeys(f, frames, lightPhase) : input::KeyboardMouseState{};
        if (shadingPress && f == shadingPress->first) keys.press(shadingPress->second);
        if (inRanges(drillFrames, f)) keys.press(input::Key::Drill);
        if (inRanges(eraseFrames, f)) keys.press(input::Key::Erase);
        if (std::count(undoFrames.begin(), undoFrames.end(), f)) keys.press(input::Key::Undo);
        if (std::count(redoFrames.begin(), redoFrames.end(), f)) keys.press(input::Key::Redo);
        std::vector<input::HoldRequest> holds;
        if (f == 0 && cl.value("drill-mesh")) holds.push_back({input::kKeyboardBinding, drillMesh});
        InputFrame inputFrame = input.step(now, keys, frameDt, static_cast<int>(state.meshes.size()), holds);
        step.apply(inputFrame.actions, size.y, {}, "<panel>");
        state.toggleRecording = state.screenshot = false;   // nothing to toggle or capture headless
        recording.addFrame(now, frameDt, size, step.frame().camera, state, keys, inputFrame);
    }
    recording.finish();
    std::printf("wrote %s: %d frames, %zu synthetic devices, %zu meshes, scene %s\n", out.c_str(), frames, kinds.size(), state.meshes.size(),
                sceneFromSession.c_str());
    if (state.removal && !state.removal->empty())
        std::printf("drilled %.3f mL (%zu undo steps); removal %s\n", state.removal->drilledVolumeMm3() / 1000.0, state.undoHistory->undoSteps(),
                    state.removal->digest().c_str());
    return 0;
}

}  // namespace

Command recordCommand() {
    return {{"record", "--scene S --out F.jsonl --synthetic DEVICES", "record a session headless from scripted devices",
             {{"scene", true, "scene file (JSON)"},
              {"out", true, "session file to write (.jsonl)"},
              {"synthetic", true, "comma-separated devices: " + kindList() + " (optional with --move-lights or --press-shading)"},
              {"frames", true, "frames to record (default 150)"},
              {"fps", true, "frames per second of session time (default 30)"},
              {"report-hz", true, "reports per second per device (default 125)"},
              {"seed", true, "seed of the scripted motion (default 1)"},
              {"mapping", true, "mapping JSON (default: the shipped assets/input/default_mapping.json)"},
              {"size", true, "image size WxH recorded for the frames (default: the scene's)", "WxH"},
              {"unplug", true, "FRAME: unplug the last device there and plug it back one second later"},
              {"move-lights", false, "also turn the lights with scripted keys (I/J/K/L, O) and Shift + left drags"},
              {"press-shading", true, "MODE@FRAME: press the key of shading MODE (1-6) at FRAME, as at the window", "MODE@FRAME"},
              {"drill", true, "FIRST-LAST[,...]: frames over which the mesh --drill-mesh drills (as B held at the window)", "RANGES"},
              {"erase", true, "FIRST-LAST[,...]: frames over which it erases (N held)", "RANGES"},
              {"drill-mesh", true, "index of the mesh that drills: the keyboard holds it from frame 0 (default: the keyboard's, 0)"},
              {"undo", true, "FRAME[,...]: undo the last stroke or setting edit there (Ctrl+Z pressed)"},
              {"redo", true, "FRAME[,...]: redo there (Ctrl+Shift+Z pressed)"}}},
            &record};
}

}  // namespace curette::commands
