// libFuzzer target: transfer-function JSON through the strict JSON reader.
#include "io/transfer_function_file.h"
#include "base/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        curette::io::parseTransferFunctionJsonText(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.json");
    } catch (const curette::InputError&) {
    }
    return 0;
}
