#include "render/gpu_volume.h"

#include "base/error.h"

#include <algorithm>
#include <string>

namespace curette {

namespace {

struct TextureFormat {
    GLenum internal, format, type;
};

TextureFormat textureFormat(StorageFormat f) {
    switch (f) {
        case StorageFormat::UNorm8: return {GL_R8, GL_RED, GL_UNSIGNED_BYTE};
        case StorageFormat::UNorm16: return {GL_R16, GL_RED, GL_UNSIGNED_SHORT};
        case StorageFormat::Float32: return {GL_R32F, GL_RED, GL_FLOAT};
    }
    return {GL_R8, GL_RED, GL_UNSIGNED_BYTE};
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

GpuVolume::GpuVolume(const gl::ContextInfo& info, const VolumeData& data)
    : format_(data.format), valueScale_(data.valueScale), valueOffset_(data.valueOffset), noData_(data) {
    for (int axis = 0; axis < 3; ++axis)
        if (data.dims[axis] < 1 || data.dims[axis] > info.max3DTextureSize)
            throw InputError(data.source, "dim[" + std::to_string(axis + 1) + "]",
                             "between 1 and " + std::to_string(info.max3DTextureSize) +
                                 " voxels (GL_MAX_3D_TEXTURE_SIZE of " + info.renderer + ")",
                             std::to_string(data.dims[axis]));
    geometry_.dims = data.dims;
    geometry_.indexToWorld = data.indexToWorld;

    TextureFormat tf = textureFormat(format_);
    texture_ = gl::createTexture(GL_TEXTURE_3D);
    glTextureStorage3D(texture_.name(), 1, tf.internal, data.dims.x, data.dims.y, data.dims.z);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage3D(texture_.name(), 0, 0, 0, 0, data.dims.x, data.dims.y, data.dims.z, tf.format, tf.type,
                        data.voxels.data());
    glTextureParameteri(texture_.name(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(texture_.name(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        glTextureParameteri(texture_.name(), wrap, GL_CLAMP_TO_EDGE);
    glObjectLabel(GL_TEXTURE, texture_.name(), -1, "V (data volume)");
    if (glGetError() == GL_OUT_OF_MEMORY)
        throw SystemError(data.source + ": not enough GPU memory for a " + std::to_string(data.voxels.size()) +
                          "-byte volume texture");
    gpuBytes_ = data.voxels.size();

    // One pass over the voxels for the finer bricks; the ray caster's are their unions.
    seenBrickGrid_ = (data.dims + seenBrickSize - 1) / seenBrickSize;
    seenBrickRanges_ = brickRangesOf(data, seenBrickSize, seenBrickGrid_);
    brickGrid_ = (data.dims + brickSize - 1) / brickSize;
    brickRanges_ = coarserBrickRanges(seenBrickRanges_, seenBrickGrid_, brickSize / seenBrickSize, brickGrid_);
}

}  // namespace curette
