#include "input/hid/device_manager.h"

#include "base/log.h"
#include "input/hid/known_devices.h"
#include "input/raw_reports.h"

#include <algorithm>
#include <utility>

namespace curette::input {

DeviceManager::DeviceManager(std::unique_ptr<HidBackend> backend, double rescanSeconds)
    : backend_(std::move(backend)), rescanSeconds_(rescanSeconds) {}

void DeviceManager::say(const std::string& message) {
    if (!said_.insert(message).second) return;
    messages_.push_back(message);
    log::info(message);
}

std::vector<DeviceManager::StartupStep> DeviceManager::startupSteps(DeviceFamily family, Bus bus) {
    std::vector<StartupStep> steps;
    auto padded = [](std::vector<std::uint8_t> bytes, std::size_t size) {
        bytes.resize(size, 0);
        return bytes;
    };
    switch (family) {
        case DeviceFamily::DualShock4:
            if (bus == Bus::Bluetooth) steps.push_back({StartupStep::GetFeature, padded({0x02}, 37)});
            break;
        case DeviceFamily::DualSense:
            if (bus == Bus::Bluetooth) steps.push_back({StartupStep::GetFeature, padded({0x09}, 20)});
            break;
        case DeviceFamily::SwitchPro: {
            std::size_t size = bus == Bus::Bluetooth ? 49 : 64;
            if (bus != Bus::Bluetooth)
                for (std::uint8_t command : {std::uint8_t{0x02}, std::uint8_t{0x03}, std::uint8_t{0x02}, std::uint8_t{0x04}}) steps.push_back({StartupStep::Write, padded({0x80, command}, size)});
            // Subcommand 0x03 (input report mode) with 0x30 (full), sequence 0, neutral rumble.
            steps.push_back({StartupStep::Write, padded({0x01, 0x00, 0x00, 0x01, 0x40, 0x40, 0x00, 0x01, 0x40, 0x40, 0x03, 0x30}, size)});
            break;
        }
        case DeviceFamily::XboxBluetooth:
        case DeviceFamily::SpaceMouse: break;
    }
    return steps;
}

void DeviceManager::open(const HidDeviceDescription& d, DeviceFamily family) {
    std::string error;
    std::unique_ptr<HidHandle> handle = backend_->open(d.path, error);
    std::string name = std::string(familyName(family)) + (d.product.empty() ? "" : " (" + d.product + ")");
    if (!handle) {
        failedPaths_.insert(d.path);
        if (error == "permission denied")
            say("cannot open " + d.path + " " + name + ": permission denied; install the udev rules: sudo cp assets/udev/70-curette.rules "
                "/etc/udev/rules.d/ && sudo udevadm control --reload && sudo udevadm trigger");
        else
            say("cannot open " + d.path + " " + name + ": " + error);
        return;
    }
    for (const StartupStep& step : startupSteps(family, d.bus)) {
        int result = 0;
        if (step.kind == StartupStep::Write) {
            result = handle->write(step.bytes);
        } else {
            std::vector<std::uint8_t> buffer = step.bytes;
            result = handle->getFeature(buffer.data(), buffer.size());
        }
        if (result < 0) say(d.path + " " + name + ": a start-up report failed (" + handle->lastError() + "); it may send reduced reports");
    }
    auto device = std::make_unique<Device>();
    device->info = {nextId_++, family, d.path, d.product, d.serial, d.vendorId, d.productId, d.bus};
    device->handle = std::move(handle);
    say("opened " + d.path + " " + name + " as device " + std::to_string(device->info.id));
    devices_.push_back(std::move(device));
}

void DeviceManager::rescan() {
    std::vector<HidDeviceDescription> found = backend_->enumerate();
    std::set<std::string> present;
    for (const HidDeviceDescription& d : found) present.insert(d.path);
    // Release devices that left.
    for (auto it = devices_.begin(); it != devices_.end();) {
        if (!present.count((*it)->info.path)) {
            say("released device " + std::to_string((*it)->info.id) + " (" + (*it)->info.path + "): unplugged");
            it = devices_.erase(it);
        } else {
            ++it;
        }
    }
    // A path that failed and disappeared may come back with new permissions: forget it.
    for (auto it = failedPaths_.begin(); it != failedPaths_.end();) it = present.count(*it) ? std::next(it) : failedPaths_.erase(it);
    // Open new ones (several top-level collections share a path: one device per path).
    std::set<std::string> opened;
    for (const auto& d : devices_) opened.insert(d->info.path);
    for (const HidDeviceDescription& d : found) {
        if (opened.count(d.path) || failedPaths_.count(d.path)) continue;
        std::optional<DeviceFamily> family = familyOf(d.vendorId, d.productId);
        if (!family) continue;
        open(d, *family);
        opened.insert(d.path);
    }
}

void DeviceManager::poll(double now) {
    now_ = now;
    if (now - lastScan_ >= rescanSeconds_) {
        lastScan_ = now;
        rescan();
    }
    std::uint8_t buffer[256];
    for (auto it = devices_.begin(); it != devices_.end();) {
        Device& device = **it;
        bool lost = false;
        // Drain everything pending (bounded, so a flood cannot stall a frame).
        for (int n = 0; n < 256; ++n) {
            int size = device.handle->read(buffer, sizeof buffer);
            if (size == 0) break;
            if (size < 0) {
                lost = true;
                break;
            }
            std::span<const std::uint8_t> report(buffer, static_cast<std::size_t>(size));
            ParseResult result = parseReport(device.info.family, report, device.state);
            if (device.counts[result]++ == 0 && result != ParseResult::Accepted && result != ParseResult::Ignored)
                say("device " + std::to_string(device.info.id) + " (" + familyName(device.info.family) + "): ignored a report (" +
                    parseResultName(result) + ", id 0x" + toHex(report.first(1)) + ", " + std::to_string(size) +
                    " bytes); further ones are only counted");
            reports_.push_back({device.info.id, now, std::vector<std::uint8_t>(report.begin(), report.end())});
        }
        if (lost) {
            say("released device " + std::to_string(device.info.id) + " (" + device.info.path + "): " + device.handle->lastError());
            it = devices_.erase(it);
        } else {
            ++it;
        }
    }
}

std::vector<RawReport> DeviceManager::takeReports() { return std::exchange(reports_, {}); }
std::vector<std::string> DeviceManager::takeMessages() { return std::exchange(messages_, {}); }

}  // namespace curette::input
