#pragma once
// Which VID/PID pairs curette drives, and with which parser (IDs from SDL's usb_ids.h, the Linux HID drivers
// and spacenavd's device list).

#include "input/device_state.h"

#include <cstdint>
#include <optional>

namespace curette::input {

std::optional<DeviceFamily> familyOf(std::uint16_t vendorId, std::uint16_t productId);

}  // namespace curette::input
