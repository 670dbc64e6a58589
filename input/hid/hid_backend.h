#pragma once
// The hidapi calls curette needs, behind an interface: the real one (hidapi 0.13.1, hidraw backend: USB and
// Bluetooth) and a fake for tests and synthetic sessions that drives the same device-manager code path.

#include "input/device_state.h"

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace curette::input {

struct HidDeviceDescription {
    std::string path;     // /dev/hidrawN on Linux
    std::uint16_t vendorId = 0, productId = 0;
    std::string product, serial;
    Bus bus = Bus::Unknown;
    int usagePage = 0, usage = 0;
};

class HidHandle {
public:
    virtual ~HidHandle() = default;
    // Non-blocking: > 0 bytes read (buffer[0] = report ID), 0 nothing pending, < 0 the device is gone.
    virtual int read(std::uint8_t* buffer, std::size_t size) = 0;
    virtual int write(std::span<const std::uint8_t> report) = 0;                    // output report
    virtual int getFeature(std::uint8_t* buffer, std::size_t size) = 0;             // buffer[0] = report ID
    virtual std::string lastError() const = 0;
};

class HidBackend {
public:
    virtual ~HidBackend() = default;
    virtual std::vector<HidDeviceDescription> enumerate() = 0;
    // nullptr on failure, with `error` set (e.g. "permission denied").
    virtual std::unique_ptr<HidHandle> open(const std::string& path, std::string& error) = 0;
};

// hidapi over hidraw. Throws SystemError when hid_init fails.
std::unique_ptr<HidBackend> createHidapiBackend();

}  // namespace curette::input
