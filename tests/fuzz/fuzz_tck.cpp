// libFuzzer target: MRtrix .tck headers and streamlines from arbitrary bytes.
#include "io/tract_file.h"
#include "base/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        curette::io::readTckBytes(std::span(data, size), "fuzz.tck");
    } catch (const curette::InputError&) {
    }
    return 0;
}
