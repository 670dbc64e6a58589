#pragma once
// A scalar volume as it lives in memory and on the GPU: voxels in a compact storage format, the map from the
// stored texel value to the physical value, and the voxel-index-to-world affine (DESIGN.md "Coordinates").

#include <glm/glm.hpp>

#include <cstdint>
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
    double minValue = 0.0, maxValue = 0.0;  // physical value range over all voxels
    std::string source;                     // file it came from, for messages
    int volumeCount = 1;                    // 3-D volumes in the file (4-D/5-D NIfTI); this is volumeIndex
    int volumeIndex = 0;
    std::uint64_t noDataVoxels = 0;         // voxels that were NaN or Inf in the file ("no data": transparent)
    std::string description;                // what the reader knows beyond the grid (DICOM: modality, series), one line

    std::size_t voxelCount() const {
        return static_cast<std::size_t>(dims.x) * static_cast<std::size_t>(dims.y) * static_cast<std::size_t>(dims.z);
    }
    std::size_t linearIndex(int i, int j, int k) const {
        return (static_cast<std::size_t>(k) * static_cast<std::size_t>(dims.y) + static_cast<std::size_t>(j)) *
                   static_cast<std::size_t>(dims.x) + static_cast<std::size_t>(i);
    }
    // Texel value as the GPU sees it (before valueScale/valueOffset).
    double normalized(std::size_t index) const;
    // Physical value of one voxel.
    double value(int i, int j, int k) const { return valueScale * normalized(linearIndex(i, j, k)) + valueOffset; }
    // Length of each index axis in millimetres (column norms of the affine).
    glm::dvec3 spacing() const;
    // Recomputes minValue/maxValue from the voxels.
    void updateRange();
};

// Builds VolumeData from raw samples of any ScalarType: picks the storage format (uint8 -> UNorm8, int16 and
// uint16 -> UNorm16 with an offset for int16, int32/float32/float64 -> Float32), swaps bytes when the data's
// endianness differs from the machine's, folds slope/intercept into valueScale/valueOffset, and fills the
// range. Throws InputError(source, "data", "finite values", ...) for NaN or Inf in float data.
VolumeData buildVolume(const std::string& source, glm::ivec3 dims, ScalarType type, const std::uint8_t* samples,
                       bool bigEndian, double slope, double intercept, const glm::dmat4& indexToWorld);

std::size_t scalarTypeSize(ScalarType type);

}  // namespace curette
