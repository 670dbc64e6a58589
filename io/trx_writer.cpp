#include "io/trx_writer.h"

#include "base/atomic_file.h"
#include "base/error.h"
#include "io/tract_writing.h"

#include <zlib.h>

#include <cstdio>
#include <limits>
#include <span>
#include <string>

namespace curette::io {

namespace {

// PKWARE APPNOTE 4.3: 4.3.7 local file header, 4.3.12 central directory header, 4.3.16 end of central directory.
constexpr std::uint32_t kLocalSignature = 0x04034b50, kCentralSignature = 0x02014b50, kEndSignature = 0x06054b50;
constexpr std::uint16_t kVersionNeeded = 20;              // 2.0: the lowest that names "stored" with a directory
constexpr std::uint16_t kVersionMadeBy = (3 << 8) | 20;  // 3 = UNIX, so the external attributes are its modes
constexpr std::uint16_t kDosDate = (0 << 9) | (1 << 5) | 1, kDosTime = 0;  // 1980-01-01 00:00: reproducible files
constexpr std::uint32_t kUnixMode = 0100644u << 16;
// Without Zip64 sizes and offsets are 32-bit, and 0xFFFFFFFF means "see the Zip64 record".
constexpr std::uint64_t kMaxZip32 = std::numeric_limits<std::uint32_t>::max() - 1;

struct Entry {
    std::string name;
    std::uint32_t crc = 0;
    std::uint64_t size = 0, localOffset = 0;
};

// The fields local and central headers share, from "version needed" to the extra field length.
void appendCommon(std::vector<std::uint8_t>& out, const Entry& e) {
    appendLittle(out, kVersionNeeded);
    appendLittle(out, std::uint16_t{0});  // flags: sizes and CRC are in the header, names are ASCII
    appendLittle(out, std::uint16_t{0});  // method: stored
    appendLittle(out, kDosTime);
    appendLittle(out, kDosDate);
    appendLittle(out, e.crc);
    appendLittle(out, static_cast<std::uint32_t>(e.size));  // compressed = uncompressed when stored
    appendLittle(out, static_cast<std::uint32_t>(e.size));
    appendLittle(out, static_cast<std::uint16_t>(e.name.size()));
    appendLittle(out, std::uint16_t{0});  // no extra field
}

std::vector<std::uint8_t> localHeader(const Entry& e) {
    std::vector<std::uint8_t> out;
    appendLittle(out, kLocalSignature);
    appendCommon(out, e);
    out.insert(out.end(), e.name.begin(), e.name.end());
    return out;
}

std::uint32_t crcOf(std::uint32_t crc, std::span<const std::uint8_t> bytes) {
    return static_cast<std::uint32_t>(crc32_z(crc, bytes.data(), bytes.size()));
}

// The positions' little-endian float32 bytes in parts of `chunk` points, each handed to `use`.
template <typename Use>
void forEachPositionChunk(const std::vector<glm::vec3>& points, std::size_t chunk, Use&& use) {
    std::vector<std::uint8_t> bytes;
    bytes.reserve(12 * chunk);
    for (std::size_t first = 0; first < points.size(); first += chunk) {
        bytes.clear();
        std::size_t end = std::min(points.size(), first + chunk);
        for (std::size_t p = first; p < end; ++p)
            for (int a = 0; a < 3; ++a) appendLittle(bytes, points[p][a]);
        use(std::span<const std::uint8_t>(bytes));
    }
}

std::string headerJson(const Tractogram& tracts) {
    const TractReferenceGrid grid = tractReferenceGrid(tracts);
    const glm::dmat4 m = grid.voxelToRas();
    std::string json = "{\n  \"DIMENSIONS\": [" + std::to_string(grid.dims.x) + ", " + std::to_string(grid.dims.y) + ", " +
                       std::to_string(grid.dims.z) + "],\n  \"VOXEL_TO_RASMM\": [";
    for (int row = 0; row < 4; ++row) {
        json += row ? ",\n    [" : "\n    [";
        for (int col = 0; col < 4; ++col) {
            char number[32];
            std::snprintf(number, sizeof number, "%.17g", m[col][row]);
            json += (col ? ", " : "") + std::string(number);
        }
        json += "]";
    }
    json += "\n  ],\n  \"NB_STREAMLINES\": " + std::to_string(tracts.streamlineCount()) + ",\n  \"NB_VERTICES\": " +
            std::to_string(tracts.points.size()) + "\n}\n";
    return json;
}

}  // namespace

void writeTrx(const std::filesystem::path& path, const Tractogram& tracts) {
    const std::string source = path.string();
    requireWritableTractogram(source, tracts);

    const std::string header = headerJson(tracts);
    std::vector<std::uint8_t> offsets;
    offsets.reserve(8 * tracts.offsets.size());
    for (std::uint32_t o : tracts.offsets) appendLittle(offsets, std::uint64_t{o});

    Entry headerEntry{"header.json", crcOf(0, {reinterpret_cast<const std::uint8_t*>(header.data()), header.size()}), header.size()};
    Entry offsetsEntry{"offsets.uint64", crcOf(0, offsets), offsets.size()};
    Entry positionsEntry{"positions.3.float32", 0, 12 * static_cast<std::uint64_t>(tracts.points.size())};
    // Every local header, member and the directory before the end record must sit below 4 GiB.
    std::uint64_t archive = 0;
    for (Entry* e : {&headerEntry, &offsetsEntry, &positionsEntry}) {
        e->localOffset = archive;
        archive += 30 + e->name.size() + e->size;
    }
    archive += 3 * 46 + headerEntry.name.size() + offsetsEntry.name.size() + positionsEntry.name.size();
    if (archive > kMaxZip32)
        throw InputError(source, positionsEntry.name, "an archive below 4 GiB (at most about 357 million vertices; Zip64 is not written)",
                         std::to_string(tracts.points.size()) + " vertices, " + std::to_string(archive) + " bytes");

    // The CRC must precede the data in the local header, so the positions are converted twice: once for it,
    // once to write, rather than held whole (a million streamlines are ~800 MB).
    constexpr std::size_t kChunkPoints = 1 << 16;
    forEachPositionChunk(tracts.points, kChunkPoints, [&](std::span<const std::uint8_t> part) { positionsEntry.crc = crcOf(positionsEntry.crc, part); });

    AtomicFileWriter file(path);
    file.write(localHeader(headerEntry));
    file.write({reinterpret_cast<const std::uint8_t*>(header.data()), header.size()});
    file.write(localHeader(offsetsEntry));
    file.write(offsets);
    file.write(localHeader(positionsEntry));
    forEachPositionChunk(tracts.points, kChunkPoints, [&](std::span<const std::uint8_t> part) { file.write(part); });

    const std::uint64_t directoryOffset = file.size();
    std::vector<std::uint8_t> directory;
    for (const Entry* e : {&headerEntry, &offsetsEntry, &positionsEntry}) {
        appendLittle(directory, kCentralSignature);
        appendLittle(directory, kVersionMadeBy);
        appendCommon(directory, *e);
        appendLittle(directory, std::uint16_t{0});  // comment length
        appendLittle(directory, std::uint16_t{0});  // disk number
        appendLittle(directory, std::uint16_t{0});  // internal attributes
        appendLittle(directory, kUnixMode);
        appendLittle(directory, static_cast<std::uint32_t>(e->localOffset));
        directory.insert(directory.end(), e->name.begin(), e->name.end());
    }
    const std::uint64_t directorySize = directory.size();
    appendLittle(directory, kEndSignature);
    appendLittle(directory, std::uint16_t{0});  // this disk
    appendLittle(directory, std::uint16_t{0});  // the directory's disk
    appendLittle(directory, std::uint16_t{3});  // entries on this disk
    appendLittle(directory, std::uint16_t{3});  // entries in all
    appendLittle(directory, static_cast<std::uint32_t>(directorySize));
    appendLittle(directory, static_cast<std::uint32_t>(directoryOffset));
    appendLittle(directory, std::uint16_t{0});  // comment length
    file.write(directory);
    file.commit();
}

}  // namespace curette::io
