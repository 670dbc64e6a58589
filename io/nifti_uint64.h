#pragma once
// 64-bit unsigned volumes as NIfTI-1 single files (datatype 1280, DT_UINT64 in nifti1.h; bitpix 64): what the
// drilled removal is saved as (session/removal_file.h), words of sub-cell bits per voxel, so it reads back
// bit for bit. One word per voxel is a 3-D file; more (`words`) a 4-D one, dim[4] = words, the fourth index
// slowest (word w of every voxel, then w + 1). Written with the header of io/nifti_writer.h (intent 0, sform
// and qform from the affine), little-endian, gzip-compressed when the name ends in `.gz`. The reader takes
// exactly that layout: NIfTI-1 "n+1", either endianness, dim[0] 3 or 4, datatype 1280, scl_slope 0 or 1 with
// scl_inter 0, sform_code > 0 (the affine is the srow rows, float32 as stored).

#include <glm/glm.hpp>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace curette::io {

inline constexpr int kMaxNiftiUint64Words = 64;

struct Uint64Volume {
    glm::ivec3 dims{0};
    glm::dmat4 indexToWorld{1.0};
    int words = 1;                       // per voxel (dim[4] of a 4-D file; at most kMaxNiftiUint64Words)
    std::vector<std::uint64_t> values;   // x fastest, the word slowest
};

// Atomic (base/atomic_file.h): no partial file remains on failure.
void writeNiftiUint64(const std::filesystem::path& path, const Uint64Volume& volume, const std::string& description);
// The same file from its planes, so a large sparse volume is never whole in memory (a `.gz` file only in its
// compressed form): plane(word, z, out) fills word `word` of every voxel of plane z, x fastest (dims.x * dims.y).
using Uint64Planes = std::function<void(int word, int z, std::span<std::uint64_t> out)>;
void writeNiftiUint64(const std::filesystem::path& path, glm::ivec3 dims, const glm::dmat4& indexToWorld, int words,
                      const std::string& description, const Uint64Planes& plane);
// Throws InputError naming the file and the field (datatype, dim, sform_code, ...) on anything else.
Uint64Volume readNiftiUint64(const std::filesystem::path& path);
Uint64Volume readNiftiUint64Bytes(std::span<const std::uint8_t> bytes, const std::string& source);

}  // namespace curette::io
