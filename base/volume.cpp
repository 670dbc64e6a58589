#include "base/volume.h"

#include "base/error.h"
#include "base/log.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

namespace curette {

const char* scalarTypeName(ScalarType type) {
    switch (type) {
        case ScalarType::UInt8: return "uint8";
        case ScalarType::Int16: return "int16";
        case ScalarType::UInt16: return "uint16";
        case ScalarType::Int32: return "int32";
        case ScalarType::Float32: return "float32";
        case ScalarType::Float64: return "float64";
    }
    return "?";
}

std::size_t scalarTypeSize(ScalarType type) {
    switch (type) {
        case ScalarType::UInt8: return 1;
        case ScalarType::Int16:
        case ScalarType::UInt16: return 2;
        case ScalarType::Int32:
        case ScalarType::Float32: return 4;
        case ScalarType::Float64: return 8;
    }
    return 0;
}

std::size_t bytesPerVoxel(StorageFormat format) {
    switch (format) {
        case StorageFormat::UNorm8: return 1;
        case StorageFormat::UNorm16: return 2;
        case StorageFormat::Float32: return 4;
    }
    return 0;
}

double VolumeData::normalized(std::size_t index) const {
    switch (format) {
        case StorageFormat::UNorm8: return voxels[index] / 255.0;
        case StorageFormat::UNorm16: {
            std::uint16_t v;
            std::memcpy(&v, voxels.data() + 2 * index, 2);
            return v / 65535.0;
        }
        case StorageFormat::Float32: {
            float v;
            std::memcpy(&v, voxels.data() + 4 * index, 4);
            return v;
        }
    }
    return 0.0;
}

bool VolumeData::isNoData(std::size_t index) const {
    if (noDataVoxels == 0 || format != StorageFormat::Float32) return false;
    float v;
    std::memcpy(&v, voxels.data() + 4 * index, 4);
    return v == noDataTexel;  // no finite voxel can equal it: it lies far outside the finite range
}

double VolumeData::value(int i, int j, int k) const {
    std::size_t index = linearIndex(i, j, k);
    if (isNoData(index)) return std::numeric_limits<double>::quiet_NaN();
    return valueScale * normalized(index) + valueOffset;
}

glm::dvec3 VolumeData::spacing() const {
    return {glm::length(glm::dvec3(indexToWorld[0])), glm::length(glm::dvec3(indexToWorld[1])),
            glm::length(glm::dvec3(indexToWorld[2]))};
}

void VolumeData::updateRange() {
    std::size_t n = voxelCount();
    if (n == 0) {
        minValue = maxValue = 0;
        return;
    }
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    if (format == StorageFormat::UNorm8) {
        std::uint8_t a = 255, b = 0;
        for (std::uint8_t v : voxels) a = std::min(a, v), b = std::max(b, v);
        lo = a / 255.0, hi = b / 255.0;
    } else {
        for (std::size_t i = 0; i < n; ++i) {
            if (isNoData(i)) continue;
            double v = normalized(i);
            lo = std::min(lo, v), hi = std::max(hi, v);
        }
        if (lo > hi) lo = hi = 0.0;  // no voxel has data
    }
    double a = valueScale * lo + valueOffset, b = valueScale * hi + valueOffset;
    minValue = std::min(a, b), maxValue = std::max(a, b);
}

namespace {
// B of noDataTexelBelow: more than the data's span and magnitude.
double noDataMagnitude(double min, double max) { return std::abs(min) + std::abs(max) + (max - min) + 1.0; }
}  // namespace

float noDataTexelBelow(double lo, double hi, double valueScale, double valueOffset) {
    double a = valueScale * lo + valueOffset, b = valueScale * hi + valueOffset;
    double min = std::min(a, b), max = std::max(a, b);
    double magnitude = noDataMagnitude(min, max);
    double factor = std::clamp(1e18 / magnitude, 1024.0, 1073741824.0);  // 2^10 .. 2^30
    double texel = (min - factor * magnitude - valueOffset) / (valueScale != 0.0 ? valueScale : 1.0);
    return static_cast<float>(std::clamp(texel, -1e30, 1e30));
}

NoDataSamples::NoDataSamples(const VolumeData& volume) {
    if (volume.noDataVoxels == 0 || volume.format != StorageFormat::Float32) return;
    any = true;
    double scale = volume.valueScale != 0.0 ? volume.valueScale : 1.0;  // as noDataTexelBelow divides
    side = scale < 0.0 ? -1.0f : 1.0f;
    double texel = (volume.minValue - noDataMagnitude(volume.minValue, volume.maxValue) - volume.valueOffset) / scale;
    bound = static_cast<float>(side * texel);
}

namespace {

template <typename T>
T load(const std::uint8_t* p, bool swap) {
    T value;
    if (!swap) {
        std::memcpy(&value, p, sizeof(T));
        return value;
    }
    std::uint8_t reversed[sizeof(T)];
    for (std::size_t b = 0; b < sizeof(T); ++b) reversed[b] = p[sizeof(T) - 1 - b];
    std::memcpy(&value, reversed, sizeof(T));
    return value;
}

}  // namespace

VolumeData buildVolume(const std::string& source, glm::ivec3 dims, ScalarType type, const std::uint8_t* samples,
                       bool bigEndian, double slope, double intercept, const glm::dmat4& indexToWorld) {
    VolumeData volume;
    volume.dims = dims;
    volume.indexToWorld = indexToWorld;
    volume.sourceType = type;
    volume.source = source;
    const bool swap = bigEndian != (std::endian::native == std::endian::big);
    const std::size_t n = volume.voxelCount();
    const std::size_t size = scalarTypeSize(type);
    switch (type) {
        case ScalarType::UInt8:
            volume.format = StorageFormat::UNorm8;
            volume.voxels.assign(samples, samples + n);
            volume.valueScale = slope * 255.0;
            volume.valueOffset = intercept;
            break;
        case ScalarType::UInt16:
        case ScalarType::Int16: {
            volume.format = StorageFormat::UNorm16;
            volume.voxels.resize(2 * n);
            const bool isSigned = type == ScalarType::Int16;
            for (std::size_t i = 0; i < n; ++i) {
                std::uint16_t raw = load<std::uint16_t>(samples + size * i, swap);
                // int16 is shifted into [0, 65535] so every value is exact in R16 UNorm.
                std::uint16_t stored = isSigned ? static_cast<std::uint16_t>(raw ^ 0x8000u) : raw;
                std::memcpy(volume.voxels.data() + 2 * i, &stored, 2);
            }
            volume.valueScale = slope * 65535.0;
            volume.valueOffset = intercept - (isSigned ? slope * 32768.0 : 0.0);
            break;
        }
        case ScalarType::Int32:
        case ScalarType::Float32:
        case ScalarType::Float64: {
            volume.format = StorageFormat::Float32;
            volume.voxels.resize(4 * n);
            // Finite values are stored as they are; NaN and Inf are "no data", stored after the pass once
            // the finite range (and so noDataTexelBelow) is known.
            float lo = std::numeric_limits<float>::infinity(), hi = -lo;
            for (std::size_t i = 0; i < n; ++i) {
                double v = type == ScalarType::Int32     ? load<std::int32_t>(samples + size * i, swap)
                           : type == ScalarType::Float32 ? load<float>(samples + size * i, swap)
                                                         : load<double>(samples + size * i, swap);
                float f = static_cast<float>(v);
                if (!std::isfinite(v)) {
                    ++volume.noDataVoxels;
                    f = std::numeric_limits<float>::quiet_NaN();
                } else if (std::isinf(f)) {
                    throw InputError(source, "data", "values within float32 range", std::to_string(v));
                } else {
                    lo = std::min(lo, f), hi = std::max(hi, f);
                }
                std::memcpy(volume.voxels.data() + 4 * i, &f, 4);
            }
            volume.valueScale = slope;
            volume.valueOffset = intercept;
            if (volume.noDataVoxels > 0) {
                if (volume.noDataVoxels == n)
                    throw InputError(source, "data", "at least one finite voxel value", "only NaN and Inf (no data anywhere)");
                volume.noDataTexel = noDataTexelBelow(lo, hi, slope, intercept);
                for (std::size_t i = 0; i < n; ++i) {
                    float f;
                    std::memcpy(&f, volume.voxels.data() + 4 * i, 4);
                    if (std::isnan(f)) std::memcpy(volume.voxels.data() + 4 * i, &volume.noDataTexel, 4);
                }
                log::warn(source + ": " + std::to_string(volume.noDataVoxels) + " of " + std::to_string(n) +
                          " voxels are NaN or Inf: no data, rendered transparent and left out of the value range");
            }
            break;
        }
    }
    volume.updateRange();
    return volume;
}

}  // namespace curette
