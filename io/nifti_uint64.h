#pragma once
// 64-bit unsigned volumes as NIfTI-1 single files (datatype 1280, DT_UINT64 in nifti1.h; bitpix 64): what the
// drilled removal is saved as (session/removal_file.h), one word of sub-cell bits per voxel, so it reads back
// bit for bit. Written with the header of io/nifti_writer.h (intent 0, sform and qform from the affine),
// little-endian, gzip-compressed when the name ends in `.gz`. The reader takes exactly that layout: NIfTI-1
// "n+1", either endianness, dim[0] 3, datatype 1280, scl_slope 0 or 1 with scl_inter 0, sform_code > 0 (the
// affine is the srow rows, float32 as stored).

#include <glm/glm.hpp>

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace curette::io {

struct Uint64Volume {
    glm::ivec3 dims{0};
    glm::dmat4 indexToWorld{1.0};
    std::vector<std::uint64_t> values;   // x fastest
};

// Atomic (base/atomic_file.h): no partial file remains on failure.
void writeNiftiUint64(const std::filesystem::path& path, const Uint64Volume& volume, const std::string& description);
// Throws InputError naming the file and the field (datatype, dim, sform_code, ...) on anything else.
Uint64Volume readNiftiUint64(const std::filesystem::path& path);
Uint64Volume readNiftiUint64Bytes(std::span<const std::uint8_t> bytes, const std::string& source);

}  // namespace curette::io
