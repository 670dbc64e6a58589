#include "input/devices/encoders.h"

#include "input/devices/parsers.h"

#include <algorithm>
#include <cmath>

namespace curette::input {

namespace {

std::uint8_t stick8(float v, bool invert) {
    float x = invert ? -v : v;
    return static_cast<std::uint8_t>(std::clamp(std::lround(127.5f + 127.5f * x), 0L, 255L));
}
std::uint8_t trigger8(float v) { return static_cast<std::uint8_t>(std::clamp(std::lround(255.0f * v), 0L, 255L)); }
void put16(std::vector<std::uint8_t>& b, std::size_t at, std::uint16_t v) {
    b[at] = static_cast<std::uint8_t>(v & 0xFF);
    b[at + 1] = static_cast<std::uint8_t>(v >> 8);
}
std::uint8_t bit(const DeviceState& s, int button, std::uint8_t mask) { return s.pressed(button) ? mask : 0; }

// The DS4 block from the first stick byte (as parsers.cpp sonyDs4Block reads it).
void sonyBlock(const DeviceState& s, std::uint8_t* c) {
    c[0] = stick8(s.axes[LeftX], false);
    c[1] = stick8(s.axes[LeftY], true);
    c[2] = stick8(s.axes[RightX], false);
    c[3] = stick8(s.axes[RightY], true);
    c[4] = static_cast<std::uint8_t>(sonyHat(s.buttons) | bit(s, West, 0x10) | bit(s, South, 0x20) | bit(s, East, 0x40) | bit(s, North, 0x80));
    c[5] = static_cast<std::uint8_t>(bit(s, LeftShoulder, 0x01) | bit(s, RightShoulder, 0x02) | bit(s, LeftTriggerButton, 0x04) |
                                     bit(s, RightTriggerButton, 0x08) | bit(s, Select, 0x10) | bit(s, Start, 0x20) |
                                     bit(s, LeftStick, 0x40) | bit(s, RightStick, 0x80));
    c[6] = static_cast<std::uint8_t>(bit(s, Home, 0x01) | bit(s, Touchpad, 0x02));
    c[7] = trigger8(s.axes[LeftTrigger]);
    c[8] = trigger8(s.axes[RightTrigger]);
}

void sealCrc(std::vector<std::uint8_t>& b) {
    std::uint32_t crc = sonyBluetoothCrc(0xA1, std::span(b).subspan(0, 74));
    for (int i = 0; i < 4; ++i) b[74 + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(crc >> (8 * i));
}

}  // namespace

int sonyHat(std::uint32_t buttons) {
    bool up = (buttons >> DpadUp) & 1, right = (buttons >> DpadRight) & 1, down = (buttons >> DpadDown) & 1, left = (buttons >> DpadLeft) & 1;
    if (up && right) return 1;
    if (right && down) return 3;
    if (down && left) return 5;
    if (left && up) return 7;
    if (up) return 0;
    if (right) return 2;
    if (down) return 4;
    if (left) return 6;
    return 8;
}

std::vector<std::uint8_t> encodeDualShock4Usb(const DeviceState& s) {
    std::vector<std::uint8_t> b(64, 0);
    b[0] = 0x01;
    sonyBlock(s, b.data() + 1);
    return b;
}

std::vector<std::uint8_t> encodeDualShock4Bluetooth(const DeviceState& s) {
    std::vector<std::uint8_t> b(78, 0);
    b[0] = 0x11;
    b[1] = 0xC0;  // HID data present (0x80), CRC (0x40)
    sonyBlock(s, b.data() + 3);
    sealCrc(b);
    return b;
}

std::vector<std::uint8_t> encodeDualSenseUsb(const DeviceState& s) {
    std::vector<std::uint8_t> b(64, 0);
    b[0] = 0x01;
    std::uint8_t* c = b.data() + 1;
    c[0] = stick8(s.axes[LeftX], false);
    c[1] = stick8(s.axes[LeftY], true);
    c[2] = stick8(s.axes[RightX], false);
    c[3] = stick8(s.axes[RightY], true);
    c[4] = trigger8(s.axes[LeftTrigger]);
    c[5] = trigger8(s.axes[RightTrigger]);
    c[7] = static_cast<std::uint8_t>(sonyHat(s.buttons) | bit(s, West, 0x10) | bit(s, South, 0x20) | bit(s, East, 0x40) | bit(s, North, 0x80));
    c[8] = static_cast<std::uint8_t>(bit(s, LeftShoulder, 0x01) | bit(s, RightShoulder, 0x02) | bit(s, LeftTriggerButton, 0x04) |
                                     bit(s, RightTriggerButton, 0x08) | bit(s, Select, 0x10) | bit(s, Start, 0x20) |
                                     bit(s, LeftStick, 0x40) | bit(s, RightStick, 0x80));
    c[9] = static_cast<std::uint8_t>(bit(s, Home, 0x01) | bit(s, Touchpad, 0x02));
    return b;
}

std::vector<std::uint8_t> encodeDualSenseBluetooth(const DeviceState& s) {
    std::vector<std::uint8_t> usb = encodeDualSenseUsb(s);
    std::vector<std::uint8_t> b(78, 0);
    b[0] = 0x31;
    std::copy(usb.begin() + 1, usb.begin() + 64, b.begin() + 2);  // +1 offset
    sealCrc(b);
    return b;
}

std::vector<std::uint8_t> encodeSwitchProFull(const DeviceState& s) {
    std::vector<std::uint8_t> b(49, 0);
    b[0] = 0x30;
    b[2] = 0x8E;  // battery full, powered
    b[3] = static_cast<std::uint8_t>(bit(s, West, 0x01) | bit(s, North, 0x02) | bit(s, South, 0x04) | bit(s, East, 0x08) |
                                     bit(s, RightShoulder, 0x40) | bit(s, RightTriggerButton, 0x80));
    b[4] = static_cast<std::uint8_t>(bit(s, Select, 0x01) | bit(s, Start, 0x02) | bit(s, RightStick, 0x04) | bit(s, LeftStick, 0x08) |
                                     bit(s, Home, 0x10) | bit(s, Capture, 0x20));
    b[5] = static_cast<std::uint8_t>(bit(s, DpadDown, 0x01) | bit(s, DpadUp, 0x02) | bit(s, DpadRight, 0x04) | bit(s, DpadLeft, 0x08) |
                                     bit(s, LeftShoulder, 0x40) | bit(s, LeftTriggerButton, 0x80));
    auto twelve = [](float v) { return static_cast<int>(std::clamp(std::lround(2048.0f + 2047.0f * v), 0L, 4095L)); };
    auto pack = [&](std::size_t at, float x, float y) {
        int X = twelve(x), Y = twelve(y);
        b[at] = static_cast<std::uint8_t>(X & 0xFF);
        b[at + 1] = static_cast<std::uint8_t>(((X >> 8) & 0x0F) | ((Y & 0x0F) << 4));
        b[at + 2] = static_cast<std::uint8_t>(Y >> 4);
    };
    pack(6, s.axes[LeftX], s.axes[LeftY]);
    pack(9, s.axes[RightX], s.axes[RightY]);
    return b;
}

std::vector<std::uint8_t> encodeXboxBluetooth(const DeviceState& s) {
    std::vector<std::uint8_t> b(17, 0);
    b[0] = 0x01;
    auto axis16 = [](float v) { return static_cast<std::uint16_t>(std::clamp(std::lround(32768.0f + 32767.0f * v), 0L, 65535L)); };
    put16(b, 1, axis16(s.axes[LeftX]));
    put16(b, 3, axis16(-s.axes[LeftY]));
    put16(b, 5, axis16(s.axes[RightX]));
    put16(b, 7, axis16(-s.axes[RightY]));
    put16(b, 9, static_cast<std::uint16_t>(std::lround(1023.0f * std::clamp(s.axes[LeftTrigger], 0.0f, 1.0f))));
    put16(b, 11, static_cast<std::uint16_t>(std::lround(1023.0f * std::clamp(s.axes[RightTrigger], 0.0f, 1.0f))));
    int hat = sonyHat(s.buttons);
    b[13] = static_cast<std::uint8_t>(hat == 8 ? 0 : hat + 1);
    b[14] = static_cast<std::uint8_t>(bit(s, South, 0x01) | bit(s, East, 0x02) | bit(s, West, 0x08) | bit(s, North, 0x10) |
                                      bit(s, LeftShoulder, 0x40) | bit(s, RightShoulder, 0x80));
    b[15] = static_cast<std::uint8_t>(bit(s, Select, 0x04) | bit(s, Start, 0x08) | bit(s, Home, 0x10) | bit(s, LeftStick, 0x20) |
                                      bit(s, RightStick, 0x40));
    b[16] = bit(s, Capture, 0x01);
    return b;
}

namespace {
std::vector<std::uint8_t> spaceMouseAxes(std::uint8_t id, const DeviceState& s, int first, int count) {
    std::vector<std::uint8_t> b(1 + 2 * static_cast<std::size_t>(count), 0);
    b[0] = id;
    for (int a = 0; a < count; ++a)
        put16(b, 1 + 2 * static_cast<std::size_t>(a),
              static_cast<std::uint16_t>(static_cast<std::int16_t>(std::lround(350.0f * s.axes[static_cast<std::size_t>(first + a)]))));
    return b;
}
}  // namespace

std::vector<std::uint8_t> encodeSpaceMouseCombined(const DeviceState& s) { return spaceMouseAxes(0x01, s, 0, 6); }
std::vector<std::uint8_t> encodeSpaceMouseTranslation(const DeviceState& s) { return spaceMouseAxes(0x01, s, 0, 3); }
std::vector<std::uint8_t> encodeSpaceMouseRotation(const DeviceState& s) { return spaceMouseAxes(0x02, s, 3, 3); }
std::vector<std::uint8_t> encodeSpaceMouseButtons(const DeviceState& s) {
    return {0x03, static_cast<std::uint8_t>(s.buttons & 0xFF), static_cast<std::uint8_t>((s.buttons >> 8) & 0xFF),
            static_cast<std::uint8_t>((s.buttons >> 16) & 0xFF), static_cast<std::uint8_t>((s.buttons >> 24) & 0xFF)};
}

}  // namespace curette::input
