#pragma once
// The drilled removal on the GPU (the binder of shaders/drill_removal.glsl): the drilled fraction per voxel
// (R8, plan/removal_volume.h's drilledByte, trilinear between voxel centres) and, per brick of 4^3 voxels,
// whether a drilled voxel lies within the dilation radius (R8UI; step IV's category b). Attached to the
// TransferFunctionTexture like the labels, so every pass that classifies carries it; a scene never drilled
// compiles none of it. Updated brick by brick from the removal's version log: a stroke step uploads only the
// bricks it changed.

#include "gl/objects.h"
#include "gl/program.h"
#include "plan/removal_volume.h"
#include "render/volume_texture.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace curette {

class RemovalTexture {
public:
    RemovalTexture(const VolumeLayout& layout, const glm::dmat4& indexToWorld);

    // Brings the textures to `removal`'s version (changed bricks only) and the near flags to `dilationRadiusMm`.
    void update(const plan::RemovalVolume& removal, double dilationRadiusMm);
    std::uint64_t version() const { return version_; }

    // Per brick (4^3 voxels, x fastest): a voxel drilled in it.
    const std::vector<std::uint8_t>& drilledBricks() const { return drilledBricks_; }
    // The bricks within `radiusMm` of `bricks` (flags of the same grid), a conservative brick dilation.
    std::vector<std::uint8_t> dilateBricks(const std::vector<std::uint8_t>& bricks, double radiusMm) const;
    glm::ivec3 brickGrid() const { return bricks_; }

    void addDefines(gl::Defines& defines) const;
    void apply(gl::Program& program) const;
    std::size_t gpuBytes() const;

private:
    glm::ivec3 dims_, bricks_;
    VolumeLayout layout_;
    double minStretchMm_ = 1;   // the smallest world length of a unit index step (a lower bound)
    gl::Texture fraction_, near_;
    std::vector<std::uint8_t> drilledBricks_;
    std::uint64_t version_ = 0;
    double nearRadiusMm_ = -1;
};

}  // namespace curette
