#pragma once
// Phong's gradient of an 8-bit scan as a texture (volume.glsl's gradientWorld with GRADIENT_VOLUME): per voxel
// the central differences, RGBA16_SNORM, built once per volume (shaders/gradient_volume.comp) by the `gradient
// volume` pass when a phong ray cast first needs it. The ray cast then reads one filtered texel per gradient instead of six.
//
// Why it is the same gradient: along an axis, the difference of two trilinear samples one voxel either side of
// a point is the trilinear interpolation, with the same weights, of the voxels' own central differences. The
// differences are exact in 16 bits (k 8-bit steps stored as 128 k of 32767). The texture has one texel more on
// every side holding what clamp-to-edge sampling reads outside the cells: along the axis the two clamped
// neighbours are one voxel (0), across it the edge's differences. Other scans (16-bit, float, with no-data
// voxels, folded) keep the six reads: their differences would not be exact in 16 bits, or the pad not hold.

#include "gl/objects.h"
#include "gl/program.h"

#include <cstddef>

namespace curette {

class GpuVolume;

// A difference of k 8-bit steps is stored as 128 k (of 32767): exact for |k| <= 255. Read back as a normalized
// value difference (k / 255) by 1 / kGradientStoreScale.
inline constexpr int kGradientStoreSteps = 128;
inline constexpr double kGradientStoreScale = kGradientStoreSteps * 255.0 / 32767.0;

class GradientVolume {
public:
    static bool supports(const GpuVolume& volume);
    bool built() const { return static_cast<bool>(texture_); }
    void build(const GpuVolume& volume);
    // Binds it and sets volume.glsl's gradient uniforms (programs compiled with GRADIENT_VOLUME).
    void apply(gl::Program& program) const;
    std::size_t gpuBytes() const;

private:
    gl::Texture texture_;
    glm::ivec3 dims_{0};   // the volume's (the texture's are 2 more)
    gl::Program program_;  // shaders/gradient_volume.comp
};

}  // namespace curette
