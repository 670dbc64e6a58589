#pragma once
// SHA-256 (FIPS 180-4), for the checksums a report records of its input files (plan/report_output.h).

#include <array>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>

namespace curette {

class Sha256 {
public:
    Sha256();
    void update(std::span<const std::uint8_t> bytes);
    void update(std::string_view text);
    // The digest as 64 lower-case hex digits, as sha256sum prints it. The hasher is spent after it.
    std::string hexDigest();

private:
    void block(const std::uint8_t* data);
    std::array<std::uint32_t, 8> state_;
    std::array<std::uint8_t, 64> pending_{};
    std::size_t pendingBytes_ = 0;
    std::uint64_t totalBytes_ = 0;
};

std::string sha256Hex(std::span<const std::uint8_t> bytes);
std::string sha256Hex(std::string_view text);
// A file's digest, read in pieces; throws InputError(path, "", "a readable file") when it cannot be read.
std::string sha256OfFile(const std::filesystem::path& path);

}  // namespace curette
