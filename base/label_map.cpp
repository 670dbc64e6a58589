#include "base/label_map.h"

#include "base/error.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

namespace curette {

namespace {

constexpr double kIntegerTolerance = 1e-3;
constexpr int kNotALabel = -1;

// The id of a physical value, or kNotALabel when it is not an integer in 0..65535 (within the tolerance).
int labelOf(double value) {
    if (!std::isfinite(value)) return kNotALabel;
    double rounded = std::round(value);
    if (std::abs(value - rounded) > kIntegerTolerance || rounded < 0.0 || rounded > 65535.0) return kNotALabel;
    return static_cast<int>(rounded);
}

[[noreturn]] void refuseVoxel(const VolumeData& volume, std::size_t index) {
    std::size_t nx = static_cast<std::size_t>(volume.dims.x), ny = static_cast<std::size_t>(volume.dims.y);
    std::size_t i = index % nx, j = (index / nx) % ny, k = index / (nx * ny);
    char value[32];
    std::snprintf(value, sizeof value, "%.10g", volume.valueScale * volume.normalized(index) + volume.valueOffset);
    throw InputError(volume.source, "voxel (" + std::to_string(i) + ", " + std::to_string(j) + ", " + std::to_string(k) + ")",
                     "integer label ids 0..65535", value);
}

bool equalIgnoringCase(std::string_view a, std::string_view b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (std::tolower(static_cast<unsigned char>(a[i])) != std::tolower(static_cast<unsigned char>(b[i]))) return false;
    return true;
}

}  // namespace

const LabelEntry* LabelTable::find(int id) const {
    for (const LabelEntry& e : entries)
        if (e.id == id) return &e;
    return nullptr;
}

const LabelEntry* LabelTable::findName(std::string_view name) const {
    for (const LabelEntry& e : entries)
        if (equalIgnoringCase(e.name, name)) return &e;
    return nullptr;
}

LabelMap labelMapFromVolume(const VolumeData& volume) {
    LabelMap map;
    map.dims = volume.dims;
    map.indexToWorld = volume.indexToWorld;
    map.source = volume.source;
    const std::size_t n = volume.voxelCount();
    map.ids.resize(n);
    if (volume.format == StorageFormat::Float32) {
        for (std::size_t index = 0; index < n; ++index) {
            if (volume.isNoData(index)) {
                map.ids[index] = 0;
                continue;
            }
            int label = labelOf(volume.valueScale * volume.normalized(index) + volume.valueOffset);
            if (label == kNotALabel) refuseVoxel(volume, index);
            map.ids[index] = static_cast<std::uint16_t>(label);
        }
        return map;
    }
    // UNorm8/UNorm16: one table from stored value to id, the same expression as VolumeData::value.
    const bool eightBit = volume.format == StorageFormat::UNorm8;
    const std::size_t levels = eightBit ? 256 : 65536;
    const double denominator = eightBit ? 255.0 : 65535.0;
    std::vector<int> labelOfStored(levels);
    for (std::size_t s = 0; s < levels; ++s)
        labelOfStored[s] = labelOf(volume.valueScale * (static_cast<double>(s) / denominator) + volume.valueOffset);
    const std::uint8_t* bytes = volume.voxels.data();
    for (std::size_t index = 0; index < n; ++index) {
        std::size_t stored = bytes[index];
        if (!eightBit) {
            std::uint16_t sample;  // native endian, as VolumeData stores it
            std::memcpy(&sample, bytes + 2 * index, 2);
            stored = sample;
        }
        int label = labelOfStored[stored];
        if (label == kNotALabel) refuseVoxel(volume, index);
        map.ids[index] = static_cast<std::uint16_t>(label);
    }
    return map;
}

LabelMap resampleNearest(const LabelMap& source, glm::ivec3 dims, const glm::dmat4& indexToWorld) {
    LabelMap out;
    out.dims = dims;
    out.indexToWorld = indexToWorld;
    out.source = source.source;
    out.ids.assign(out.voxelCount(), 0);
    if (source.voxelCount() == 0 || out.ids.empty()) return out;
    // Target index -> source index, one affine; per row only the start point is computed from (j, k), and
    // along i the point moves by the first column.
    const glm::dmat4 targetToSource = glm::inverse(source.indexToWorld) * indexToWorld;
    const glm::dvec3 stepI(targetToSource[0]), stepJ(targetToSource[1]), stepK(targetToSource[2]), origin(targetToSource[3]);
    const long sx = source.dims.x, sy = source.dims.y, sz = source.dims.z;
    const std::uint16_t* from = source.ids.data();
    std::uint16_t* to = out.ids.data();
    for (int k = 0; k < dims.z; ++k)
        for (int j = 0; j < dims.y; ++j) {
            // +0.5 so that floor() rounds to the nearest voxel centre.
            const glm::dvec3 rowStart = origin + static_cast<double>(j) * stepJ + static_cast<double>(k) * stepK + glm::dvec3(0.5);
            std::uint16_t* row = to + out.linearIndex(0, j, k);
            for (int i = 0; i < dims.x; ++i) {
                const glm::dvec3 p = rowStart + static_cast<double>(i) * stepI;
                const double fx = std::floor(p.x), fy = std::floor(p.y), fz = std::floor(p.z);
                // Compared as doubles first, so points far outside never overflow the conversion.
                if (fx < 0.0 || fy < 0.0 || fz < 0.0 || fx >= static_cast<double>(sx) || fy >= static_cast<double>(sy) ||
                    fz >= static_cast<double>(sz))
                    continue;
                const long x = static_cast<long>(fx), y = static_cast<long>(fy), z = static_cast<long>(fz);
                row[i] = from[static_cast<std::size_t>((z * sy + y) * sx + x)];
            }
        }
    return out;
}

}  // namespace curette
