#include "input/device_state.h"

namespace curette::input {

const char* familyName(DeviceFamily f) {
    switch (f) {
        case DeviceFamily::DualShock4: return "dualshock4";
        case DeviceFamily::DualSense: return "dualsense";
        case DeviceFamily::SwitchPro: return "switch_pro";
        case DeviceFamily::XboxBluetooth: return "xbox_bt";
        case DeviceFamily::SpaceMouse: return "spacemouse";
    }
    return "?";
}

std::optional<DeviceFamily> familyFromName(std::string_view name) {
    for (DeviceFamily f : kDeviceFamilies)
        if (name == familyName(f)) return f;
    return std::nullopt;
}

bool isGamepad(DeviceFamily f) { return f != DeviceFamily::SpaceMouse; }

const char* buttonName(int b) {
    static const char* names[] = {"south", "east", "west", "north", "left_shoulder", "right_shoulder", "left_stick", "right_stick",
                                  "start", "select", "home", "touchpad", "capture", "dpad_up", "dpad_right", "dpad_down",
                                  "dpad_left", "left_trigger", "right_trigger"};
    return b >= 0 && b < ButtonCount ? names[b] : "?";
}

}  // namespace curette::input
