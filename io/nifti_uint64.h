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
#include <memory>
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
// Reads such a file plane by plane, word slowest then z, so only the file as stored (compressed) and one plane
// are in memory. The constructor reads and checks the header: it throws InputError naming the file and the
// field (datatype, dim, sform_code, ...) on anything else, and names vox_offset when the file cannot hold the
// voxels its header claims (a gzip member inflates at most 1032-fold, so a small file cannot claim gigabytes).
class NiftiUint64Reader {
public:
    explicit NiftiUint64Reader(const std::filesystem::path& path);
    NiftiUint64Reader(std::span<const std::uint8_t> bytes, std::string source);   // the file's bytes, kept by the caller
    ~NiftiUint64Reader();
    glm::ivec3 dims() const { return dims_; }
    const glm::dmat4& indexToWorld() const { return indexToWorld_; }
    int words() const { return words_; }
    // The next plane into `out` (dims.x * dims.y values, x fastest) and which it is; false after the last.
    // Throws InputError(vox_offset) when the file ends first.
    bool next(int& word, int& z, std::span<std::uint64_t> out);

private:
    void open(std::span<const std::uint8_t> stored);
    void readExactly(std::span<std::uint8_t> out);
    [[noreturn]] void voxelsMissing(const std::string& found) const;
    std::string source_;
    std::vector<std::uint8_t> stored_;   // the file as read from disk (compressed or not)
    std::span<const std::uint8_t> plain_;   // an uncompressed file: its bytes
    std::size_t cursor_ = 0;
    std::unique_ptr<class Inflater> inflater_;
    glm::ivec3 dims_{0};
    glm::dmat4 indexToWorld_{1.0};
    int words_ = 1;
    std::uint64_t voxelBytes_ = 0;   // what the header claims after vox_offset
    bool swap_ = false;
    int nextWord_ = 0, nextZ_ = 0;
    std::vector<std::uint8_t> buffer_;
};

// The whole volume (through NiftiUint64Reader).
Uint64Volume readNiftiUint64(const std::filesystem::path& path);
Uint64Volume readNiftiUint64Bytes(std::span<const std::uint8_t> bytes, const std::string& source);

}  // namespace curette::io
