// libFuzzer target: MetaImage headers and LOCAL data (raw and zlib/gzip compressed) from arbitrary bytes.
#include "io/metaimage.h"
#include "base/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        // A base directory that does not exist: separate data files are never found.
        curette::io::readMetaImageBytes(std::span(data, size), "fuzz.mha", "/nonexistent-fuzz-dir");
    } catch (const curette::InputError&) {
    }
    return 0;
}
