#pragma once
// Base64 (RFC 4648 section 4, with '=' padding): how binary data rides inside text files, a glTF buffer or an
// image of a self-contained report page (data URIs, RFC 2397).

#include <cstdint>
#include <span>
#include <string>

namespace curette {

std::string base64(std::span<const std::uint8_t> bytes);

}  // namespace curette
