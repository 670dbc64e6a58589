#pragma once
// The devices curette drives, kept current while it runs: enumeration every second (a device plugged in
// mid-session is opened, one that disappears or fails to read is released, without a restart), the output
// or feature reports a device needs before it streams, non-blocking reads drained every frame into each
// device's state, and every report kept with its time for the session recorder. A device that cannot be
// opened (Linux permissions) is reported once, with the fix.

#include "input/devices/parsers.h"
#include "input/hid/hid_backend.h"

#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

namespace curette::input {

struct DeviceInfo {
    int id = 0;               // unique for the session, never reused
    DeviceFamily family = DeviceFamily::DualShock4;
    std::string path, product, serial;
    std::uint16_t vendorId = 0, productId = 0;
    Bus bus = Bus::Unknown;
};

struct RawReport {
    int deviceId = 0;
    double timeSeconds = 0;
    std::vector<std::uint8_t> bytes;
};

struct Device {
    DeviceInfo info;
    DeviceState state;
    std::map<ParseResult, std::uint64_t> counts;  // reports by outcome
    std::unique_ptr<HidHandle> handle;
};

class DeviceManager {
public:
    explicit DeviceManager(std::unique_ptr<HidBackend> backend, double rescanSeconds = 1.0);

    // Once per frame: rescans when due, then drains every device's pending reports.
    void poll(double nowSeconds);
    const std::vector<std::unique_ptr<Device>>& devices() const { return devices_; }
    // Reports received since the last call, in arrival order.
    std::vector<RawReport> takeReports();
    // Messages for the user (opened, released, cannot open); each distinct one once.
    std::vector<std::string> takeMessages();

    // The reports a device of `family` on `bus` needs before it streams full reports (SDL's hidapi drivers,
    // Linux hid-playstation and hid-nintendo: DS4 BT reads feature 0x02; DualSense BT reads feature 0x09;
    // Switch Pro: USB handshake 80 02, 80 03, 80 02, 80 04, then subcommand 0x03 0x30 for the full report
    // mode). Exposed for tests.
    struct StartupStep {
        enum Kind { Write, GetFeature } kind;
        std::vector<std::uint8_t> bytes;  // for GetFeature: bytes[0] = report ID, size = buffer length
    };
    static std::vector<StartupStep> startupSteps(DeviceFamily family, Bus bus);

private:
    void rescan();
    void open(const HidDeviceDescription& d, DeviceFamily family);
    void say(const std::string& message);

    std::unique_ptr<HidBackend> backend_;
    double rescanSeconds_, lastScan_ = -1e300, now_ = 0;
    int nextId_ = 1;
    std::vector<std::unique_ptr<Device>> devices_;
    std::vector<RawReport> reports_;
    std::vector<std::string> messages_;
    std::set<std::string> said_;
    std::set<std::string> failedPaths_;  // cannot open: not retried every scan (reported once)
};

}  // namespace curette::input
