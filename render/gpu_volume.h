#pragma once
// The data volume V on the GPU: a 3D texture in the volume's own storage format (R8, R16 or R32F; no
// conversion, so 8-bit CT/MRI costs one byte a voxel), its geometry, and per-brick value ranges used to
// skip empty space. A volume longer than GL_MAX_3D_TEXTURE_SIZE along one axis is folded into pieces
// (render/model/volume_layout.h); every volume-sized texture follows the same layout.

#include "gl/context.h"
#include "gl/objects.h"
#include "base/volume.h"
#include "render/model/volume_geometry.h"
#include "render/model/volume_layout.h"
#include "render/volume_texture.h"

#include <algorithm>
#include <vector>

namespace curette {

class GpuVolume {
public:
    static constexpr int brickSize = 4;

    // Throws InputError(source, "dim", ...) when no layout fits GL_MAX_3D_TEXTURE_SIZE (VolumeLayout::forLimit).
    GpuVolume(const gl::ContextInfo& info, const VolumeData& data);

    const VolumeGeometry& geometry() const { return geometry_; }
    const VolumeLayout& layout() const { return layout_; }
    // The 3-D texture size limit the layout is made for: GL_MAX_3D_TEXTURE_SIZE, or less when the environment
    // sets CURETTE_MAX_3D_TEXTURE_SIZE (tests fold small volumes with it).
    static int textureSizeLimit(const gl::ContextInfo& info);
    GLuint texture() const { return texture_.name(); }
    StorageFormat format() const { return format_; }
    double valueScale() const { return valueScale_; }
    double valueOffset() const { return valueOffset_; }
    std::size_t gpuBytes() const { return gpuBytes_; }
    // Whether some voxels hold no data (NaN/Inf in the file, stored below the minimum: base/volume.h).
    bool hasNoData() const { return noData_.any; }
    // Which stored values are no data (the shaders' test, no_data.glsl).
    const NoDataSamples& noData() const { return noData_; }

    // Bricks of B^3 voxels; for each, the lowest and highest stored texel value that trilinear sampling
    // anywhere inside the brick can see (the brick plus a one-voxel apron). B = brickSize for the ray caster's
    // empty-space skipping, B = seenBrickSize for the voxels whose LAO a visible sample can read
    // (LaoSettings::onlyWhereSeen: finer, as a brick that holds tissue is computed whole).
    static constexpr int seenBrickSize = 4;
    static_assert(brickSize % seenBrickSize == 0, "a ray caster's brick is a whole number of seen bricks");
    glm::ivec3 brickGrid() const { return brickGrid_; }
    const std::vector<glm::vec2>& brickRanges() const { return brickRanges_; }
    glm::ivec3 seenBrickGrid() const { return seenBrickGrid_; }
    const std::vector<glm::vec2>& seenBrickRanges() const { return seenBrickRanges_; }
    // Along one axis, the first and last brick of B voxels whose apron holds voxel `i` (a sample in brick b
    // interpolates voxels b*B-1 .. (b+1)*B), of `bricks` bricks: the bricks a voxel's value can reach.
    static glm::ivec2 bricksHoldingVoxel(int i, int bricks, int size = brickSize) {
        return {std::max(0, (i - 1) / size), std::min(bricks - 1, (i + 1) / size)};
    }

private:
    VolumeGeometry geometry_;
    VolumeLayout layout_;
    gl::Texture texture_;
    StorageFormat format_;
    double valueScale_, valueOffset_;
    std::size_t gpuBytes_ = 0;
    NoDataSamples noData_;
    glm::ivec3 brickGrid_{0}, seenBrickGrid_{0};
    std::vector<glm::vec2> brickRanges_, seenBrickRanges_;
};

}  // namespace curette
