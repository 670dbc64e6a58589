// libFuzzer target: mapping JSON through the strict reader. What it accepts must survive a round trip
// through mappingToJson (as sessions record it) unchanged, and drive a Mapper without trouble.
#include "base/error.h"
#include "input/mapping.h"

#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace curette::input;
    try {
        MappingConfig config = parseMapping(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.json");
        std::string json = mappingToJson(config);
        if (mappingToJson(parseMapping(json, "round trip")) != json) std::abort();
        Mapper mapper(config);
        DeviceState state;
        state.axes = {1.0f, -1.0f, 0.5f, -0.5f, 1.0f, 0.0f};
        state.buttons = 0xFFFFFFFFu;
        std::vector<DeviceSnapshot> devices = {{1, DeviceFamily::DualShock4, state}, {2, DeviceFamily::SpaceMouse, state}};
        for (int frame = 0; frame < 3; ++frame) mapper.update(devices, 1.0 / 60.0, 3);
    } catch (const curette::InputError&) {
    }
    return 0;
}
