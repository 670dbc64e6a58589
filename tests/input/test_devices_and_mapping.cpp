// The device manager on the fake hidapi backend (hot-plug, permissions, start-up reports, report log), the
// mapping (dead zones, curves, speeds, frames, two devices, button edges) and the keyboard fallback.
#include "base/error.h"
#include "input/devices/encoders.h"
#include "input/hid/device_manager.h"
#include "input/hid/fake_backend.h"
#include "input/keyboard_mouse.h"
#include "input/mapping.h"
#include "input/raw_reports.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace curette::input {
namespace {

HidDeviceDescription describe(const std::string& path, std::uint16_t vid, std::uint16_t pid, Bus bus) {
    HidDeviceDescription d;
    d.path = path, d.vendorId = vid, d.productId = pid, d.bus = bus, d.product = "test";
    return d;
}

TEST(DeviceManager, HotPlugPermissionsStartupAndTheReportLog) {
    auto ports = std::make_shared<FakeHidBackend::Ports>();
    DeviceManager manager(std::make_unique<FakeHidBackend>(ports), 1.0);
    manager.poll(0.0);
    EXPECT_TRUE(manager.devices().empty());

    // A DualShock 4 over Bluetooth appears mid-run: opened at the next scan, its mode switched by reading
    // feature report 0x02, then streaming.
    FakeHidBackend::plug(*ports, describe("/dev/hidraw3", 0x054c, 0x09cc, Bus::Bluetooth));
    manager.poll(0.5);
    EXPECT_TRUE(manager.devices().empty()) << "not yet rescanned";
    manager.poll(1.0);
    ASSERT_EQ(manager.devices().size(), 1u);
    EXPECT_EQ(ports->byPath["/dev/hidraw3"].featuresRead, std::vector<std::uint8_t>{0x02});
    DeviceState pushed;
    pushed.axes[LeftX] = 1.0f;
    FakeHidBackend::queue(*ports, "/dev/hidraw3", encodeDualShock4Bluetooth(pushed));
    FakeHidBackend::queue(*ports, "/dev/hidraw3", {0x11, 0x00});  // truncated: counted, ignored
    manager.poll(1.1);
    const Device& ds4 = *manager.devices()[0];
    EXPECT_NEAR(ds4.state.axes[LeftX], 1.0f, 0.01f);
    EXPECT_EQ(ds4.counts.at(ParseResult::Accepted), 1u);
    EXPECT_EQ(ds4.counts.at(ParseResult::Truncated), 1u);
    std::vector<RawReport> log = manager.takeReports();
    ASSERT_EQ(log.size(), 2u);
    EXPECT_EQ(log[0].deviceId, ds4.info.id);
    EXPECT_EQ(log[0].timeSeconds, 1.1);

    // A Switch Pro over USB gets its handshake and the full-report subcommand.
    FakeHidBackend::plug(*ports, describe("/dev/hidraw4", 0x057e, 0x2009, Bus::Usb));
    manager.poll(2.0);
    const auto& written = ports->byPath["/dev/hidraw4"].written;
    ASSERT_EQ(written.size(), 5u);
    EXPECT_EQ(written[0][0], 0x80);
    EXPECT_EQ(written[0][1], 0x02);
    EXPECT_EQ(written[3][1], 0x04);
    EXPECT_EQ(written[4][0], 0x01);
    EXPECT_EQ(written[4][10], 0x03);
    EXPECT_EQ(written[4][11], 0x30);
    EXPECT_EQ(written[4].size(), 64u);

    // A device without permission is reported once, with the fix, and not retried every scan.
    FakeHidBackend::plug(*ports, describe("/dev/hidraw5", 0x256f, 0xc62e, Bus::Usb), true);
    manager.takeMessages();
    manager.poll(3.0);
    manager.poll(4.0);
    manager.poll(5.0);
    std::vector<std::string> messages = manager.takeMessages();
    int permission = 0;
    for (const std::string& m : messages) permission += m.find("permission denied") != std::string::npos && m.find("70-curette.rules") != std::string::npos;
    EXPECT_EQ(permission, 1);
    EXPECT_EQ(manager.devices().size(), 2u);

    // Unplugged: released at the next scan. A failing read releases it at once.
    FakeHidBackend::unplug(*ports, "/dev/hidraw3");
    manager.poll(6.0);
    EXPECT_EQ(manager.devices().size(), 1u);
    ports->byPath["/dev/hidraw4"].broken = true;
    manager.poll(6.1);
    EXPECT_TRUE(manager.devices().empty());
    // Unknown devices are left alone.
    FakeHidBackend::plug(*ports, describe("/dev/hidraw9", 0x1234, 0x5678, Bus::Usb));
    manager.poll(8.0);
    EXPECT_TRUE(manager.devices().empty());
}

MappingConfig oneGamepad(double deadZone, ResponseCurve curve, MotionFrame frame) {
    DeviceBinding b;
    b.family = "gamepad";
    b.mesh = 0;
    b.frame = frame;
    b.translation = MotionBinding{{"left_x", "left_y", "triggers"}, deadZone, curve, 50.0};
    b.rotation = MotionBinding{{"-right_y", "right_x", "shoulders"}, deadZone, curve, 90.0};
    b.buttons = {{South, "cycle_mesh"}, {East, "reset_pose"}, {Start, "toggle_recording"}};
    return MappingConfig{{b}};
}

glm::dvec3 totalTranslation(const std::vector<Action>& actions) {
    glm::dvec3 t(0.0);
    for (const Action& a : actions)
        if (auto* m = std::get_if<MoveMesh>(&a)) t += m->translationMm;
    return t;
}

TEST(Mapping, DeadZonesCurvesAndSpeeds) {
    Mapper mapper(oneGamepad(0.2, {}, MotionFrame::Camera));
    std::vector<DeviceSnapshot> devices{{1, DeviceFamily::DualShock4, {}}};
    // Inside the radial dead zone: nothing.
    devices[0].state.axes[LeftX] = 0.12f, devices[0].state.axes[LeftY] = 0.12f;  // |v| = 0.17 < 0.2
    EXPECT_TRUE(mapper.update(devices, 0.1, 3).empty());
    // Just outside: small and continuous.
    devices[0].state.axes[LeftX] = 0.21f, devices[0].state.axes[LeftY] = 0.0f;
    glm::dvec3 t = totalTranslation(mapper.update(devices, 0.1, 3));
    EXPECT_GT(t.x, 0.0);
    EXPECT_LT(t.x, 0.1);
    // One second of full deflection at 50 mm/s moves 50 mm, in 60 frames as in one.
    devices[0].state.axes[LeftX] = 1.0f;
    glm::dvec3 sum(0.0);
    for (int i = 0; i < 60; ++i) sum += totalTranslation(mapper.update(devices, 1.0 / 60.0, 3));
    EXPECT_NEAR(sum.x, 50.0, 1e-9);
    // A power curve halves... squares the response: half deflection past the zone gives a quarter speed.
    Mapper curved(oneGamepad(0.0, ResponseCurve{ResponseCurve::Power, 2.0}, MotionFrame::Camera));
    devices[0].state.axes[LeftX] = 0.5f;
    EXPECT_NEAR(totalTranslation(curved.update(devices, 1.0, 3)).x, 50.0 * 0.25, 1e-6);
    // Triggers: forward minus back.
    devices[0].state.axes[LeftX] = 0.0f;
    devices[0].state.axes[RightTrigger] = 1.0f;
    EXPECT_NEAR(totalTranslation(curved.update(devices, 1.0, 3)).z, 50.0, 1e-6);
}

TEST(Mapping, FramesButtonEdgesAndCycling) {
    Mapper world(oneGamepad(0.1, {}, MotionFrame::World));
    std::vector<DeviceSnapshot> devices{{1, DeviceFamily::XboxBluetooth, {}}};
    devices[0].state.axes[RightX] = 1.0f;
    std::vector<Action> a = world.update(devices, 0.5, 3);
    ASSERT_EQ(a.size(), 1u);
    const MoveMesh& m = std::get<MoveMesh>(a[0]);
    EXPECT_EQ(m.frame, MotionFrame::World);
    EXPECT_NEAR(m.rotationRad.y, 0.5 * 90.0 * std::numbers::pi / 180.0, 1e-9);
    // Holding a button fires once; the next press again. Cycling wraps.
    devices[0].state.axes[RightX] = 0.0f;
    devices[0].state.buttons = 1u << South;
    int selects = 0, held = -1;
    for (int frame = 0; frame < 5; ++frame)
        for (const Action& action : world.update(devices, 0.016, 3))
            if (auto* s = std::get_if<SelectMesh>(&action)) ++selects, held = s->mesh;
    EXPECT_EQ(selects, 1);
    EXPECT_EQ(held, 1);
    for (int press = 0; press < 2; ++press) {
        devices[0].state.buttons = 0;
        world.update(devices, 0.016, 3);
        devices[0].state.buttons = 1u << South;
        world.update(devices, 0.016, 3);
    }
    EXPECT_EQ(world.heldMesh(0), 0) << "1 -> 2 -> 0 with three meshes";
    devices[0].state.buttons = 1u << East;
    a = world.update(devices, 0.016, 3);
    ASSERT_EQ(a.size(), 1u);
    EXPECT_EQ(std::get<ResetPose>(a[0]).mesh, 0);
}

TEST(Mapping, TwoDevicesDriveTwoMeshesInOneFrame) {
    MappingConfig config = loadMapping(std::string(CURETTE_SOURCE_DIR) + "/assets/input/default_mapping.json");
    Mapper mapper(config);
    DeviceState mouse, pad;
    mouse.axes[TranslateX] = 1.0f;  // the SpaceMouse pushed right
    pad.axes[LeftY] = 1.0f;         // the gamepad's stick up
    std::vector<Action> actions = mapper.update({{3, DeviceFamily::SpaceMouse, mouse}, {7, DeviceFamily::DualSense, pad}}, 0.1, 2);
    std::map<int, glm::dvec3> byMesh;
    for (const Action& a : actions)
        if (auto* m = std::get_if<MoveMesh>(&a)) byMesh[m->mesh] += m->translationMm;
    ASSERT_EQ(byMesh.size(), 2u);
    EXPECT_GT(byMesh[0].x, 0.0) << "the SpaceMouse holds mesh 0 and moves it right";
    EXPECT_GT(byMesh[1].y, 0.0) << "the gamepad holds mesh 1 and moves it up";
    EXPECT_EQ(mapper.boundDevice(0), 3);
    EXPECT_EQ(mapper.boundDevice(1), 7);
    // The recorded mapping parses back to the same behaviour.
    Mapper again(parseMapping(mappingToJson(config), "recorded"));
    std::vector<Action> same = again.update({{3, DeviceFamily::SpaceMouse, mouse}, {7, DeviceFamily::DualSense, pad}}, 0.1, 2);
    ASSERT_EQ(same.size(), actions.size());
    for (std::size_t i = 0; i < same.size(); ++i)
        EXPECT_EQ(std::get<MoveMesh>(same[i]).translationMm, std::get<MoveMesh>(actions[i]).translationMm);
}

TEST(Mapping, BadConfigNamesTheKey) {
    auto expectError = [](const std::string& json, const std::string& field) {
        try {
            parseMapping(json, "mapping.json");
            FAIL() << "expected an error naming " << field;
        } catch (const InputError& e) {
            EXPECT_EQ(e.field(), field) << e.what();
        }
    };
    const std::string motion = R"("translation": {"axes": ["left_x", "left_y", "none"], "mm_per_s": 10})";
    expectError(R"({"bindings": [{"device": {"family": "joystick"}}]})", "bindings[0].device.family");
    expectError(R"({"bindings": [{"device": {"family": "gamepad"}, "colour": 1}]})", "bindings[0].colour");
    expectError(R"({"bindings": [{"device": {"family": "gamepad"}, "translation": {"axes": ["left_x", "tx", "none"], "mm_per_s": 1}}]})",
                "bindings[0].translation.axes[1]");
    expectError(R"({"bindings": [{"device": {"family": "gamepad"}, "translation": {"axes": ["left_x", "left_y", "none"], "dead_zone": 1.5, "mm_per_s": 1}}]})",
                "bindings[0].translation.dead_zone");
    expectError(R"({"bindings": [{"device": {"family": "gamepad"}, "buttons": {"south": "explode"}}]})", "bindings[0].buttons.south");
    expectError(R"({"bindings": [{"device": {"family": "spacemouse"}, "buttons": {"south": "reset_pose"}}]})", "bindings[0].buttons.south");
    expectError(R"({"bindings": []})", "bindings");
    expectError(R"({"bindings": [{"device": {"family": "gamepad"}, )" + motion + R"(}], "extra": 1})", "extra");
}

TEST(Keyboard, SameActionsAsTheDevices) {
    KeyboardMapper keys(40.0, 60.0);
    KeyboardMouseState s;
    s.keys = (1u << static_cast<int>(Key::D)) | (1u << static_cast<int>(Key::W));
    std::vector<Action> a = keys.update(s, 0.5, 2);
    ASSERT_EQ(a.size(), 1u);
    EXPECT_EQ(std::get<MoveMesh>(a[0]).translationMm, glm::dvec3(20.0, 0.0, 20.0));
    s.keys = 1u << static_cast<int>(Key::Tab);
    a = keys.update(s, 0.016, 2);
    ASSERT_EQ(a.size(), 1u);
    EXPECT_EQ(std::get<SelectMesh>(a[0]).mesh, 1);
    EXPECT_TRUE(keys.update(s, 0.016, 2).empty()) << "held: no repeat";
    s.keys = 1u << static_cast<int>(Key::Digit4);
    a = keys.update(s, 0.016, 2);
    EXPECT_EQ(std::get<SetShading>(a[0]).mode, "cao");
    s.keys = 1u << static_cast<int>(Key::Digit6);
    a = keys.update(s, 0.016, 2);
    ASSERT_EQ(a.size(), 1u);
    EXPECT_EQ(std::get<SetShading>(a[0]).mode, "ismos");
    s.keys = 0;
    s.rightDragPixels = {3, -2};
    a = keys.update(s, 0.016, 2);
    EXPECT_EQ(std::get<DragMesh>(a[0]).pixels, glm::dvec2(3, -2));
    EXPECT_EQ(std::get<DragMesh>(a[0]).mesh, 1);
}

// Lights: J/L and I/K turn the selected light at the keyboard's degrees per second, O selects the next one,
// and a Shift + left drag turns it by kLightDegPerPixel (right: yaw +, up on screen: pitch +); no mesh needed.
TEST(Keyboard, LightKeysAndShiftDragTurnTheSelectedLight) {
    KeyboardMapper keys(40.0, 60.0);
    KeyboardMouseState s;
    const double degree = std::numbers::pi / 180.0;
    s.keys = (1u << static_cast<int>(Key::L)) | (1u << static_cast<int>(Key::K));
    std::vector<Action> a = keys.update(s, 0.5, 0);
    ASSERT_EQ(a.size(), 1u);
    const MoveLight& m = std::get<MoveLight>(a[0]);
    EXPECT_EQ(m.light, -1) << "the selected light";
    EXPECT_NEAR(m.yawPitchRad.x, 30.0 * degree, 1e-15);
    EXPECT_NEAR(m.yawPitchRad.y, -30.0 * degree, 1e-15);
    s.keys = (1u << static_cast<int>(Key::J)) | (1u << static_cast<int>(Key::I));
    a = keys.update(s, 0.25, 3);
    ASSERT_EQ(a.size(), 1u);
    EXPECT_NEAR(std::get<MoveLight>(a[0]).yawPitchRad.x, -15.0 * degree, 1e-15);
    EXPECT_NEAR(std::get<MoveLight>(a[0]).yawPitchRad.y, 15.0 * degree, 1e-15);
    s.keys = 1u << static_cast<int>(Key::O);
    a = keys.update(s, 0.016, 0);
    ASSERT_EQ(a.size(), 1u);
    EXPECT_TRUE(std::holds_alternative<NextLight>(a[0]));
    EXPECT_TRUE(keys.update(s, 0.016, 0).empty()) << "held: no repeat";
    s.keys = 0;
    s.lightDragPixels = {8, -4};   // right and up on the screen
    a = keys.update(s, 0.016, 2);
    ASSERT_EQ(a.size(), 1u);
    EXPECT_NEAR(std::get<MoveLight>(a[0]).yawPitchRad.x, 8 * kLightDegPerPixel * degree, 1e-15);
    EXPECT_NEAR(std::get<MoveLight>(a[0]).yawPitchRad.y, 4 * kLightDegPerPixel * degree, 1e-15);
    s.lightDragPixels = {0, 0};
    EXPECT_TRUE(keys.update(s, 0.016, 2).empty()) << "nothing held: no light action";
}

TEST(RawReports, HexRoundTripAndErrors) {
    std::vector<std::uint8_t> bytes = {0x00, 0x11, 0xab, 0xff};
    EXPECT_EQ(toHex(bytes), "0011abff");
    EXPECT_EQ(fromHex("0011ABff", "s", "f"), bytes);
    EXPECT_THROW(fromHex("001", "s", "f"), InputError);
    EXPECT_THROW(fromHex("00zz", "s", "f"), InputError);
}

}  // namespace
}  // namespace curette::input
