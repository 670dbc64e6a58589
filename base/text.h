#pragma once
// Small text helpers every reader needs.

#include <string_view>

namespace curette {

// White space as std::isspace has it in the "C" locale.
inline constexpr std::string_view kWhiteSpace = " \t\n\v\f\r";

// `text` without the leading and trailing characters found in `blanks` (a format says which pad its values).
std::string_view trim(std::string_view text, std::string_view blanks = kWhiteSpace);

}  // namespace curette
