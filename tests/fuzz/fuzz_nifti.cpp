// libFuzzer target: NIfTI-1 and NIfTI-2 headers and data from arbitrary bytes (the seeds hold both). Input
// errors are expected; anything else (a crash, a sanitizer report, an uncaught exception) is a bug.
#include "io/nifti.h"
#include "base/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        curette::io::readNiftiBytes(std::span(data, size), "fuzz.nii");
    } catch (const curette::InputError&) {
    }
    return 0;
}
