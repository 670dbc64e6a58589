#include "render/gpu_volume.h"

#include "base/error.h"

#include <algorithm>
#include <cstdlib>
#include <string>

namespace curette {

namespace {

VolumeTextureFormat textureFormat(StorageFormat f) {
    switch (f) {
        case StorageFormat::UNorm8: return {GL_R8, GL_RED, GL_UNSIGNED_BYTE, 1};
        case StorageFormat::UNorm16: return {GL_R16, GL_RED, GL_UNSIGNED_SHORT, 2};
        case StorageFormat::Float32: return {GL_R32F, GL_RED, GL_FLOAT, 4};
    }
    return {GL_R8, GL_RED, GL_UNSIGNED_BYTE, 1};
}

// Brick ranges with a one-voxel apron: a sample in brick b interpolates voxels b*B-1 .. (b+1)*B. One pass
// over the voxels: each voxel updates the (up to 8) bricks whose apron holds it.
std::vector<glm::vec2> brickRangesOf(const VolumeData& data, int size, glm::ivec3 grid) {
    std::vector<glm::vec2> ranges(static_cast<std::size_t>(grid.x) * static_cast<std::size_t>(grid.y) * static_cast<std::size_t>(grid.z),
                                  glm::vec2(1e30f, -1e30f));
    for (int k = 0; k < data.dims.z; ++k) {
        glm::ivec2 bzRange = GpuVolume::bricksHoldingVoxel(k, grid.z, size);
        for (int j = 0; j < data.dims.y; ++j) {
            glm::ivec2 byRange = GpuVolume::bricksHoldingVoxel(j, grid.y, size);
            std::size_t row = data.linearIndex(0, j, k);
            for (int i = 0; i < data.dims.x; ++i) {
                glm::ivec2 bxRange = GpuVolume::bricksHoldingVoxel(i, grid.x, size);
                float v = static_cast<float>(data.normalized(row + static_cast<std::size_t>(i)));
                for (int bz = bzRange.x; bz <= bzRange.y; ++bz)
                    for (int by = byRange.x; by <= byRange.y; ++by)
                        for (int bx = bxRange.x; bx <= bxRange.y; ++bx) {
                            glm::vec2& r = ranges[(static_cast<std::size_t>(bz) * static_cast<std::size_t>(grid.y) + static_cast<std::size_t>(by)) *
                                                      static_cast<std::size_t>(grid.x) +
                                                  static_cast<std::size_t>(bx)];
                            r.x = std::min(r.x, v);
                            r.y = std::max(r.y, v);
                        }
            }
        }
    }
    return ranges;
}

// The ranges of bricks `factor` times larger along each axis, from the finer ones: a coarse brick b's apron,
// voxels b*F*B-1 .. (b+1)*F*B, is the union of its children's (b*F .. b*F+F-1) aprons, so its range is the
// union of theirs, exactly (min and max), without another pass over the voxels.
std::vector<glm::vec2> coarserBrickRanges(const std::vector<glm::vec2>& fine, glm::ivec3 fineGrid, int factor, glm::ivec3 grid) {
    std::vector<glm::vec2> ranges(static_cast<std::size_t>(grid.x) * static_cast<std::size_t>(grid.y) * static_cast<std::size_t>(grid.z),
                                  glm::vec2(1e30f, -1e30f));
    for (int z = 0; z < fineGrid.z; ++z)
        for (int y = 0; y < fineGrid.y; ++y)
            for (int x = 0; x < fineGrid.x; ++x) {
                const glm::vec2& child = fine[(static_cast<std::size_t>(z) * static_cast<std::size_t>(fineGrid.y) + static_cast<std::size_t>(y)) *
                                                  static_cast<std::size_t>(fineGrid.x) +
                                              static_cast<std::size_t>(x)];
                glm::vec2& r = ranges[(static_cast<std::size_t>(z / factor) * static_cast<std::size_t>(grid.y) + static_cast<std::size_t>(y / factor)) *
                                          static_cast<std::size_t>(grid.x) +
                                      static_cast<std::size_t>(x / factor)];
                r.x = std::min(r.x, child.x);
                r.y = std::max(r.y, child.y);
            }
    return ranges;
}

}  // namespace

int GpuVolume::textureSizeLimit(const gl::ContextInfo& info) {
    int limit = info.max3DTextureSize;
    if (const char* forced = std::getenv("CURETTE_MAX_3D_TEXTURE_SIZE")) {
        int n = std::atoi(forced);
        if (n < 2) throw InputError("CURETTE_MAX_3D_TEXTURE_SIZE", "value", "an integer of at least 2", forced);
        limit = std::min(limit, n);
    }
    return limit;
}

GpuVolume::GpuVolume(const gl::ContextInfo& info, const VolumeData& data)
    : format_(data.format), valueScale_(data.valueScale), valueOffset_(data.valueOffset), noData_(data) {
    layout_ = VolumeLayout::forLimit(data.dims, textureSizeLimit(info), data.source);
    if (data.voxels.size() != data.voxelCount() * bytesPerVoxel(data.format))
        throw SystemError(data.source + ": " + std::to_string(data.voxels.size()) + " bytes of voxels for " + std::to_string(data.voxelCount()) +
                          " voxels (a reader's bug)");
    geometry_.dims = data.dims;
    geometry_.indexToWorld = data.indexToWorld;

    VolumeTextureFormat tf = textureFormat(format_);
    texture_ = createVolumeTexture(layout_, tf, "V (data volume)");
    uploadVolumeBox(texture_.name(), layout_, tf, glm::ivec3(0), data.dims, data.voxels.data());
    if (glGetError() == GL_OUT_OF_MEMORY)
        throw SystemError(data.source + ": not enough GPU memory for a " + std::to_string(data.voxels.size()) +
                          "-byte volume texture");
    gpuBytes_ = layout_.texelCount() * std::size_t(tf.bytesPerVoxel);

    // One pass over the voxels for the finer bricks; the ray caster's are their unions.
    seenBrickGrid_ = (data.dims + seenBrickSize - 1) / seenBrickSize;
    seenBrickRanges_ = brickRangesOf(data, seenBrickSize, seenBrickGrid_);
    brickGrid_ = (data.dims + brickSize - 1) / brickSize;
    brickRanges_ = coarserBrickRanges(seenBrickRanges_, seenBrickGrid_, brickSize / seenBrickSize, brickGrid_);
}

}  // namespace curette
