#pragma once
// Files are written atomically: the content goes to a temporary file beside the target, is flushed to disk,
// then renamed over the target. A crash or an error leaves either the old file or none, never a partial one.

#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>
#include <string_view>

namespace curette {

// Throws SystemError (naming the path) when the directory is not writable or the disk is full.
void writeFileAtomically(const std::filesystem::path& path, std::span<const std::uint8_t> bytes);
void writeFileAtomically(const std::filesystem::path& path, std::string_view text);

// Reads a whole file; throws InputError(path, "", "a readable file") when it cannot be opened.
std::vector<std::uint8_t> readFileBytes(const std::filesystem::path& path);

}  // namespace curette
