#pragma once
// Report encoders: the inverse of each parser (input/devices/parsers.h), building the bytes a device would
// send for a given state. Tests build their reports from the documented layouts with these, the input
// benchmark feeds them to the parsers, and synthetic sessions drive the device manager with them (through
// the fake hidapi backend, the production code path).

#include "input/device_state.h"

#include <cstdint>
#include <vector>

namespace curette::input {

std::vector<std::uint8_t> encodeDualShock4Usb(const DeviceState& s);        // report 0x01, 64 bytes
std::vector<std::uint8_t> encodeDualShock4Bluetooth(const DeviceState& s);  // report 0x11, 78 bytes, CRC
std::vector<std::uint8_t> encodeDualSenseUsb(const DeviceState& s);         // report 0x01, 64 bytes
std::vector<std::uint8_t> encodeDualSenseBluetooth(const DeviceState& s);   // report 0x31, 78 bytes, CRC
std::vector<std::uint8_t> encodeSwitchProFull(const DeviceState& s);        // report 0x30, 49 bytes
std::vector<std::uint8_t> encodeXboxBluetooth(const DeviceState& s);        // report 0x01, 17 bytes
// SpaceMouse: the single 13-byte report 0x01 (all axes), or the split 0x01/0x02 pair of 7 bytes; buttons 0x03.
std::vector<std::uint8_t> encodeSpaceMouseCombined(const DeviceState& s);
std::vector<std::uint8_t> encodeSpaceMouseTranslation(const DeviceState& s);
std::vector<std::uint8_t> encodeSpaceMouseRotation(const DeviceState& s);
std::vector<std::uint8_t> encodeSpaceMouseButtons(const DeviceState& s);

// Sony hat value (0..7 clockwise from north, 8 released) for the d-pad bits of `buttons`.
int sonyHat(std::uint32_t buttons);

}  // namespace curette::input
