#pragma once
// What every device parser produces: one normalised state per device, so the mapping never sees a report
// layout. Gamepads fill the stick and trigger axes and the logical buttons; 6-DoF devices (SpaceMouse)
// fill translation and rotation and their numbered buttons.

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>
#include <string>

namespace curette::input {

enum class DeviceFamily { DualShock4, DualSense, SwitchPro, XboxBluetooth, SpaceMouse };
inline constexpr DeviceFamily kDeviceFamilies[] = {DeviceFamily::DualShock4, DeviceFamily::DualSense, DeviceFamily::SwitchPro,
                                                   DeviceFamily::XboxBluetooth, DeviceFamily::SpaceMouse};
const char* familyName(DeviceFamily family);     // "dualshock4", "dualsense", "switch_pro", "xbox_bt", "spacemouse"
std::optional<DeviceFamily> familyFromName(std::string_view name);
bool isGamepad(DeviceFamily family);

enum class Bus { Usb, Bluetooth, Unknown };

// Axes, all normalised. Gamepad sticks in [-1, 1] with +y up; triggers in [0, 1]. 6-DoF translation and
// rotation in [-1, 1] of the device's full scale, in the device's raw HID axis order and signs (the mapping
// decides what they mean: spacenavd and Blender read the 3Dconnexion axes with different signs and order).
enum Axis : int {
    LeftX, LeftY, RightX, RightY, LeftTrigger, RightTrigger,  // gamepads
    TranslateX = 0, TranslateY, TranslateZ, RotateX, RotateY, RotateZ,  // 6-DoF
    AxisCount = 6
};

// Logical gamepad buttons (bit positions). The d-pad and hat land on DpadUp..DpadLeft.
enum Button : int {
    South, East, West, North, LeftShoulder, RightShoulder, LeftStick, RightStick, Start, Select, Home, Touchpad,
    Capture, DpadUp, DpadRight, DpadDown, DpadLeft, LeftTriggerButton, RightTriggerButton, ButtonCount
};
const char* buttonName(int button);   // "south", ..., for gamepads; "button0".. for 6-DoF

struct DeviceState {
    std::array<float, AxisCount> axes{};
    std::uint32_t buttons = 0;    // gamepads: bit per Button; 6-DoF: bit n = device button n
    bool pressed(int button) const { return (buttons >> button) & 1u; }
    bool operator==(const DeviceState&) const = default;
};

}  // namespace curette::input
