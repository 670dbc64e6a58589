#include "input/hid/hid_backend.h"

#include "base/error.h"

#include <hidapi/hidapi.h>

#include <cerrno>
#include <cstring>
#include <cwchar>

namespace curette::input {

namespace {

std::string narrow(const wchar_t* text) {
    std::string out;
    if (!text) return out;
    for (; *text; ++text) out += *text < 128 ? static_cast<char>(*text) : '?';
    return out;
}

class HidapiHandle final : public HidHandle {
public:
    explicit HidapiHandle(hid_device* device) : device_(device) { hid_set_nonblocking(device_, 1); }
    ~HidapiHandle() override { hid_close(device_); }
    int read(std::uint8_t* buffer, std::size_t size) override { return hid_read(device_, buffer, size); }
    int write(std::span<const std::uint8_t> report) override { return hid_write(device_, report.data(), report.size()); }
    int getFeature(std::uint8_t* buffer, std::size_t size) override { return hid_get_feature_report(device_, buffer, size); }
    std::string lastError() const override { return narrow(hid_error(device_)); }

private:
    hid_device* device_;
};

class HidapiBackend final : public HidBackend {
public:
    HidapiBackend() {
        if (hid_init() != 0) throw SystemError("hidapi could not initialise (hid_init failed)");
    }
    ~HidapiBackend() override { hid_exit(); }
    std::vector<HidDeviceDescription> enumerate() override {
        std::vector<HidDeviceDescription> list;
        hid_device_info* all = hid_enumerate(0, 0);
        for (hid_device_info* d = all; d; d = d->next) {
            HidDeviceDescription desc;
            desc.path = d->path ? d->path : "";
            desc.vendorId = d->vendor_id;
            desc.productId = d->product_id;
            desc.product = narrow(d->product_string);
            desc.serial = narrow(d->serial_number);
            desc.bus = d->bus_type == HID_API_BUS_USB ? Bus::Usb : d->bus_type == HID_API_BUS_BLUETOOTH ? Bus::Bluetooth : Bus::Unknown;
            desc.usagePage = d->usage_page;
            desc.usage = d->usage;
            list.push_back(desc);
        }
        hid_free_enumeration(all);
        return list;
    }
    std::unique_ptr<HidHandle> open(const std::string& path, std::string& error) override {
        errno = 0;
        hid_device* device = hid_open_path(path.c_str());
        if (!device) {
            int code = errno;
            std::string text = narrow(hid_error(nullptr));  // hidapi >= 0.13 keeps the global error text
            bool denied = code == EACCES || code == EPERM || text.find("ermission denied") != std::string::npos;
            error = denied ? "permission denied" : !text.empty() ? text : code ? std::strerror(code) : "cannot open";
            return nullptr;
        }
        return std::make_unique<HidapiHandle>(device);
    }
};

}  // namespace

std::unique_ptr<HidBackend> createHidapiBackend() { return std::make_unique<HidapiBackend>(); }

}  // namespace curette::input
