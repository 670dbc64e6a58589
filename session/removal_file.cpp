#include "session/removal_file.h"

#include "base/error.h"
#include "io/nifti_uint64.h"
#include "base/sha256.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace curette {

namespace {

std::string dimsText(glm::ivec3 d) { return std::to_string(d.x) + " x " + std::to_string(d.y) + " x " + std::to_string(d.z); }

// NIfTI-1 stores the srow rows as float32: the scan's affine matches when each coefficient is within float
// rounding of the file's.
bool sameAffine(const glm::dmat4& file, const glm::dmat4& scan) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 3; ++r)
            if (std::abs(file[c][r] - scan[c][r]) > 1e-5 * std::max(1.0, std::abs(scan[c][r]))) return false;
    return true;
}

}  // namespace

std::filesystem::path removalFileBeside(const std::filesystem::path& owner) {
    return owner.parent_path() / (owner.stem().string() + ".removal.nii.gz");
}

void writeRemovalFile(const std::filesystem::path& path, const plan::RemovalVolume& removal) {
    // Plane by plane from the sparse removal: 64 bytes a voxel would be 455 MB for a 1 mm head uncompressed.
    const glm::ivec3 dims = removal.dims();
    const plan::VoxelBox box = removal.drilledBox();
    io::writeNiftiUint64(path, dims, removal.indexToWorld(), plan::kRemovalWordsPerVoxel, "curette drilled removal: 8x8x8 bits",
                         [&](int w, int z, std::span<std::uint64_t> out) {
                             if (z < box.origin.z || z >= box.origin.z + box.size.z) return;
                             for (int y = box.origin.y; y < box.origin.y + box.size.y; ++y)
                                 for (int x = box.origin.x; x < box.origin.x + box.size.x; ++x)
                                     out[static_cast<std::size_t>(y) * dims.x + x] = removal.mask({x, y, z})[static_cast<std::size_t>(w)];
                         });
}

namespace {

// A word of 4 x 4 x 4 sub-cell bits (bit i + 4 j + 16 k) as the 8 x 8 x 8 mask of the same region.
plan::VoxelMask fromFourPerAxis(std::uint64_t word) {
    static_assert(plan::kRemovalCellsPerAxis == 8);
    plan::VoxelMask m{};
    for (int k = 0; k < 4; ++k)
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i)
                if ((word >> ((k * 4 + j) * 4 + i)) & 1u)
                    for (int c = 0; c < 8; ++c)
                        m[static_cast<std::size_t>(2 * k + (c >> 2))] |= std::uint64_t(1) << ((2 * j + ((c >> 1) & 1)) * 8 + 2 * i + (c & 1));
    return m;
}

}  // namespace

std::shared_ptr<plan::RemovalVolume> readRemovalFile(const std::filesystem::path& path, glm::ivec3 dims, const glm::dmat4& indexToWorld,
                                                     const std::string& referrer, const std::string& key, std::string* fileDigest) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw InputError(referrer, key, "a removal file (NIfTI-1, datatype 1280) that exists", "\"" + path.string() + "\": no such file");
    // Plane by plane into the sparse bricks: only the compressed file, one plane and the drilled bricks are in
    // memory (the dense words are 64 bytes a voxel).
    io::NiftiUint64Reader reader(path);
    if (reader.dims() != dims) throw InputError(path.string(), "dim", dimsText(dims) + " (the scan's grid)", dimsText(reader.dims()));
    if (!sameAffine(reader.indexToWorld(), indexToWorld)) throw InputError(path.string(), "srow_x/y/z", "the scan's index-to-world affine (RAS mm)", "another grid");
    const bool fourPerAxis = reader.words() == 1;
    if (!fourPerAxis && reader.words() != plan::kRemovalWordsPerVoxel)
        throw InputError(path.string(), "dim[4]", std::to_string(plan::kRemovalWordsPerVoxel) + " words per voxel (8 x 8 x 8 sub-cells; or a 3-D file of 4 x 4 x 4)",
                         std::to_string(reader.words()));
    auto removal = std::make_shared<plan::RemovalVolume>(dims, indexToWorld);
    plan::BrickMaskMap bricks;
    std::vector<std::array<std::uint64_t, 2>> oldRecords;   // a 4 x 4 x 4 file's words as version 6 digested them: index and word
    std::vector<std::uint64_t> plane(static_cast<std::size_t>(dims.x) * static_cast<std::size_t>(dims.y));
    int word = 0, z = 0;
    while (reader.next(word, z, plane))
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x) {
                std::uint64_t value = plane[static_cast<std::size_t>(y) * dims.x + x];
                if (value == 0) continue;
                glm::ivec3 p(x, y, z), inside = p % plan::kRemovalBrickSize;
                std::uint32_t brick = removal->brickNumber(p / plan::kRemovalBrickSize);
                std::size_t inBrick = static_cast<std::size_t>((inside.z * plan::kRemovalBrickSize + inside.y) * plan::kRemovalBrickSize + inside.x);
                auto [at, added] = bricks.try_emplace(brick);
                if (added) at->second.fill(plan::VoxelMask{});
                if (fourPerAxis) {
                    at->second[inBrick] = fromFourPerAxis(value);
                    oldRecords.push_back({std::uint64_t(brick) * plan::kRemovalBrickVoxels + inBrick, value});
                } else {
                    at->second[inBrick][static_cast<std::size_t>(word)] = value;
                }
            }
    // Version 6 digested brick by brick, x fastest inside a brick: the records' index order.
    std::sort(oldRecords.begin(), oldRecords.end());
    Sha256 oldDigest;
    for (const auto& record : oldRecords) oldDigest.update(std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(record.data()), sizeof record));
    removal->setBricks(bricks);
    if (fileDigest) *fileDigest = fourPerAxis ? oldDigest.hexDigest() : removal->digest();
    return removal;
}

std::shared_ptr<const plan::RemovalVolume> sessionStartRemoval(const Session& session, const LoadedScene& loaded) {
    if (session.header.version < kDrillFromInputVersion) return loaded.removal;
    if (session.header.removal.empty()) return nullptr;
    std::filesystem::path path = session.header.removal;
    if (path.is_relative()) path = session.file.parent_path() / path;
    std::string where = session.file.string();
    std::string digest;
    std::shared_ptr<plan::RemovalVolume> removal =
        readRemovalFile(path, loaded.volume.dims, loaded.volume.indexToWorld, where, "line 1: removal.file", &digest);
    if (digest != session.header.removalDigest)
        throw InputError(path.string(), "voxels", "the removal the session started from (digest " + session.header.removalDigest + ")",
                         "another one (digest " + digest + ")");
    return removal;
}

}  // namespace curette
