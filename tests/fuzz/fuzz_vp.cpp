// libFuzzer target: 3D Slicer volume-property (.vp) text.
#include "io/transfer_function_file.h"
#include "base/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        curette::io::parseSlicerVolumeProperty(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.vp");
    } catch (const curette::InputError&) {
    }
    return 0;
}
