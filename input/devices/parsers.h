#pragma once
// One parser per device family: a pure function from one input report (buffer[0] = report ID, as hidapi
// returns it) to the device state. It returns the reason a report was rejected (and then leaves `state`
// untouched, so a bad report never makes a mesh jump). Layouts follow the sources named at each parser:
// SDL's src/joystick/hidapi drivers, Linux drivers/hid/hid-playstation.c and hid-nintendo.c, spacenavd.

#include "input/device_state.h"

#include <cstdint>
#include <span>

namespace curette::input {

enum class ParseResult {
    Accepted,
    Ignored,         // a valid report that carries no state (battery, subcommand reply, LED ack...)
    Truncated,       // shorter than its layout
    UnknownReport,   // a report ID this family does not send
    Corrupt,         // a failed checksum or a field outside its range
};
const char* parseResultName(ParseResult r);

// DualShock 4 (SDL_hidapi_ps4.c, hid-playstation.c): USB report 0x01 (64 bytes), Bluetooth 0x11-0x19 (78 bytes, +2 offset,
// CRC-32 of 0xA1 + bytes 0..73 at 74-77) and the minimal Bluetooth 0x01 report (10 bytes).
ParseResult parseDualShock4(std::span<const std::uint8_t> report, DeviceState& state);
// DualSense (SDL_hidapi_ps5.c, hid-playstation.c): USB 0x01 (64 bytes), Bluetooth 0x31 (78 bytes, +1 offset, CRC as DS4) and the
// simple 10-byte 0x01.
ParseResult parseDualSense(std::span<const std::uint8_t> report, DeviceState& state);
// Switch Pro (SDL_hidapi_switch.c, hid-nintendo.c): full report 0x30 and subcommand reply 0x21 (>= 49 bytes; 12-bit sticks, Y up),
// simple report 0x3F (BT default before the handshake), 0x81 USB command replies (ignored).
ParseResult parseSwitchPro(std::span<const std::uint8_t> report, DeviceState& state);
// Xbox One/Series over Bluetooth (SDL_hidapi_xboxone.c): report 0x01 in the 17-byte layout and the old 16-byte (FW 3.x)
// layout; 0x02 (Xbox button, old firmware) and 0x04 (battery).
ParseResult parseXboxBluetooth(std::span<const std::uint8_t> report, DeviceState& state);
// 3Dconnexion (spacenavd src/dev.c, Blender GHOST_NDOFManager): 0x01 translation (7 bytes) or all six axes (13 bytes), 0x02 rotation, 0x03
// buttons; axes signed 16-bit, +-350 full scale (clamped), raw axis order and signs.
ParseResult parseSpaceMouse(std::span<const std::uint8_t> report, DeviceState& state);

ParseResult parseReport(DeviceFamily family, std::span<const std::uint8_t> report, DeviceState& state);

// CRC-32 (zlib's) of `seed` followed by `bytes`: the Sony Bluetooth report checksum.
std::uint32_t sonyBluetoothCrc(std::uint8_t seed, std::span<const std::uint8_t> bytes);

}  // namespace curette::input
