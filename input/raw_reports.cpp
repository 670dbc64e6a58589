#include "input/raw_reports.h"

#include "base/error.h"

namespace curette::input {

std::string toHex(std::span<const std::uint8_t> bytes) {
    static const char* digits = "0123456789abcdef";
    std::string text;
    text.reserve(2 * bytes.size());
    for (std::uint8_t b : bytes) text += digits[b >> 4], text += digits[b & 15];
    return text;
}

std::vector<std::uint8_t> fromHex(std::string_view text, const std::string& source, const std::string& field) {
    auto nibble = [](char c) -> int {
        if (c >= '0' && c <= '9') return c - '0';
        if (c >= 'a' && c <= 'f') return c - 'a' + 10;
        if (c >= 'A' && c <= 'F') return c - 'A' + 10;
        return -1;
    };
    if (text.size() % 2 != 0) throw InputError(source, field, "hex digits in pairs", "an odd number of digits");
    std::vector<std::uint8_t> bytes;
    bytes.reserve(text.size() / 2);
    for (std::size_t i = 0; i < text.size(); i += 2) {
        int hi = nibble(text[i]), lo = nibble(text[i + 1]);
        if (hi < 0 || lo < 0) throw InputError(source, field, "hex digits in pairs", "\"" + std::string(text.substr(i, 2)) + "\"");
        bytes.push_back(static_cast<std::uint8_t>(hi * 16 + lo));
    }
    return bytes;
}

}  // namespace curette::input
