// libFuzzer target: every device parser on arbitrary bytes (the first byte picks the family). Beyond not
// crashing, it checks the parsers' contract: an accepted report gives finite axes in range, and a rejected one
// leaves the state exactly as it was (a bad report never makes a mesh jump).
#include "input/devices/parsers.h"

#include <cmath>
#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace curette::input;
    if (size < 1) return 0;
    DeviceFamily family = kDeviceFamilies[data[0] % std::size(kDeviceFamilies)];
    DeviceState state;
    state.axes = {0.5f, -0.5f, 0.25f, -0.25f, 0.125f, 0.75f};
    state.buttons = 0xA5A5u;
    const DeviceState before = state;
    ParseResult result = parseReport(family, std::span(data + 1, size - 1), state);
    if (result == ParseResult::Accepted) {
        for (float a : state.axes)
            if (!std::isfinite(a) || a < -1.0f || a > 1.0f) std::abort();
        if (isGamepad(family) && (state.axes[LeftTrigger] < 0.0f || state.axes[RightTrigger] < 0.0f)) std::abort();
    } else if (result != ParseResult::Ignored && !(state == before)) {
        std::abort();
    }
    return 0;
}
