#pragma once
// CPU double-precision twin of GL texture sampling: trilinear filtering with clamp-to-edge (or a zero
// border) over texture coordinates, exactly as the GL specification defines it (OpenGL 4.5 core, 8.14.2).
// Used by every CPU reference so GPU kernels and oracles agree on what "a sample" is.

#include "base/volume.h"

#include <glm/glm.hpp>

#include <functional>
#include <vector>

namespace curette::reference {

enum class Wrap { ClampToEdge, ZeroBorder };

// f(i, j, k) gives the texel at integer coordinates inside the grid.
double sampleTrilinear(const std::function<double(int, int, int)>& texel, glm::ivec3 dims, glm::dvec3 tex, Wrap wrap);

// A dense double grid with trilinear sampling.
struct Grid {
    glm::ivec3 dims{0};
    std::vector<double> values;  // i fastest
    double at(int i, int j, int k) const {
        return values[(static_cast<std::size_t>(k) * static_cast<std::size_t>(dims.y) + static_cast<std::size_t>(j)) *
                          static_cast<std::size_t>(dims.x) + static_cast<std::size_t>(i)];
    }
    double& at(int i, int j, int k) {
        return values[(static_cast<std::size_t>(k) * static_cast<std::size_t>(dims.y) + static_cast<std::size_t>(j)) *
                          static_cast<std::size_t>(dims.x) + static_cast<std::size_t>(i)];
    }
    double sample(glm::dvec3 tex, Wrap wrap) const;
};

// no_data.glsl's rule: twice the index gradient along each axis from the stored values one voxel below and
// above and at the sample itself; one-sided where a neighbour is no data, 0 where both are.
glm::dvec3 differencesAcross(const NoDataSamples& noData, glm::dvec3 minus, glm::dvec3 centre, glm::dvec3 plus);

// A volume as the shaders read it: its texture (clamp to edge), which samples are no data, and the
// gradients of volume.glsl (filtered samples) and voxel_clip.comp (voxels), one-sided next to no data. A
// no-data sample is transparent on the GPU (the TF table, render/transfer_function_texture.h), so the twins
// leave it out.
class VolumeSampler {
public:
    explicit VolumeSampler(const VolumeData& volume);
    double texel(glm::dvec3 tex) const;                  // the stored value, filtered
    double voxelTexel(glm::ivec3 v) const;               // of the voxel, the index clamped to the grid
    double value(double texel) const { return volume_.valueScale * texel + volume_.valueOffset; }
    bool noData(double texel) const { return noData_(texel); }
    glm::dvec3 gradientWorld(glm::dvec3 tex) const;      // value per mm
    glm::dvec3 voxelGradientWorld(glm::ivec3 v) const;   // value per mm

private:
    const VolumeData& volume_;
    NoDataSamples noData_;
    glm::dvec3 texelSize_;
    glm::dmat3 gradientToWorld_;
};

}  // namespace curette::reference
