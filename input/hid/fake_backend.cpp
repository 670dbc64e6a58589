#include "input/hid/fake_backend.h"

#include <algorithm>
#include <cstring>

namespace curette::input {

namespace {

class FakeHandle final : public HidHandle {
public:
    FakeHandle(std::shared_ptr<FakeHidBackend::Ports> ports, std::string path) : ports_(std::move(ports)), path_(std::move(path)) {}
    FakeHidBackend::Port* port() {
        auto it = ports_->byPath.find(path_);
        return it == ports_->byPath.end() ? nullptr : &it->second;
    }
    int read(std::uint8_t* buffer, std::size_t size) override {
        FakeHidBackend::Port* p = port();
        if (!p || p->broken) return -1;
        if (p->pending.empty()) return 0;
        std::vector<std::uint8_t> report = std::move(p->pending.front());
        p->pending.pop_front();
        std::size_t n = std::min(size, report.size());
        std::memcpy(buffer, report.data(), n);
        return static_cast<int>(n);
    }
    int write(std::span<const std::uint8_t> report) override {
        FakeHidBackend::Port* p = port();
        if (!p) return -1;
        p->written.emplace_back(report.begin(), report.end());
        return static_cast<int>(report.size());
    }
    int getFeature(std::uint8_t* buffer, std::size_t size) override {
        FakeHidBackend::Port* p = port();
        if (!p || size == 0) return -1;
        p->featuresRead.push_back(buffer[0]);
        std::memset(buffer + 1, 0, size - 1);
        return static_cast<int>(size);
    }
    std::string lastError() const override { return "device disconnected"; }

private:
    std::shared_ptr<FakeHidBackend::Ports> ports_;
    std::string path_;
};

}  // namespace

std::vector<HidDeviceDescription> FakeHidBackend::enumerate() {
    std::vector<HidDeviceDescription> list;
    for (const auto& [path, port] : ports_->byPath) list.push_back(port.description);
    return list;
}

std::unique_ptr<HidHandle> FakeHidBackend::open(const std::string& path, std::string& error) {
    auto it = ports_->byPath.find(path);
    if (it == ports_->byPath.end()) {
        error = "no such device";
        return nullptr;
    }
    if (it->second.permissionDenied) {
        error = "permission denied";
        return nullptr;
    }
    return std::make_unique<FakeHandle>(ports_, path);
}

void FakeHidBackend::plug(Ports& ports, HidDeviceDescription description, bool permissionDenied) {
    Port& p = ports.byPath[description.path];
    p = Port{};
    p.description = std::move(description);
    p.permissionDenied = permissionDenied;
}

void FakeHidBackend::unplug(Ports& ports, const std::string& path) { ports.byPath.erase(path); }

void FakeHidBackend::queue(Ports& ports, const std::string& path, std::vector<std::uint8_t> report) {
    ports.byPath[path].pending.push_back(std::move(report));
}

}  // namespace curette::input
