#include "input/hid/known_devices.h"

namespace curette::input {

std::optional<DeviceFamily> familyOf(std::uint16_t vid, std::uint16_t pid) {
    struct Entry {
        std::uint16_t vid, pid;
        DeviceFamily family;
    };
    static const Entry table[] = {
        // Sony (SDL usb_ids.h, hid-playstation): DualShock 4 v1, v2, USB wireless adapter; DualSense, Edge.
        {0x054c, 0x05c4, DeviceFamily::DualShock4}, {0x054c, 0x09cc, DeviceFamily::DualShock4},
        {0x054c, 0x0ba0, DeviceFamily::DualShock4}, {0x054c, 0x0ce6, DeviceFamily::DualSense},
        {0x054c, 0x0df2, DeviceFamily::DualSense},
        // Nintendo Switch Pro Controller (USB and BT).
        {0x057e, 0x2009, DeviceFamily::SwitchPro},
        // Xbox One / Series over Bluetooth (USB is GIP, not HID: Linux's xpad driver binds it).
        {0x045e, 0x02e0, DeviceFamily::XboxBluetooth}, {0x045e, 0x02fd, DeviceFamily::XboxBluetooth},
        {0x045e, 0x0b20, DeviceFamily::XboxBluetooth}, {0x045e, 0x0b05, DeviceFamily::XboxBluetooth},
        {0x045e, 0x0b22, DeviceFamily::XboxBluetooth}, {0x045e, 0x0b13, DeviceFamily::XboxBluetooth},
        {0x045e, 0x0b0c, DeviceFamily::XboxBluetooth}, {0x045e, 0x0b21, DeviceFamily::XboxBluetooth},
        // 3Dconnexion (spacenavd usbdb, Blender, OpenSCAD): Logitech-era and 3Dconnexion VIDs.
        {0x046d, 0xc603, DeviceFamily::SpaceMouse}, {0x046d, 0xc605, DeviceFamily::SpaceMouse},
        {0x046d, 0xc606, DeviceFamily::SpaceMouse}, {0x046d, 0xc621, DeviceFamily::SpaceMouse},
        {0x046d, 0xc623, DeviceFamily::SpaceMouse}, {0x046d, 0xc625, DeviceFamily::SpaceMouse},
        {0x046d, 0xc626, DeviceFamily::SpaceMouse}, {0x046d, 0xc627, DeviceFamily::SpaceMouse},
        {0x046d, 0xc628, DeviceFamily::SpaceMouse}, {0x046d, 0xc629, DeviceFamily::SpaceMouse},
        {0x046d, 0xc62b, DeviceFamily::SpaceMouse}, {0x256f, 0xc62e, DeviceFamily::SpaceMouse},
        {0x256f, 0xc62f, DeviceFamily::SpaceMouse}, {0x256f, 0xc631, DeviceFamily::SpaceMouse},
        {0x256f, 0xc632, DeviceFamily::SpaceMouse}, {0x256f, 0xc633, DeviceFamily::SpaceMouse},
        {0x256f, 0xc635, DeviceFamily::SpaceMouse}, {0x256f, 0xc636, DeviceFamily::SpaceMouse},
        {0x256f, 0xc638, DeviceFamily::SpaceMouse}, {0x256f, 0xc63a, DeviceFamily::SpaceMouse},
        {0x256f, 0xc652, DeviceFamily::SpaceMouse},
    };
    for (const Entry& e : table)
        if (e.vid == vid && e.pid == pid) return e.family;
    return std::nullopt;
}

}  // namespace curette::input
