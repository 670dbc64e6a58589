#include "io/tck_writer.h"

#include "base/atomic_file.h"
#include "base/error.h"
#include "io/tract_writing.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

namespace curette::io {

namespace {

void appendFloat(std::vector<std::uint8_t>& bytes, float value) {
    std::uint8_t raw[4];
    std::memcpy(raw, &value, 4);
    if constexpr (std::endian::native == std::endian::big) std::reverse(raw, raw + 4);
    bytes.insert(bytes.end(), raw, raw + 4);
}

void appendTriplet(std::vector<std::uint8_t>& bytes, float x, float y, float z) {
    appendFloat(bytes, x), appendFloat(bytes, y), appendFloat(bytes, z);
}

// The header with `file: . OFFSET` naming its own length: the digits of OFFSET count, so grow until it is stable.
std::string headerText(std::size_t count) {
    const std::string before = "mrtrix tracks\ncount: " + std::to_string(count) + "\ndatatype: Float32LE\nfile: . ";
    const std::string after = "\nEND\n";
    std::size_t offset = before.size() + after.size();
    while (true) {
        std::string text = before + std::to_string(offset) + after;
        if (text.size() == offset) return text;
        offset = text.size();
    }
}

}  // namespace

void writeTck(const std::filesystem::path& path, const Tractogram& tracts) {
    const std::string source = path.string();
    requireWritableTractogram(source, tracts);
    std::size_t written = 0;
    for (std::size_t s = 0; s < tracts.streamlineCount(); ++s) written += tracts.pointCount(s) > 0;
    const std::string header = headerText(written);
    std::vector<std::uint8_t> bytes(header.begin(), header.end());
    bytes.reserve(header.size() + 12 * (tracts.points.size() + written + 1));
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    for (std::size_t s = 0; s < tracts.streamlineCount(); ++s) {
        if (tracts.pointCount(s) == 0) continue;
        for (std::uint32_t p = tracts.offsets[s]; p < tracts.offsets[s + 1]; ++p) {
            const glm::vec3& v = tracts.points[p];
            appendTriplet(bytes, v.x, v.y, v.z);
        }
        appendTriplet(bytes, nan, nan, nan);
    }
    appendTriplet(bytes, inf, inf, inf);
    writeFileAtomically(path, bytes);
}

}  // namespace curette::io
