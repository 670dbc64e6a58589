#pragma once
// Raw reports as text for session files: lowercase hex, two digits a byte.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace curette::input {

std::string toHex(std::span<const std::uint8_t> bytes);
// Throws InputError(source, field, "hex digits in pairs") on anything else.
std::vector<std::uint8_t> fromHex(std::string_view text, const std::string& source, const std::string& field);

}  // namespace curette::input
