#pragma once
// Writing TRX tractograms for the tests, independently of the reader (io/trx.cpp): the members as the
// spec lays them out (header.json, positions.3.<dtype>, offsets.<dtype>, dpv/, dps/, groups/), zipped with
// libzip (stored or deflated) or written as a folder. Nothing in curette writes TRX; this is test-only.

#include "base/tractogram.h"

#include <zip.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace curette::test {

// Float -> IEEE 754 binary16 for values a half holds exactly (normal range): the tests pick such values so
// the float16 reader can be compared exactly.
inline std::uint16_t exactHalf(float f) {
    if (f == 0.0f) return std::signbit(f) ? 0x8000 : 0;
    std::uint32_t bits = std::bit_cast<std::uint32_t>(f);
    auto sign = static_cast<std::uint16_t>((bits >> 16) & 0x8000u);
    int exponent = static_cast<int>((bits >> 23) & 0xffu) - 127 + 15;
    std::uint32_t fraction = bits & 0x7fffffu;
    if (exponent <= 0 || exponent >= 31 || (fraction & 0x1fffu) != 0) throw std::logic_error("not exactly a normal half: " + std::to_string(f));
    return static_cast<std::uint16_t>(sign | (exponent << 10) | (fraction >> 13));
}

struct TrxLayout {
    std::string positionsDtype = "float32";  // float16, float32, float64 (or anything, for error tests)
    std::string offsetsDtype = "uint64";     // uint32, uint64
    bool sentinel = true;                    // N + 1 offsets ending with NB_VERTICES (else N)
    bool extras = true;                      // dpv/, dps/, groups/ members the reader must ignore
};

using TrxMembers = std::map<std::string, std::vector<std::uint8_t>>;  // name in the archive -> bytes

template <typename T>
void appendLittle(std::vector<std::uint8_t>& out, T value) {
    std::uint8_t raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    if constexpr (std::endian::native == std::endian::big)
        for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
    out.insert(out.end(), raw, raw + sizeof(T));
}

inline std::vector<std::uint8_t> textBytes(const std::string& s) { return {s.begin(), s.end()}; }

inline std::string trxHeaderJson(std::size_t streamlines, std::size_t vertices) {
    return R"({"VOXEL_TO_RASMM": [[2, 0, 0, -90], [0, 2, 0, -126], [0, 0, 2, -72], [0, 0, 0, 1]], "DIMENSIONS": [91, 109, 91], )"
           R"("NB_STREAMLINES": )" + std::to_string(streamlines) + R"(, "NB_VERTICES": )" + std::to_string(vertices) + "}";
}

inline TrxMembers trxMembers(const Tractogram& t, const TrxLayout& layout = {}) {
    TrxMembers m;
    m["header.json"] = textBytes(trxHeaderJson(t.streamlineCount(), t.points.size()));
    std::vector<std::uint8_t>& positions = m["positions.3." + layout.positionsDtype];
    for (const glm::vec3& p : t.points)
        for (int c = 0; c < 3; ++c) {
            if (layout.positionsDtype == "float16") appendLittle(positions, exactHalf(p[c]));
            else if (layout.positionsDtype == "float64") appendLittle(positions, static_cast<double>(p[c]));
            else appendLittle(positions, p[c]);
        }
    std::vector<std::uint8_t>& offsets = m["offsets." + layout.offsetsDtype];
    std::size_t entries = t.streamlineCount() + (layout.sentinel ? 1 : 0);
    for (std::size_t s = 0; s < entries; ++s) {
        if (layout.offsetsDtype == "uint32") appendLittle(offsets, t.offsets[s]);
        else appendLittle(offsets, static_cast<std::uint64_t>(t.offsets[s]));
    }
    if (layout.extras) {
        for (std::size_t v = 0; v < t.points.size(); ++v) appendLittle(m["dpv/color.3.uint8"], std::uint8_t{200});
        for (std::size_t s = 0; s < t.streamlineCount(); ++s) appendLittle(m["dps/length.float32"], 1.5f);
        appendLittle(m["groups/bundle.uint32"], std::uint32_t{0});
        appendLittle(m["dpg/bundle/mean.float32"], 3.0f);
    }
    return m;
}

// A zip of the members; folders get their own directory entries, as zip tools write them.
inline void writeTrxZip(const std::filesystem::path& path, const TrxMembers& members, bool deflate) {
    int error = 0;
    zip_t* zip = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &error);
    if (!zip) throw std::runtime_error("zip_open failed for " + path.string());
    std::vector<std::string> folders;
    for (const auto& [name, bytes] : members) {
        std::size_t slash = name.rfind('/');
        if (slash != std::string::npos) {
            std::string folder = name.substr(0, slash);
            bool known = false;
            for (const std::string& f : folders) known |= f == folder;
            if (!known && zip_dir_add(zip, folder.c_str(), 0) >= 0) folders.push_back(folder);
        }
        // The buffers outlive zip_close (the members map is the caller's), so libzip need not copy them.
        zip_source_t* source = zip_source_buffer(zip, bytes.data(), bytes.size(), 0);
        zip_int64_t index = source ? zip_file_add(zip, name.c_str(), source, ZIP_FL_OVERWRITE) : -1;
        if (index < 0) {
            zip_source_free(source);
            zip_discard(zip);
            throw std::runtime_error("zip_file_add failed for " + name);
        }
        zip_set_file_compression(zip, static_cast<zip_uint64_t>(index), deflate ? ZIP_CM_DEFLATE : ZIP_CM_STORE, 9);
        zip_file_set_mtime(zip, static_cast<zip_uint64_t>(index), 1700000000, 0);
    }
    if (zip_close(zip) != 0) {
        std::string reason = zip_strerror(zip);
        zip_discard(zip);
        throw std::runtime_error("zip_close failed for " + path.string() + ": " + reason);
    }
}

// The compression method of every top-level member of a zip (to check that "deflated" really is).
inline std::map<std::string, int> zipMethods(const std::filesystem::path& path) {
    std::map<std::string, int> methods;
    int error = 0;
    zip_t* zip = zip_open(path.c_str(), ZIP_RDONLY, &error);
    if (!zip) return methods;
    for (zip_int64_t i = 0; i < zip_get_num_entries(zip, 0); ++i) {
        zip_stat_t st;
        if (zip_stat_index(zip, static_cast<zip_uint64_t>(i), 0, &st) == 0) methods[st.name] = st.comp_method;
    }
    zip_discard(zip);
    return methods;
}

inline void writeTrxFolder(const std::filesystem::path& folder, const TrxMembers& members) {
    std::filesystem::remove_all(folder);
    for (const auto& [name, bytes] : members) {
        std::filesystem::path file = folder / name;
        std::filesystem::create_directories(file.parent_path());
        std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    }
}

}  // namespace curette::test
