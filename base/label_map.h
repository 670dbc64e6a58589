#pragma once
// Label volumes beside the scan ("the carve becomes a plan"): a grid of integer label ids (0 = no label) with
// the same index-to-world convention as VolumeData (centre of voxel (i,j,k) -> world RAS millimetres), and the
// table that names and colours the ids. Readers of label tables live in io/label_table.h; the formats are
// described in io/label_table.h (colour tables). Ids are 16-bit: NIfTI uint8/uint16 label files,
// Slicer's uchar/ushort segmentations and the mricron atlases (AAL 116 labels, AICHA 192) all fit.

#include "base/volume.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace curette {

struct LabelEntry {
    int id = 0;
    std::string name;
    glm::dvec4 rgba{0.0, 0.0, 0.0, 1.0};  // each in 0..1
};

struct LabelTable {
    std::vector<LabelEntry> entries;  // in file order
    std::string source;               // file it came from, for messages

    // The entry with this id, or nullptr.
    const LabelEntry* find(int id) const;
    // The entry whose name equals `name` ignoring ASCII case (exact otherwise: no trimming, no '_' = ' '), or nullptr.
    const LabelEntry* findName(std::string_view name) const;
};

struct LabelMap {
    glm::ivec3 dims{0};            // voxels along i, j, k; i varies fastest in `ids`
    glm::dmat4 indexToWorld{1.0};  // centre of voxel (i,j,k) -> world millimetres (RAS), as VolumeData
    std::vector<std::uint16_t> ids;
    std::string source;            // file it came from, for messages

    std::size_t voxelCount() const {
        return static_cast<std::size_t>(dims.x) * static_cast<std::size_t>(dims.y) * static_cast<std::size_t>(dims.z);
    }
    std::size_t linearIndex(int i, int j, int k) const {
        return (static_cast<std::size_t>(k) * static_cast<std::size_t>(dims.y) + static_cast<std::size_t>(j)) *
                   static_cast<std::size_t>(dims.x) + static_cast<std::size_t>(i);
    }
    std::uint16_t id(int i, int j, int k) const { return ids[linearIndex(i, j, k)]; }
};

// The label ids of a volume read by io::readVolume. Every voxel's physical value (VolumeData::value) must be
// an integer in [0, 65535] within 1e-3, else InputError(volume.source, "voxel (i, j, k)", "integer label ids
// 0..65535", the value). Voxels without data (NaN/Inf in the file) become 0.
LabelMap labelMapFromVolume(const VolumeData& volume);

// `source` on another grid (dims, indexToWorld): each target voxel centre is mapped through the two affines
// into source index space and takes the label of the nearest source voxel centre (round half up per axis);
// centres that fall outside the source grid (beyond half a voxel past its edge voxels) get 0. Ids are never
// interpolated. The result's source is `source.source`.
LabelMap resampleNearest(const LabelMap& source, glm::ivec3 dims, const glm::dmat4& indexToWorld);

}  // namespace curette
