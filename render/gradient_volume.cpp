#include "render/gradient_volume.h"

#include "gl/bindings.h"
#include "render/gpu_volume.h"
#include "render/volume_texture.h"

namespace curette {

namespace {
const VolumeTextureFormat kFormat{GL_RGBA16_SNORM, GL_RGBA, GL_SHORT, 8};
// The texture: the scan's voxels and one texel of padding on every side.
VolumeLayout paddedLayout(glm::ivec3 dims) { return VolumeLayout::unfolded(dims + 2); }
}  // namespace

bool GradientVolume::supports(const GpuVolume& volume) {
    return volume.format() == StorageFormat::UNorm8 && !volume.layout().folded() && !volume.hasNoData();
}

void GradientVolume::build(const GpuVolume& volume) {
    dims_ = volume.geometry().dims;
    const glm::ivec3 size = dims_ + 2;
    texture_ = createVolumeTexture(paddedLayout(dims_), kFormat, "gradient volume");
    if (!program_) program_ = gl::Program::compute("gradient_volume.comp");
    program_.use();
    program_.set("volumeSize", dims_);
    program_.set("storeScale", static_cast<float>(kGradientStoreScale));
    glBindTextureUnit(binding::volume, volume.texture());
    glBindImageTexture(binding::imageGradientVolume, texture_.name(), 0, GL_TRUE, 0, GL_WRITE_ONLY, kFormat.internal);
    program_.dispatchCovering(glm::uvec3(size));
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
}

void GradientVolume::apply(gl::Program& p) const {
    // A texture coordinate t of the volume (cells over [0, 1]) is t * n / (n + 2) + 1 / (n + 2) in the padded one.
    glm::dvec3 n(dims_);
    p.set("gradientVolumeScale", glm::vec3(n / (n + 2.0)));
    p.set("gradientVolumeOffset", glm::vec3(1.0 / (n + 2.0)));
    p.set("gradientVolumeUnit", static_cast<float>(1.0 / kGradientStoreScale));
    glBindTextureUnit(binding::gradientVolume, texture_.name());
}

std::size_t GradientVolume::gpuBytes() const {
    return texture_ ? paddedLayout(dims_).texelCount() * static_cast<std::size_t>(kFormat.bytesPerVoxel) : 0;
}

}  // namespace curette
