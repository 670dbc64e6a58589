#include "io/trk_writer.h"

#include "base/atomic_file.h"
#include "base/error.h"
#include "io/tract_writing.h"

#include <cstring>
#include <limits>

namespace curette::io {

namespace {

constexpr std::size_t kHeaderBytes = 1000;
constexpr std::size_t kMaxNames = 10, kNameBytes = 20;

// Little-endian at a fixed place in the header.
template <typename T>
void storeLittle(std::uint8_t* p, T value) {
    std::vector<std::uint8_t> raw;
    appendLittle(raw, value);
    std::memcpy(p, raw.data(), sizeof(T));
}

void requireNames(const std::string& source, const char* field, const std::vector<std::string>& names) {
    if (names.size() > kMaxNames)
        throw InputError(source, field, "at most 10 names (the .trk header has room for 10)", std::to_string(names.size()));
    for (std::size_t i = 0; i < names.size(); ++i)
        if (names[i].size() > kNameBytes || names[i].find('\0') != std::string::npos)
            throw InputError(source, std::string(field) + "[" + std::to_string(i) + "]", "a name of at most 20 bytes without NUL",
                             "\"" + names[i] + "\"");
}

void putNames(std::uint8_t* at, const std::vector<std::string>& names) {
    for (std::size_t i = 0; i < names.size(); ++i) std::memcpy(at + kNameBytes * i, names[i].data(), names[i].size());
}

}  // namespace

void writeTrk(const std::filesystem::path& path, const Tractogram& tracts) {
    const std::string source = path.string();
    requireWritableTractogram(source, tracts);
    requireNames(source, "scalarNames", tracts.scalarNames);
    requireNames(source, "propertyNames", tracts.propertyNames);
    const std::size_t nScalars = tracts.scalarNames.size(), nProperties = tracts.propertyNames.size();
    if (tracts.scalars.size() != tracts.points.size() * nScalars)
        throw InputError(source, "scalars", std::to_string(nScalars) + " per point (" + std::to_string(tracts.points.size() * nScalars) + ")",
                         std::to_string(tracts.scalars.size()));
    if (tracts.properties.size() != tracts.streamlineCount() * nProperties)
        throw InputError(source, "properties",
                         std::to_string(nProperties) + " per streamline (" + std::to_string(tracts.streamlineCount() * nProperties) + ")",
                         std::to_string(tracts.properties.size()));
    // Empty streamlines are left out: nibabel drops them when it reads (a file whose n_count counted them would
    // disagree with what it returns), and TrackVis draws nothing for them.
    std::size_t written = 0;
    for (std::size_t s = 0; s < tracts.streamlineCount(); ++s) written += tracts.pointCount(s) > 0;
    constexpr std::size_t kMaxInt32 = static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max());
    if (written > kMaxInt32) throw InputError(source, "n_count", "at most 2^31 - 1 streamlines (an int32)", std::to_string(written));
    if (tracts.points.size() > kMaxInt32)  // bounds every streamline's int32 point count
        throw InputError(source, "n_points", "at most 2^31 - 1 points (an int32)", std::to_string(tracts.points.size()));

    const TractReferenceGrid grid = tractReferenceGrid(tracts);
    const glm::dmat4 voxToRas = grid.voxelToRas();
    glm::dmat4 offset(1.0), scale(1.0);
    offset[3] = glm::dvec4(-0.5, -0.5, -0.5, 1.0);
    for (int a = 0; a < 3; ++a) scale[a][a] = 1.0 / grid.voxelSize;
    const glm::dmat4 worldToVoxmm = glm::inverse(voxToRas * offset * scale);

    std::vector<std::uint8_t> bytes(kHeaderBytes, 0);
    std::uint8_t* h = bytes.data();
    std::memcpy(h, "TRACK", 5);
    for (int a = 0; a < 3; ++a) {
        storeLittle(h + 6 + 2 * a, static_cast<std::int16_t>(grid.dims[a]));
        storeLittle(h + 12 + 4 * a, static_cast<float>(grid.voxelSize));
    }
    storeLittle(h + 36, static_cast<std::int16_t>(nScalars));
    putNames(h + 38, tracts.scalarNames);
    storeLittle(h + 238, static_cast<std::int16_t>(nProperties));
    putNames(h + 240, tracts.propertyNames);
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col) storeLittle(h + 440 + 4 * (4 * row + col), static_cast<float>(voxToRas[col][row]));
    std::memcpy(h + 948, "RAS", 3);
    storeLittle(h + 988, static_cast<std::int32_t>(written));
    storeLittle(h + 992, std::int32_t{2});
    storeLittle(h + 996, static_cast<std::int32_t>(kHeaderBytes));

    // Streamed in parts of about 1 MiB: a million streamlines are ~800 MB of points.
    constexpr std::size_t kChunk = 1 << 20;
    AtomicFileWriter file(path);
    bytes.reserve(kChunk + 1024);
    for (std::size_t s = 0; s < tracts.streamlineCount(); ++s) {
        if (tracts.pointCount(s) == 0) continue;
        appendLittle(bytes, static_cast<std::int32_t>(tracts.pointCount(s)));
        for (std::uint32_t p = tracts.offsets[s]; p < tracts.offsets[s + 1]; ++p) {
            glm::dvec4 voxmm = worldToVoxmm * glm::dvec4(glm::dvec3(tracts.points[p]), 1.0);
            for (int a = 0; a < 3; ++a) appendLittle(bytes, static_cast<float>(voxmm[a]));
            for (std::size_t k = 0; k < nScalars; ++k) appendLittle(bytes, tracts.scalars[p * nScalars + k]);
        }
        for (std::size_t k = 0; k < nProperties; ++k) appendLittle(bytes, tracts.properties[s * nProperties + k]);
        if (bytes.size() >= kChunk) file.write(bytes), bytes.clear();
    }
    file.write(bytes);
    file.commit();
}

}  // namespace curette::io
