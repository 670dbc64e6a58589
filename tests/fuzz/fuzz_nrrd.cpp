// libFuzzer target: attached NRRD headers (raw, gzip, ascii encodings) from arbitrary bytes.
#include "io/nrrd.h"
#include "base/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        // A base directory that does not exist: detached data files are never found.
        curette::io::readNrrdBytes(std::span(data, size), "fuzz.nrrd", "/nonexistent-fuzz-dir");
    } catch (const curette::InputError&) {
    }
    return 0;
}
