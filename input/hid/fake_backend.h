#pragma once
// A scriptable stand-in for hidapi: devices are plugged and unplugged, reports queued, permissions denied,
// and everything written to a device is kept. The device manager runs on it exactly as on hidapi, so hot-plug,
// permissions and start-up handshakes are tested for real, and synthetic sessions use the production path.

#include "input/hid/hid_backend.h"

#include <deque>
#include <map>
#include <memory>

namespace curette::input {

class FakeHidBackend final : public HidBackend {
public:
    struct Port {
        HidDeviceDescription description;
        std::deque<std::vector<std::uint8_t>> pending;
        bool permissionDenied = false;
        bool broken = false;                               // reads fail as if unplugged mid-read
        std::vector<std::vector<std::uint8_t>> written;    // output reports, in order
        std::vector<std::uint8_t> featuresRead;            // feature report IDs requested
    };
    // The ports outlive the backend (the device manager owns the backend; tests keep this).
    struct Ports {
        std::map<std::string, Port> byPath;
    };

    explicit FakeHidBackend(std::shared_ptr<Ports> ports) : ports_(std::move(ports)) {}
    std::vector<HidDeviceDescription> enumerate() override;
    std::unique_ptr<HidHandle> open(const std::string& path, std::string& error) override;

    static void plug(Ports& ports, HidDeviceDescription description, bool permissionDenied = false);
    static void unplug(Ports& ports, const std::string& path);
    static void queue(Ports& ports, const std::string& path, std::vector<std::uint8_t> report);

private:
    std::shared_ptr<Ports> ports_;
};

}  // namespace curette::input
