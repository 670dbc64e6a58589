#pragma once
// Writing small volume files for the parser tests.

#include "base/error.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <glm/glm.hpp>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace curette::test {

// The mricron-data atlases and heads (Debian package mricron-data, installed by scripts/setup).
inline const std::filesystem::path kMricronTemplates = "/usr/share/mricron/templates";

// Skips the test, naming the file and the package, when a mricron-data file is missing.
#define SKIP_WITHOUT_MRICRON(file)                                                                          \
    if (!std::filesystem::exists(::curette::test::kMricronTemplates / (file)))                              \
    GTEST_SKIP() << (::curette::test::kMricronTemplates / (file)).string() << " is missing (Debian package mricron-data)"

// Runs `read` and expects an InputError that names `file` and `field`.
template <typename Read>
void expectInputError(Read&& read, const std::string& file, const std::string& field) {
    try {
        read();
        ADD_FAILURE() << "expected an InputError naming " << field;
    } catch (const InputError& e) {
        EXPECT_EQ(e.file(), file);
        EXPECT_EQ(e.field(), field) << e.what();
    }
}

inline std::filesystem::path scratchDirectory() {
    std::filesystem::path dir = std::filesystem::temp_directory_path() / ("curette-io-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    return dir;
}

inline void writeBytes(const std::filesystem::path& path, const std::vector<std::uint8_t>& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

inline std::vector<std::uint8_t> gzipBytes(const std::vector<std::uint8_t>& in) {
    z_stream s{};
    deflateInit2(&s, 6, Z_DEFLATED, 16 + MAX_WBITS, 8, Z_DEFAULT_STRATEGY);
    std::vector<std::uint8_t> out(deflateBound(&s, static_cast<uLong>(in.size())) + 64);
    s.next_in = const_cast<Bytef*>(in.data());
    s.avail_in = static_cast<uInt>(in.size());
    s.next_out = out.data();
    s.avail_out = static_cast<uInt>(out.size());
    deflate(&s, Z_FINISH);
    out.resize(s.total_out);
    deflateEnd(&s);
    return out;
}

// Appends a value with the requested endianness.
template <typename T>
void put(std::vector<std::uint8_t>& bytes, T value, bool bigEndian) {
    std::uint8_t raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    if (bigEndian)
        for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
    bytes.insert(bytes.end(), raw, raw + sizeof(T));
}

template <typename T>
void set(std::vector<std::uint8_t>& bytes, std::size_t offset, T value, bool bigEndian) {
    std::vector<std::uint8_t> tmp;
    put(tmp, value, bigEndian);
    std::memcpy(bytes.data() + offset, tmp.data(), tmp.size());
}

}  // namespace curette::test
