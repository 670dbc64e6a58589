// libFuzzer target: TrackVis .trk headers and tracks from arbitrary bytes.
#include "io/tract_file.h"
#include "base/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        curette::io::readTrkBytes(std::span(data, size), "fuzz.trk");
    } catch (const curette::InputError&) {
    }
    return 0;
}
