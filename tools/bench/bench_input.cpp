// curette bench input: how fast each device family's reports parse (with the round-trip error of the axes
// through the report layout next to it), and the latency input adds between a report being readable and the
// clip-mesh pose that follows from it: device-manager poll (read, parse), input pipeline (parse, map) and the
// interaction step, per frame, for two devices at realistic report rates. No hardware here: the reports come
// through the fake hidapi backend, the same code path as live devices minus the kernel's hidraw read.
#include "tools/bench/bench_input.h"

#include "tools/bench/report.h"
#include "session/interaction.h"
#include "session/live_input.h"
#include "input/devices/encoders.h"
#include "input/devices/parsers.h"
#include "input/hid/fake_backend.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>

namespace curette::bench {

namespace {

using Clock = std::chrono::steady_clock;

struct Variant {
    const char* name;
    input::DeviceFamily family;
    bool gamepad;
    std::function<std::vector<std::vector<std::uint8_t>>(const input::DeviceState&)> encode;
};

std::vector<Variant> variants() {
    using namespace input;
    auto one = [](auto f) { return [f](const DeviceState& s) { return std::vector<std::vector<std::uint8_t>>{f(s)}; }; };
    return {
        {"DualShock 4 USB (0x01, 64 B)", DeviceFamily::DualShock4, true, one(encodeDualShock4Usb)},
        {"DualShock 4 BT (0x11, 78 B, CRC-32)", DeviceFamily::DualShock4, true, one(encodeDualShock4Bluetooth)},
        {"DualSense USB (0x01, 64 B)", DeviceFamily::DualSense, true, one(encodeDualSenseUsb)},
        {"DualSense BT (0x31, 78 B, CRC-32)", DeviceFamily::DualSense, true, one(encodeDualSenseBluetooth)},
        {"Switch Pro (0x30, 49 B)", DeviceFamily::SwitchPro, true, one(encodeSwitchProFull)},
        {"Xbox BT (0x01, 17 B)", DeviceFamily::XboxBluetooth, true, one(encodeXboxBluetooth)},
        {"SpaceMouse split (0x01 + 0x02, 7 B each)", DeviceFamily::SpaceMouse, false,
         [](const DeviceState& s) { return std::vector<std::vector<std::uint8_t>>{encodeSpaceMouseTranslation(s), encodeSpaceMouseRotation(s)}; }},
        {"SpaceMouse combined (0x01, 13 B)", DeviceFamily::SpaceMouse, false, one(encodeSpaceMouseCombined)},
    };
}

input::DeviceState randomState(std::mt19937& random, bool gamepad) {
    std::uniform_real_distribution<float> axis(-1.0f, 1.0f), trigger(0.0f, 1.0f);
    input::DeviceState s;
    for (int a = 0; a < input::AxisCount; ++a) s.axes[a] = axis(random);
    if (gamepad) {
        s.axes[input::LeftTrigger] = trigger(random);
        s.axes[input::RightTrigger] = trigger(random);
    }
    return s;
}

double percentile(std::vector<double> v, double p) {
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1, static_cast<std::size_t>(p * static_cast<double>(v.size() - 1) + 0.5))];
}

}  // namespace

int benchInput(const CommandLine& cl) {
    int reportCount = CommandLine::parseInt("reports", cl.valueOr("reports", "20000"), 100, 10000000);
    int frames = CommandLine::parseInt("frames", cl.valueOr("frames", "20000"), 100, 10000000);
    std::string jsonPath = cl.valueOr("json", "bench-input.json");
    std::printf("curette bench input: %d random reports per family, %d frames of two devices\n", reportCount, frames);

    // 1. Parse throughput and axis round-trip error.
    Table parse("Report parsing (one core)", {"device / report", "reports/s (millions)", "ns/report", "max axis error (round trip)", "axis step"});
    std::mt19937 random(1);
    for (const Variant& v : variants()) {
        std::vector<std::vector<std::uint8_t>> reports;
        std::vector<input::DeviceState> states;
        for (int i = 0; i < reportCount; ++i) {
            states.push_back(randomState(random, v.gamepad));
            for (auto& r : v.encode(states.back())) reports.push_back(std::move(r));
        }
        // Error: every state through its reports and back.
        double maxError = 0;
        std::size_t perState = reports.size() / states.size();
        for (std::size_t i = 0; i < states.size(); ++i) {
            input::DeviceState parsed;
            for (std::size_t k = 0; k < perState; ++k) input::parseReport(v.family, reports[i * perState + k], parsed);
            // The Switch Pro's ZL/ZR are buttons, not axes: its error is over the sticks.
            int axes = v.family == input::DeviceFamily::SwitchPro ? input::LeftTrigger : input::AxisCount;
            for (int a = 0; a < axes; ++a) maxError = std::max(maxError, static_cast<double>(std::abs(parsed.axes[a] - states[i].axes[a])));
        }
        // Speed: the whole set, repeated until at least 0.2 s.
        input::DeviceState state;
        std::size_t parsed = 0, accepted = 0;
        auto start = Clock::now();
        double seconds = 0;
        while (seconds < 0.2) {
            for (const auto& r : reports) accepted += input::parseReport(v.family, r, state) == input::ParseResult::Accepted;
            parsed += reports.size();
            seconds = std::chrono::duration<double>(Clock::now() - start).count();
        }
        if (accepted != parsed) std::fprintf(stderr, "%s: %zu of %zu reports rejected\n", v.name, parsed - accepted, parsed);
        const char* quantum = v.family == input::DeviceFamily::SpaceMouse   ? "1/350 = 2.9e-3"
                              : v.family == input::DeviceFamily::SwitchPro ? "1/2047 = 4.9e-4 (sticks; ZL/ZR digital)"
                              : v.family == input::DeviceFamily::XboxBluetooth ? "1/32767 (sticks), 1/1023 (triggers)"
                                                                               : "1/127.5 = 7.8e-3";
        parse.add({v.name, static_cast<double>(parsed) / seconds / 1e6, seconds / static_cast<double>(parsed) * 1e9, maxError, quantum});
    }
    parse.print();

    // 2. Report -> pose latency per frame: a SpaceMouse (split reports) and a DualShock 4 over Bluetooth, each with
    // the reports a 30 fps frame sees at their rates (SpaceMouse ~ 120 Hz: 4 pairs; DS4 BT ~ 250 Hz: 8 reports).
    auto ports = std::make_shared<input::FakeHidBackend::Ports>();
    input::FakeHidBackend::plug(*ports, {"/dev/hidraw-bench-0", 0x046d, 0xc626, "SpaceNavigator", "", input::Bus::Usb, 1, 8});
    input::FakeHidBackend::plug(*ports, {"/dev/hidraw-bench-1", 0x054c, 0x09cc, "Wireless Controller", "", input::Bus::Bluetooth, 1, 5});
    LiveInput live(std::make_unique<input::FakeHidBackend>(ports), input::defaultMapping(), 40.0, 60.0);
    InteractionState state;
    for (int i = 0; i < 2; ++i) {
        SceneClipMesh sphere{.name = "sphere " + std::to_string(i),
                             .geometry = meshFromDescription(R"({"shape": "sphere", "radius_mm": 20})", "<bench>", ".")};
        state.meshes.push_back(MeshState::make(state.nextMeshId++, sphere));
    }
    OrbitCamera camera;
    std::vector<double> pollUs, pipelineUs, totalUs;
    std::size_t reportsSeen = 0;
    for (int f = 0; f < frames; ++f) {
        double t = f / 30.0;
        for (int k = 0; k < 8; ++k) {
            input::DeviceState s = randomState(random, true);
            if (k % 2 == 0) {
                input::DeviceState m = randomState(random, false);
                input::FakeHidBackend::queue(*ports, "/dev/hidraw-bench-0", input::encodeSpaceMouseTranslation(m));
                input::FakeHidBackend::queue(*ports, "/dev/hidraw-bench-0", input::encodeSpaceMouseRotation(m));
            }
            input::FakeHidBackend::queue(*ports, "/dev/hidraw-bench-1", input::encodeDualShock4Bluetooth(s));
        }
        auto start = Clock::now();
        InputFrame in = live.step(t, input::KeyboardMouseState{}, 1.0 / 30.0, static_cast<int>(state.meshes.size()));
        auto mapped = Clock::now();
        state.apply(in.actions, camera, 512);
        auto end = Clock::now();
        reportsSeen += in.reports.size();
        if (f < 10) continue;  // warm-up (the first frame opens the devices)
        pollUs.push_back(std::chrono::duration<double, std::micro>(mapped - start).count());
        pipelineUs.push_back(std::chrono::duration<double, std::micro>(end - mapped).count());
        totalUs.push_back(std::chrono::duration<double, std::micro>(end - start).count());
    }
    Table latency("Report -> pose latency per frame (2 devices, " + std::to_string(reportsSeen / static_cast<std::size_t>(frames)) +
                      " reports/frame)",
                  {"stage", "min us", "median us", "p99 us", "max us", "p99 as % of a 60 Hz frame"});
    auto row = [&](const char* stage, const std::vector<double>& us) {
        latency.add({stage, *std::min_element(us.begin(), us.end()), median(us), percentile(us, 0.99), *std::max_element(us.begin(), us.end()),
                     100.0 * percentile(us, 0.99) / 16666.7});
    };
    row("poll + parse + map (LiveInput::step)", pollUs);
    row("apply to poses (InteractionState::apply)", pipelineUs);
    row("total", totalUs);
    latency.print();

    nlohmann::json document = {{"bench", "input"}, {"tables", {parse.toJson(), latency.toJson()}}};
    writeJson(jsonPath, document);
    return 0;
}

}  // namespace curette::bench
