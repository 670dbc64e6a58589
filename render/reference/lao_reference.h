#pragma once
// CPU double-precision twins of step IV (shaders/voxel_clip.comp) and of the LAO ray
// (shaders/lao_ray.glsl, CAO eq. 2 and 3), and the CPU ground truth of the benchmark (K = 512 Fibonacci).

#include "render/model/lao_directions.h"
#include "render/reference/volume_sampler.h"
#include "base/transfer_function.h"
#include "base/volume.h"

#include <functional>

namespace curette::reference {

using InsideTest = std::function<bool(glm::dvec3 world)>;

struct VoxelClipping {
    Grid opacity;                       // V_o: opacity per TF unit length after clipping
    std::vector<std::uint8_t> category; // V_m: 0 clipped, 1 affected, 2 unaffected
};

// Algorithm 2 for every voxel with the same sample offsets as the GPU (antiAliasingOffsets: the N extra
// offsets in index units, clip::antiAliasingOffsets; the count of samples inside is clip::insideSampleCount).
// `dilated` may be empty (LAO baseline: every visible voxel is affected).
VoxelClipping clipVoxels(const VolumeData& volume, const TransferFunction& tf, const InsideTest& inside,
                         const InsideTest& dilated, const std::vector<glm::dvec3>& antiAliasingOffsets);

// The LAO of voxel `v` from a V_o grid (zero outside): eq. 2 and 3 with the directions in world space.
struct LaoParameters {
    std::vector<LaoDirection> directions;
    int samples = 20;           // M
    double stepMm = 1.0;
    double unitLengthMm = 1.0;  // the TF's opacity unit length
};
double localAmbientOcclusion(const Grid& opacity, const glm::dmat4& worldToTexture, const glm::dmat4& indexToWorld,
                             glm::ivec3 v, const LaoParameters& parameters);

}  // namespace curette::reference
