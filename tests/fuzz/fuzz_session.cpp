// libFuzzer target: session files (JSON Lines), strict or lenient by the first byte. Only InputError may
// leave the parser; a lenient parse of anything with a valid header returns its valid prefix.
#include "session/session.h"
#include "base/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 1) return 0;
    bool lenient = data[0] & 1;
    try {
        curette::parseSession(std::string_view(reinterpret_cast<const char*>(data + 1), size - 1), "fuzz.jsonl", lenient);
    } catch (const curette::InputError&) {
    }
    return 0;
}
