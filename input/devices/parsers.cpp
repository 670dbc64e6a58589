#include "input/devices/parsers.h"

#include <zlib.h>

#include <algorithm>
#include <cstring>

namespace curette::input {

namespace {

std::uint16_t u16(const std::uint8_t* p) { return static_cast<std::uint16_t>(p[0] | (p[1] << 8)); }
std::int16_t s16(const std::uint8_t* p) { return static_cast<std::int16_t>(u16(p)); }
std::uint32_t u32(const std::uint8_t* p) {
    return static_cast<std::uint32_t>(p[0]) | (static_cast<std::uint32_t>(p[1]) << 8) | (static_cast<std::uint32_t>(p[2]) << 16) |
           (static_cast<std::uint32_t>(p[3]) << 24);
}

// u8 stick (0..255, centre 128, y down) -> [-1, 1] with y up.
float stick8(std::uint8_t v) { return std::clamp((static_cast<float>(v) - 127.5f) / 127.5f, -1.0f, 1.0f); }
float trigger8(std::uint8_t v) { return static_cast<float>(v) / 255.0f; }

void setBit(std::uint32_t& bits, int button, bool on) {
    if (on) bits |= 1u << button;
}

// Hat 0..7 clockwise from north, >= 8 released (Sony, Switch simple). Returns false for nothing invalid:
// Sony documents 8 as released and 9..15 are unused (taken as released).
void hatToDpad(int hat, std::uint32_t& bits) {
    if (hat < 0 || hat > 7) return;
    bool up = hat == 7 || hat == 0 || hat == 1, right = hat >= 1 && hat <= 3, down = hat >= 3 && hat <= 5, left = hat >= 5 && hat <= 7;
    setBit(bits, DpadUp, up);
    setBit(bits, DpadRight, right);
    setBit(bits, DpadDown, down);
    setBit(bits, DpadLeft, left);
}

// The DS4 / DualSense common block from the first stick byte (`c`), used by the DS4 report layout.
void sonyDs4Block(const std::uint8_t* c, DeviceState& s) {
    // c[0..3] sticks, c[4] hat + face buttons, c[5] shoulders..., c[6] PS/touchpad, c[7], c[8] triggers.
    s.axes[LeftX] = stick8(c[0]);
    s.axes[LeftY] = -stick8(c[1]);
    s.axes[RightX] = stick8(c[2]);
    s.axes[RightY] = -stick8(c[3]);
    s.axes[LeftTrigger] = trigger8(c[7]);
    s.axes[RightTrigger] = trigger8(c[8]);
    std::uint32_t b = 0;
    hatToDpad(c[4] & 0x0F, b);
    setBit(b, West, c[4] & 0x10);   // Square
    setBit(b, South, c[4] & 0x20);  // Cross
    setBit(b, East, c[4] & 0x40);   // Circle
    setBit(b, North, c[4] & 0x80);  // Triangle
    setBit(b, LeftShoulder, c[5] & 0x01);
    setBit(b, RightShoulder, c[5] & 0x02);
    setBit(b, LeftTriggerButton, c[5] & 0x04);
    setBit(b, RightTriggerButton, c[5] & 0x08);
    setBit(b, Select, c[5] & 0x10);  // Share / Create
    setBit(b, Start, c[5] & 0x20);   // Options
    setBit(b, LeftStick, c[5] & 0x40);
    setBit(b, RightStick, c[5] & 0x80);
    setBit(b, Home, c[6] & 0x01);
    setBit(b, Touchpad, c[6] & 0x02);
    s.buttons = b;
}

bool sonyCrcValid(std::span<const std::uint8_t> r) {
    if (r.size() < 78) return false;
    return sonyBluetoothCrc(0xA1, r.subspan(0, 74)) == u32(r.data() + 74);
}

}  // namespace

const char* parseResultName(ParseResult r) {
    switch (r) {
        case ParseResult::Accepted: return "accepted";
        case ParseResult::Ignored: return "ignored";
        case ParseResult::Truncated: return "truncated";
        case ParseResult::UnknownReport: return "unknown report id";
        case ParseResult::Corrupt: return "corrupt";
    }
    return "?";
}

std::uint32_t sonyBluetoothCrc(std::uint8_t seed, std::span<const std::uint8_t> bytes) {
    uLong crc = crc32(0L, Z_NULL, 0);
    crc = crc32(crc, &seed, 1);
    crc = crc32(crc, bytes.data(), static_cast<uInt>(bytes.size()));
    return static_cast<std::uint32_t>(crc);
}

ParseResult parseDualShock4(std::span<const std::uint8_t> r, DeviceState& state) {
    if (r.empty()) return ParseResult::Truncated;
    DeviceState s;
    if (r[0] == 0x01) {
        if (r.size() == 10) {
            // Bluetooth minimal report before the switch to 0x11: sticks, 3 button bytes, triggers.
            sonyDs4Block(r.data() + 1, s);
        } else if (r.size() >= 10) {
            if (r.size() < 64) return ParseResult::Truncated;
            sonyDs4Block(r.data() + 1, s);
        } else {
            return ParseResult::Truncated;
        }
    } else if (r[0] >= 0x11 && r[0] <= 0x19) {
        if (r.size() < 78) return ParseResult::Truncated;
        if (!(r[1] & 0x80)) return ParseResult::Ignored;  // no HID data in this report (SDL)
        if (!sonyCrcValid(r)) return ParseResult::Corrupt;
        sonyDs4Block(r.data() + 3, s);
    } else {
        return ParseResult::UnknownReport;
    }
    state = s;
    return ParseResult::Accepted;
}

ParseResult parseDualSense(std::span<const std::uint8_t> r, DeviceState& state) {
    if (r.empty()) return ParseResult::Truncated;
    DeviceState s;
    const std::uint8_t* c = nullptr;  // the USB layout's byte 1
    if (r[0] == 0x01 && r.size() == 10) {
        sonyDs4Block(r.data() + 1, s);  // the simple report shares the DS4 minimal layout
        state = s;
        return ParseResult::Accepted;
    }
    if (r[0] == 0x01) {
        if (r.size() < 64) return ParseResult::Truncated;
        c = r.data() + 1;
    } else if (r[0] == 0x31) {
        if (r.size() < 78) return ParseResult::Truncated;
        if (!sonyCrcValid(r)) return ParseResult::Corrupt;
        c = r.data() + 2;
    } else {
        return ParseResult::UnknownReport;
    }
    // USB offsets 1..4 sticks, 5,6 triggers, 8 hat + face, 9 shoulders, 10 PS/touchpad/mute.
    s.axes[LeftX] = stick8(c[0]);
    s.axes[LeftY] = -stick8(c[1]);
    s.axes[RightX] = stick8(c[2]);
    s.axes[RightY] = -stick8(c[3]);
    s.axes[LeftTrigger] = trigger8(c[4]);
    s.axes[RightTrigger] = trigger8(c[5]);
    std::uint32_t b = 0;
    hatToDpad(c[7] & 0x0F, b);
    setBit(b, West, c[7] & 0x10);
    setBit(b, South, c[7] & 0x20);
    setBit(b, East, c[7] & 0x40);
    setBit(b, North, c[7] & 0x80);
    setBit(b, LeftShoulder, c[8] & 0x01);
    setBit(b, RightShoulder, c[8] & 0x02);
    setBit(b, LeftTriggerButton, c[8] & 0x04);
    setBit(b, RightTriggerButton, c[8] & 0x08);
    setBit(b, Select, c[8] & 0x10);
    setBit(b, Start, c[8] & 0x20);
    setBit(b, LeftStick, c[8] & 0x40);
    setBit(b, RightStick, c[8] & 0x80);
    setBit(b, Home, c[9] & 0x01);
    setBit(b, Touchpad, c[9] & 0x02);
    s.buttons = b;
    state = s;
    return ParseResult::Accepted;
}

ParseResult parseSwitchPro(std::span<const std::uint8_t> r, DeviceState& state) {
    if (r.empty()) return ParseResult::Truncated;
    DeviceState s;
    if (r[0] == 0x30 || r[0] == 0x21) {
        if (r.size() < 49 && !(r[0] == 0x21 && r.size() >= 13)) return ParseResult::Truncated;
        const std::uint8_t* p = r.data();
        // Sticks: 12-bit packed, centre ~2048, Y grows upward (SDL inverts, Linux hid-nintendo negates for
        // their y-down conventions; ours is y-up, so Y is taken as is). Uncalibrated nominal range +-2048.
        auto twelve = [](const std::uint8_t* b, bool high) {
            return high ? static_cast<int>((b[1] >> 4) | (b[2] << 4)) : static_cast<int>(b[0] | ((b[1] & 0x0F) << 8));
        };
        auto axis = [](int v) { return std::clamp((static_cast<float>(v) - 2048.0f) / 2047.0f, -1.0f, 1.0f); };
        s.axes[LeftX] = axis(twelve(p + 6, false));
        s.axes[LeftY] = axis(twelve(p + 6, true));
        s.axes[RightX] = axis(twelve(p + 9, false));
        s.axes[RightY] = axis(twelve(p + 9, true));
        std::uint32_t b = 0;
        // Nintendo's face-button positions: B south, A east, Y west, X north.
        setBit(b, West, p[3] & 0x01);   // Y
        setBit(b, North, p[3] & 0x02);  // X
        setBit(b, South, p[3] & 0x04);  // B
        setBit(b, East, p[3] & 0x08);   // A
        setBit(b, RightShoulder, p[3] & 0x40);
        setBit(b, RightTriggerButton, p[3] & 0x80);
        setBit(b, Select, p[4] & 0x01);  // Minus
        setBit(b, Start, p[4] & 0x02);   // Plus
        setBit(b, RightStick, p[4] & 0x04);
        setBit(b, LeftStick, p[4] & 0x08);
        setBit(b, Home, p[4] & 0x10);
        setBit(b, Capture, p[4] & 0x20);
        setBit(b, DpadDown, p[5] & 0x01);
        setBit(b, DpadUp, p[5] & 0x02);
        setBit(b, DpadRight, p[5] & 0x04);
        setBit(b, DpadLeft, p[5] & 0x08);
        setBit(b, LeftShoulder, p[5] & 0x40);
        setBit(b, LeftTriggerButton, p[5] & 0x80);
        s.buttons = b;
        s.axes[LeftTrigger] = (p[5] & 0x80) ? 1.0f : 0.0f;   // ZL / ZR are digital
        s.axes[RightTrigger] = (p[3] & 0x80) ? 1.0f : 0.0f;
        state = s;
        return ParseResult::Accepted;
    }
    if (r[0] == 0x3F) {
        if (r.size() < 12) return ParseResult::Truncated;
        const std::uint8_t* p = r.data();
        std::uint32_t b = 0;
        setBit(b, South, p[1] & 0x01);  // B
        setBit(b, East, p[1] & 0x02);   // A
        setBit(b, West, p[1] & 0x04);   // Y
        setBit(b, North, p[1] & 0x08);  // X
        setBit(b, LeftShoulder, p[1] & 0x10);
        setBit(b, RightShoulder, p[1] & 0x20);
        setBit(b, LeftTriggerButton, p[1] & 0x40);
        setBit(b, RightTriggerButton, p[1] & 0x80);
        setBit(b, Select, p[2] & 0x01);
        setBit(b, Start, p[2] & 0x02);
        setBit(b, LeftStick, p[2] & 0x04);
        setBit(b, RightStick, p[2] & 0x08);
        setBit(b, Home, p[2] & 0x10);
        setBit(b, Capture, p[2] & 0x20);
        hatToDpad(p[3], b);
        auto axis16 = [](std::uint16_t v) { return std::clamp((static_cast<float>(v) - 32768.0f) / 32767.0f, -1.0f, 1.0f); };
        s.axes[LeftX] = axis16(u16(p + 4));
        s.axes[LeftY] = -axis16(u16(p + 6));  // u16 axes grow downward like a HID joystick
        s.axes[RightX] = axis16(u16(p + 8));
        s.axes[RightY] = -axis16(u16(p + 10));
        s.axes[LeftTrigger] = (p[1] & 0x40) ? 1.0f : 0.0f;
        s.axes[RightTrigger] = (p[1] & 0x80) ? 1.0f : 0.0f;
        s.buttons = b;
        state = s;
        return ParseResult::Accepted;
    }
    if (r[0] == 0x81) return ParseResult::Ignored;  // USB command reply (handshake)
    return ParseResult::UnknownReport;
}

ParseResult parseXboxBluetooth(std::span<const std::uint8_t> r, DeviceState& state) {
    if (r.empty()) return ParseResult::Truncated;
    if (r[0] == 0x04) return r.size() >= 2 ? ParseResult::Ignored : ParseResult::Truncated;  // battery
    if (r[0] == 0x02) {
        // Old firmware: the Xbox button alone in report 0x02 byte 1 bit 0.
        if (r.size() < 2) return ParseResult::Truncated;
        DeviceState s = state;
        s.buttons = (s.buttons & ~(1u << Home)) | ((r[1] & 0x01) ? 1u << Home : 0u);
        state = s;
        return ParseResult::Accepted;
    }
    if (r[0] != 0x01) return ParseResult::UnknownReport;
    if (r.size() < 16) return ParseResult::Truncated;
    const std::uint8_t* p = r.data();
    DeviceState s;
    auto axis16 = [](std::uint16_t v) { return std::clamp((static_cast<float>(v) - 32768.0f) / 32767.0f, -1.0f, 1.0f); };
    s.axes[LeftX] = axis16(u16(p + 1));
    s.axes[LeftY] = -axis16(u16(p + 3));  // 0 = up
    s.axes[RightX] = axis16(u16(p + 5));
    s.axes[RightY] = -axis16(u16(p + 7));
    std::uint16_t lt = u16(p + 9), rt = u16(p + 11);
    if (lt > 1023 || rt > 1023 || p[13] > 8) return ParseResult::Corrupt;  // 10-bit triggers, hat 0..8
    s.axes[LeftTrigger] = static_cast<float>(lt) / 1023.0f;
    s.axes[RightTrigger] = static_cast<float>(rt) / 1023.0f;
    std::uint32_t b = 0;
    hatToDpad(p[13] == 0 ? -1 : p[13] - 1, b);  // 0 centred, 1 = N ... 8 = NW
    if (r.size() == 16) {
        // FW 3.x layout.
        setBit(b, South, p[14] & 0x01);
        setBit(b, East, p[14] & 0x02);
        setBit(b, West, p[14] & 0x04);
        setBit(b, North, p[14] & 0x08);
        setBit(b, LeftShoulder, p[14] & 0x10);
        setBit(b, RightShoulder, p[14] & 0x20);
        setBit(b, Select, p[14] & 0x40);
        setBit(b, Start, p[14] & 0x80);
        setBit(b, LeftStick, p[15] & 0x01);
        setBit(b, RightStick, p[15] & 0x02);
        b |= state.buttons & (1u << Home);  // from report 0x02
    } else {
        setBit(b, South, p[14] & 0x01);
        setBit(b, East, p[14] & 0x02);
        setBit(b, West, p[14] & 0x08);
        setBit(b, North, p[14] & 0x10);
        setBit(b, LeftShoulder, p[14] & 0x40);
        setBit(b, RightShoulder, p[14] & 0x80);
        setBit(b, Select, p[15] & 0x04);  // View
        setBit(b, Start, p[15] & 0x08);   // Menu
        setBit(b, Home, p[15] & 0x10);
        setBit(b, LeftStick, p[15] & 0x20);
        setBit(b, RightStick, p[15] & 0x40);
        if (r.size() > 16) setBit(b, Capture, p[16] & 0x01);  // Share (Series)
    }
    s.buttons = b;
    state = s;
    return ParseResult::Accepted;
}

ParseResult parseSpaceMouse(std::span<const std::uint8_t> r, DeviceState& state) {
    if (r.empty()) return ParseResult::Truncated;
    // +-350 is the descriptors' logical range; larger values (seen at speed) are clamped, never a jump.
    auto axis = [](const std::uint8_t* p) { return std::clamp(static_cast<float>(s16(p)) / 350.0f, -1.0f, 1.0f); };
    DeviceState s = state;  // split reports update part of the state
    switch (r[0]) {
        case 0x01:
            if (r.size() >= 13) {
                for (int a = 0; a < 6; ++a) s.axes[static_cast<std::size_t>(a)] = axis(r.data() + 1 + 2 * a);
            } else if (r.size() >= 7) {
                for (int a = 0; a < 3; ++a) s.axes[static_cast<std::size_t>(a)] = axis(r.data() + 1 + 2 * a);
            } else {
                return ParseResult::Truncated;
            }
            break;
        case 0x02:
            if (r.size() < 7) return ParseResult::Truncated;
            for (int a = 0; a < 3; ++a) s.axes[static_cast<std::size_t>(3 + a)] = axis(r.data() + 1 + 2 * a);
            break;
        case 0x03: {
            if (r.size() < 2) return ParseResult::Truncated;
            std::uint32_t bits = 0;
            for (std::size_t i = 1; i < std::min<std::size_t>(r.size(), 5); ++i) bits |= static_cast<std::uint32_t>(r[i]) << (8 * (i - 1));
            s.buttons = bits;
            break;
        }
        case 0x17:
        case 0x1c:
        case 0x1d: return ParseResult::Ignored;  // battery; newer devices' button-number reports
        default: return ParseResult::UnknownReport;
    }
    state = s;
    return ParseResult::Accepted;
}

ParseResult parseReport(DeviceFamily family, std::span<const std::uint8_t> report, DeviceState& state) {
    switch (family) {
        case DeviceFamily::DualShock4: return parseDualShock4(report, state);
        case DeviceFamily::DualSense: return parseDualSense(report, state);
        case DeviceFamily::SwitchPro: return parseSwitchPro(report, state);
        case DeviceFamily::XboxBluetooth: return parseXboxBluetooth(report, state);
        case DeviceFamily::SpaceMouse: return parseSpaceMouse(report, state);
    }
    return ParseResult::UnknownReport;
}

}  // namespace curette::input
