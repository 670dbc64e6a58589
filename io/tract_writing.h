#pragma once
// What the tract writers (tck_writer.h, trk_writer.h, trx_writer.h) share: the check that a Tractogram can be
// written, and the reference grid the formats with a voxel space (.trk, TRX) describe when curette has no
// image to name.

#include "base/tractogram.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace curette::io {

// Appends `value` little-endian (every tract format curette writes is little-endian).
template <typename T>
void appendLittle(std::vector<std::uint8_t>& bytes, T value) {
    auto raw = std::bit_cast<std::array<std::uint8_t, sizeof(T)>>(value);
    if constexpr (std::endian::native == std::endian::big) std::reverse(raw.begin(), raw.end());
    std::size_t at = bytes.size();
    bytes.resize(at + sizeof(T));
    std::memcpy(bytes.data() + at, raw.data(), sizeof(T));
}

// InputError(source, "offsets", ...) when the offsets do not describe the points, and
// InputError(source, "points[n]", ...) for the first point with a coordinate that is not finite.
void requireWritableTractogram(const std::string& source, const Tractogram& tracts);

// A grid of cubic voxels covering every point with a voxel to spare on each side, its axes along R, A, S:
// voxel (i, j, k)'s centre is at origin + voxelSize * (i, j, k). Voxels are 1 mm unless the points span more
// than .trk's int16 dimensions allow at 1 mm. An empty tractogram gets one voxel at the origin.
struct TractReferenceGrid {
    glm::ivec3 dims{1, 1, 1};
    double voxelSize = 1.0;
    glm::dvec3 origin{0.0};
    // voxel index -> world millimetres RAS (the NIfTI-style voxel-centre affine TRX's VOXEL_TO_RASMM is).
    glm::dmat4 voxelToRas() const;
};
TractReferenceGrid tractReferenceGrid(const Tractogram& tracts);

}  // namespace curette::io
