#pragma once
// A scalar volume as it lives in memory and on the GPU: voxels in a compact storage format, the map from the
// stored texel value to the physical value, and the voxel-index-to-world affine (to RAS millimetres).

#include <glm/glm.hpp>

#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

namespace curette {

// The voxel type a file declared, kept for `curette info`.
enum class ScalarType : std::uint8_t { UInt8, Int16, UInt16, Int32, Float32, Float64 };
const char* scalarTypeName(ScalarType type);

// How voxels are held. The GPU texture has the same format (R8, R16, R32F), so a texel fetch returns
// `normalized` = stored / 255 or / 65535 for the UNorm formats and the value itself for Float32.
enum class StorageFormat : std::uint8_t { UNorm8, UNorm16, Float32 };
std::size_t bytesPerVoxel(StorageFormat format);

struct VolumeData {
    glm::ivec3 dims{0};                // voxels along i, j, k; i varies fastest in `voxels`
    glm::dmat4 indexToWorld{1.0};      // centre of voxel (i,j,k) -> world millimetres (RAS)
    StorageFormat format = StorageFormat::UNorm8;
    std::vector<std::uint8_t> voxels;  // dims.x*dims.y*dims.z elements of bytesPerVoxel(format), native endian
    // physical value = valueScale * normalized + valueOffset (NIfTI scl_slope/scl_inter folded in).
    double valueScale = 1.0;
    double valueOffset = 0.0;
    ScalarType sourceType = ScalarType::UInt8;
    double minValue = 0.0, maxValue = 0.0;  // physical value range over all voxels that have data
    std::string source;                     // file it came from, for messages
    // Every file the voxels and geometry were read from (one; a header and its data file; a DICOM series'
    // files in slice order): what a report's checksums cover. Set by io::readVolume.
    std::vector<std::filesystem::path> files;
    int volumeCount = 1;                    // 3-D volumes in the file (4-D/5-D NIfTI); this is volumeIndex
    int volumeIndex = 0;
    std::uint64_t noDataVoxels = 0;         // voxels that were NaN or Inf in the file ("no data": transparent)
    float noDataTexel = 0.0f;               // what those voxels store (Float32 only; see noDataTexelBelow)
    std::string description;                // what the reader knows beyond the grid (DICOM: modality, series), one line

    std::size_t voxelCount() const {
        return static_cast<std::size_t>(dims.x) * static_cast<std::size_t>(dims.y) * static_cast<std::size_t>(dims.z);
    }
    std::size_t linearIndex(int i, int j, int k) const {
        return (static_cast<std::size_t>(k) * static_cast<std::size_t>(dims.y) + static_cast<std::size_t>(j)) *
                   static_cast<std::size_t>(dims.x) + static_cast<std::size_t>(i);
    }
    // Texel value as the GPU sees it (before valueScale/valueOffset); noDataTexel for a voxel without data.
    double normalized(std::size_t index) const;
    // Whether a voxel was NaN or Inf in the file.
    bool isNoData(std::size_t index) const;
    // Physical value of one voxel; NaN for a voxel without data.
    double value(int i, int j, int k) const;
    // Length of each index axis in millimetres (column norms of the affine).
    glm::dvec3 spacing() const;
    // Recomputes minValue/maxValue from the voxels that have data.
    void updateRange();
};

// "No data" (NaN and Inf voxels) without a branch on the GPU: such voxels store one texel value whose
// physical value lies far below every finite one, and the transfer-function table is transparent from three
// domain widths below its first point down (render/transfer_function_texture.h). Given the finite texel range
// [lo, hi] and the texel -> physical map, returns that stored value: physical  min - F * B, where
// B = |min| + |max| + (max - min) + 1 and F = 2^30 (less when F * B would pass 1e18, so gradients squared
// stay finite in float). It is transparent under every TF whose first point d0 >= min - F * B / 2 and whose
// width is at most F * B / 6.
// Interpolation at the boundary: a sample whose eight texels give weight w to no-data voxels is moved down by
// w * F * B. For w >= 2^-24 that is at least 64 B, below the transparent start for any TF within the data's
// magnitude: a sample that touches a voxel without data is transparent, as if NaN propagated through the
// interpolation, and the data end at the cells whose eight corners all have data. A smaller non-zero w needs
// one axis weight below 2^-8, i.e. a sample within 1/256 voxel of the plane of the finite corners; GPUs that
// quantise weights to 8 bits never produce one, full-float filtering (llvmpipe) can, in that sliver, where the
// sample is classified somewhere between its finite value and transparent.
float noDataTexelBelow(double lo, double hi, double valueScale, double valueOffset);

// Which samples of a volume (stored values, filtered or not) are "no data": those whose physical value lies
// more than B below the data's minimum (B as above). A sample of finite voxels never does; a trilinear sample
// with weight w on no-data voxels is moved down by at least w F B, so it does for every w above 2 / F, a
// wider net than the transparency above (w >= 2^-24). One comparison, so the GPU makes it too
// (shaders/no_data.glsl): the stored value times `side` (the sign of valueScale, so the comparison runs in
// the physical order) below `bound`. Nothing is no data in a volume without no-data voxels.
struct NoDataSamples {
    NoDataSamples() = default;
    explicit NoDataSamples(const VolumeData& volume);
    bool any = false;
    float side = 1.0f;
    float bound = -std::numeric_limits<float>::infinity();
    bool operator()(double texel) const { return texel * side < bound; }
};

// Builds VolumeData from raw samples of any ScalarType: picks the storage format (uint8 -> UNorm8, int16 and
// uint16 -> UNorm16 with an offset for int16, int32/float32/float64 -> Float32), swaps bytes when the data's
// endianness differs from the machine's, folds slope/intercept into valueScale/valueOffset, and fills the
// range. NaN and Inf in float data are "no data": counted in noDataVoxels, stored as noDataTexelBelow(...),
// left out of the range, and warned about once (log::warn). Throws InputError(source, "data", ...) when no
// voxel has data, or when a float64 value is finite but beyond float32.
VolumeData buildVolume(const std::string& source, glm::ivec3 dims, ScalarType type, const std::uint8_t* samples,
                       bool bigEndian, double slope, double intercept, const glm::dmat4& indexToWorld);

std::size_t scalarTypeSize(ScalarType type);

}  // namespace curette
