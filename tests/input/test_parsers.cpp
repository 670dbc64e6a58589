// Device parsers against reports built from the documented layouts (input/devices/parsers.h): bytes by hand for the key
// facts, encoders for every button and extreme; truncated, unknown and corrupt reports leave the state alone.
#include "input/devices/encoders.h"
#include "input/devices/parsers.h"

#include <gtest/gtest.h>

#include <functional>
#include <random>

namespace curette::input {
namespace {

TEST(Parsers, SonyCrcMatchesTheReferenceVector) {
    // CRC-32 (zlib crc32) over 0xA1 and report 0x11 followed by 73 zero bytes -> CRC bytes ac 18 01 99
    // (little endian), computed with zlib.
    std::vector<std::uint8_t> report(74, 0);
    report[0] = 0x11;
    EXPECT_EQ(sonyBluetoothCrc(0xA1, report), 0x990118acu);
}

TEST(Parsers, DualShock4UsbBytesByHand) {
    std::vector<std::uint8_t> r(64, 0);
    r[0] = 0x01;
    r[1] = 0, r[2] = 255, r[3] = 128, r[4] = 0;  // LX left, LY down, RX centre, RY up
    r[5] = 0x04 | 0x20;                          // hat S, Cross
    r[6] = 0x01 | 0x20;                          // L1, Options
    r[7] = 0x02;                                 // touchpad click
    r[8] = 255, r[9] = 0;                        // L2 full, R2 released
    DeviceState s;
    ASSERT_EQ(parseDualShock4(r, s), ParseResult::Accepted);
    EXPECT_FLOAT_EQ(s.axes[LeftX], -1.0f);
    EXPECT_FLOAT_EQ(s.axes[LeftY], -1.0f) << "y up: 255 (down) is -1";
    EXPECT_NEAR(s.axes[RightX], 0.0f, 0.01f);
    EXPECT_FLOAT_EQ(s.axes[RightY], 1.0f);
    EXPECT_FLOAT_EQ(s.axes[LeftTrigger], 1.0f);
    EXPECT_TRUE(s.pressed(DpadDown) && !s.pressed(DpadUp) && !s.pressed(DpadLeft) && !s.pressed(DpadRight));
    EXPECT_TRUE(s.pressed(South) && s.pressed(LeftShoulder) && s.pressed(Start) && s.pressed(Touchpad));
    EXPECT_FALSE(s.pressed(East) || s.pressed(West) || s.pressed(North) || s.pressed(Home));
}

TEST(Parsers, SwitchProTwelveBitSticksByHand) {
    std::vector<std::uint8_t> r(49, 0);
    r[0] = 0x30;
    // Left X = 4095 (full right), Y = 0 (full down): b6 = 0xFF, b7 = 0x0F | (0 << 4), b8 = 0.
    r[6] = 0xFF, r[7] = 0x0F, r[8] = 0x00;
    // Right X = 2048, Y = 4095 (full up): b9 = 0x00, b10 = 0x08 | (0xF << 4), b11 = 0xFF.
    r[9] = 0x00, r[10] = 0xF8, r[11] = 0xFF;
    r[3] = 0x08;  // A
    r[5] = 0x80;  // ZL
    DeviceState s;
    ASSERT_EQ(parseSwitchPro(r, s), ParseResult::Accepted);
    EXPECT_NEAR(s.axes[LeftX], 1.0f, 1e-3f);
    EXPECT_NEAR(s.axes[LeftY], -1.0f, 1e-3f);
    EXPECT_NEAR(s.axes[RightX], 0.0f, 1e-3f);
    EXPECT_NEAR(s.axes[RightY], 1.0f, 1e-3f) << "Switch sticks grow upward";
    EXPECT_TRUE(s.pressed(East)) << "A is the east face button";
    EXPECT_EQ(s.axes[LeftTrigger], 1.0f) << "ZL is digital";
}

TEST(Parsers, SpaceMouseSignedAxesByHand) {
    // Split reports: 0x01 translation, 0x02 rotation, s16 little endian, +-350 full scale.
    DeviceState s;
    std::vector<std::uint8_t> t = {0x01, 0x5E, 0x01, 0xA2, 0xFE, 0x00, 0x00};  // X +350, Y -350, Z 0
    std::vector<std::uint8_t> r = {0x02, 0x00, 0x00, 0xAF, 0x00, 0x51, 0xFF};  // Rx 0, Ry +175, Rz -175
    ASSERT_EQ(parseSpaceMouse(t, s), ParseResult::Accepted);
    ASSERT_EQ(parseSpaceMouse(r, s), ParseResult::Accepted);
    EXPECT_FLOAT_EQ(s.axes[TranslateX], 1.0f);
    EXPECT_FLOAT_EQ(s.axes[TranslateY], -1.0f);
    EXPECT_FLOAT_EQ(s.axes[RotateY], 0.5f);
    EXPECT_FLOAT_EQ(s.axes[RotateZ], -0.5f);
    // Out-of-range values (seen at speed) clamp instead of jumping.
    std::vector<std::uint8_t> fast = {0x01, 0x23, 0x0A, 0x00, 0x00, 0x00, 0x00};  // X = 2595
    ASSERT_EQ(parseSpaceMouse(fast, s), ParseResult::Accepted);
    EXPECT_FLOAT_EQ(s.axes[TranslateX], 1.0f);
    // The single 13-byte report carries all six axes.
    std::vector<std::uint8_t> all = {0x01, 0x5E, 0x01, 0, 0, 0, 0, 0, 0, 0, 0, 0xA2, 0xFE};
    ASSERT_EQ(parseSpaceMouse(all, s), ParseResult::Accepted);
    EXPECT_FLOAT_EQ(s.axes[TranslateX], 1.0f);
    EXPECT_FLOAT_EQ(s.axes[RotateZ], -1.0f);
    EXPECT_FLOAT_EQ(s.axes[RotateY], 0.0f);
    // Buttons: bitmap little endian, bit n = button n.
    ASSERT_EQ(parseSpaceMouse(std::vector<std::uint8_t>{0x03, 0x02, 0x00}, s), ParseResult::Accepted);
    EXPECT_TRUE(s.pressed(1));
    EXPECT_FALSE(s.pressed(0));
}

using Encoder = std::function<std::vector<std::uint8_t>(const DeviceState&)>;
struct Family {
    const char* name;
    DeviceFamily family;
    std::vector<Encoder> encoders;
    std::vector<int> buttons;  // logical buttons the family reports
    bool analogTriggers;
};

std::vector<Family> gamepads() {
    std::vector<int> all;
    for (int b = 0; b < ButtonCount; ++b) all.push_back(b);
    auto without = [&](std::initializer_list<int> drop) {
        std::vector<int> list;
        for (int b : all)
            if (std::find(drop.begin(), drop.end(), b) == drop.end()) list.push_back(b);
        return list;
    };
    return {{"dualshock4", DeviceFamily::DualShock4, {encodeDualShock4Usb, encodeDualShock4Bluetooth}, without({Capture}), true},
            {"dualsense", DeviceFamily::DualSense, {encodeDualSenseUsb, encodeDualSenseBluetooth}, without({Capture}), true},
            {"switch_pro", DeviceFamily::SwitchPro, {encodeSwitchProFull}, without({Touchpad}), false},
            {"xbox_bt", DeviceFamily::XboxBluetooth, {encodeXboxBluetooth}, without({Touchpad, LeftTriggerButton, RightTriggerButton}), true}};
}

TEST(Parsers, EveryButtonBothStickExtremesTriggersAndTheHat) {
    for (const Family& f : gamepads())
        for (std::size_t e = 0; e < f.encoders.size(); ++e) {
            std::string where = std::string(f.name) + " encoder " + std::to_string(e);
            // Every button alone.
            for (int b : f.buttons) {
                if (b >= DpadUp && b <= DpadLeft) continue;  // the hat below
                DeviceState in;
                in.buttons = 1u << b;
                DeviceState out;
                ASSERT_EQ(parseReport(f.family, f.encoders[e](in), out), ParseResult::Accepted) << where;
                EXPECT_EQ(out.buttons, in.buttons) << where << " button " << buttonName(b);
            }
            // The hat's eight directions and centre.
            const std::uint32_t up = 1u << DpadUp, right = 1u << DpadRight, down = 1u << DpadDown, left = 1u << DpadLeft;
            for (std::uint32_t dpad : {0u, up, up | right, right, right | down, down, down | left, left, left | up}) {
                DeviceState in;
                in.buttons = dpad;
                DeviceState out;
                ASSERT_EQ(parseReport(f.family, f.encoders[e](in), out), ParseResult::Accepted);
                EXPECT_EQ(out.buttons, dpad) << where << " d-pad " << dpad;
            }
            // Stick extremes on each axis, both ways, and the centre.
            for (int axis : {LeftX, LeftY, RightX, RightY})
                for (float v : {-1.0f, 1.0f, 0.0f}) {
                    DeviceState in;
                    in.axes[static_cast<std::size_t>(axis)] = v;
                    DeviceState out;
                    ASSERT_EQ(parseReport(f.family, f.encoders[e](in), out), ParseResult::Accepted);
                    for (int a : {LeftX, LeftY, RightX, RightY})
                        EXPECT_NEAR(out.axes[static_cast<std::size_t>(a)], in.axes[static_cast<std::size_t>(a)], 0.01f) << where << " axis " << a;
                }
            // Triggers at 0 and full.
            if (f.analogTriggers)
                for (float v : {0.0f, 1.0f}) {
                    DeviceState in;
                    in.axes[LeftTrigger] = v;
                    in.axes[RightTrigger] = 1.0f - v;
                    DeviceState out;
                    ASSERT_EQ(parseReport(f.family, f.encoders[e](in), out), ParseResult::Accepted);
                    EXPECT_NEAR(out.axes[LeftTrigger], v, 1e-3f) << where;
                    EXPECT_NEAR(out.axes[RightTrigger], 1.0f - v, 1e-3f) << where;
                }
        }
}

TEST(Parsers, SpaceMouseEveryAxisAtBothExtremesSplitAndCombined) {
    for (int axis = 0; axis < 6; ++axis)
        for (float v : {-1.0f, 1.0f}) {
            DeviceState in;
            in.axes[static_cast<std::size_t>(axis)] = v;
            DeviceState split, combined;
            ASSERT_EQ(parseSpaceMouse(encodeSpaceMouseTranslation(in), split), ParseResult::Accepted);
            ASSERT_EQ(parseSpaceMouse(encodeSpaceMouseRotation(in), split), ParseResult::Accepted);
            ASSERT_EQ(parseSpaceMouse(encodeSpaceMouseCombined(in), combined), ParseResult::Accepted);
            EXPECT_EQ(split.axes, in.axes) << "axis " << axis;
            EXPECT_EQ(combined.axes, in.axes) << "axis " << axis;
        }
    for (int b = 0; b < 32; ++b) {
        DeviceState in, out;
        in.buttons = 1u << b;
        ASSERT_EQ(parseSpaceMouse(encodeSpaceMouseButtons(in), out), ParseResult::Accepted);
        EXPECT_EQ(out.buttons, in.buttons);
    }
}

// Truncated reports, unknown report IDs, failed checksums and random garbage are rejected without touching
// the state (no crash, no jump).
TEST(Parsers, BadReportsNeverChangeTheState) {
    DeviceState known;
    known.axes[LeftX] = 0.5f;
    known.buttons = 1u << South;
    std::mt19937 random(5);
    for (const Family& f : gamepads()) {
        for (std::size_t e = 0; e < f.encoders.size(); ++e) {
            std::vector<std::uint8_t> good = f.encoders[e](known);
            DeviceState s = known;
            // Xbox reports come in a 17- and a 16-byte layout (SDL_hidapi_xboxone.c): cut below 16 for it.
            std::size_t longest = f.family == DeviceFamily::XboxBluetooth ? 15 : good.size() - 1;
            for (std::size_t cut : {std::size_t{1}, std::size_t{5}, good.size() / 2, longest}) {
                std::vector<std::uint8_t> truncated(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(cut));
                ParseResult r = parseReport(f.family, truncated, s);
                EXPECT_NE(r, ParseResult::Accepted) << f.name << " truncated to " << cut;
                EXPECT_EQ(s, known);
            }
            std::vector<std::uint8_t> unknown = good;
            unknown[0] = 0x7E;
            EXPECT_EQ(parseReport(f.family, unknown, s), ParseResult::UnknownReport) << f.name;
            EXPECT_EQ(s, known);
        }
    }
    // A flipped bit in a Bluetooth Sony report fails its CRC.
    for (Encoder enc : {Encoder(encodeDualShock4Bluetooth), Encoder(encodeDualSenseBluetooth)}) {
        std::vector<std::uint8_t> flipped = enc(DeviceState{});
        flipped[10] ^= 0x04;
        DeviceState s = known;
        EXPECT_EQ(parseReport(flipped[0] == 0x11 ? DeviceFamily::DualShock4 : DeviceFamily::DualSense, flipped, s), ParseResult::Corrupt);
        EXPECT_EQ(s, known);
    }
    // Garbage: whatever a parser accepts stays within the normalised ranges.
    for (int n = 0; n < 20000; ++n) {
        std::vector<std::uint8_t> bytes(static_cast<std::size_t>(random() % 90));
        for (std::uint8_t& b : bytes) b = static_cast<std::uint8_t>(random());
        for (DeviceFamily family : {DeviceFamily::DualShock4, DeviceFamily::DualSense, DeviceFamily::SwitchPro, DeviceFamily::XboxBluetooth,
                                    DeviceFamily::SpaceMouse}) {
            DeviceState s = known;
            ParseResult r = parseReport(family, bytes, s);
            if (r != ParseResult::Accepted) {
                ASSERT_EQ(s, known);
                continue;
            }
            for (float a : s.axes) ASSERT_TRUE(a >= -1.0f && a <= 1.0f);
        }
    }
}

}  // namespace
}  // namespace curette::input
