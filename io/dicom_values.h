#pragma once
// What the io/dicom*.cpp files share: reading DICOM value text (PS3.5 6.2), formatting numbers for messages,
// and the sink GDCM writes its messages to. Internal to io/; defined in io/dicom.cpp.

#include <cstdint>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace curette::io::dicom_detail {

// Pixel data up to this size is accepted whatever its compression ratio (decoding), and may be this much
// short of what the header promises (the structure check while scanning).
constexpr std::uint64_t kAlwaysAcceptedBytes = 64ull << 20;

// GDCM's warnings and errors, kept out of std::cerr; decodeFile reads it for "Incomplete Pixel Data".
std::ostringstream& gdcmMessages();
void forgetGdcmMessages();

std::string trim(std::string_view text);   // without the padding of PS3.5 6.2 (space, NUL, tabs, line ends)
std::string fmt(double value);  // %.6g
// The numbers of a multi-valued DS or IS ("a\b\c"), or nothing when any value is not a number.
std::optional<std::vector<double>> numbers(const std::string& text);
std::optional<double> number(const std::string& text);

}  // namespace curette::io::dicom_detail
