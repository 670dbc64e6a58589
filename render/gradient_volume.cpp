#include "render/gradient_volume.h"

#include "base/error.h"
#include "gl/bindings.h"
#include "render/gpu_volume.h"

#include <string>

namespace curette {

bool GradientVolume::supports(const GpuVolume& volume) {
    return volume.format() == StorageFormat::UNorm8 && !volume.layout().folded() && !volume.hasNoData();
}

void GradientVolume::build(const GpuVolume& volume) {
    dims_ = volume.geometry().dims;
    const glm::ivec3 size = dims_ + 2;
    texture_ = gl::createTexture(GL_TEXTURE_3D);
    glTextureStorage3D(texture_.name(), 1, GL_RGBA16_SNORM, size.x, size.y, size.z);
    if (glGetError() == GL_OUT_OF_MEMORY) {
        texture_ = {};
        throw SystemError("not enough GPU memory for the gradient volume (" + std::to_string(gpuBytes(size)) + " bytes)");
    }
    glTextureParameteri(texture_.name(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(texture_.name(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R}) glTextureParameteri(texture_.name(), wrap, GL_CLAMP_TO_EDGE);
    if (!program_) program_ = gl::Program::compute("gradient_volume.comp");
    program_.use();
    program_.set("volumeSize", dims_);
    program_.set("storeScale", static_cast<float>(kGradientStoreScale));
    glBindTextureUnit(binding::volume, volume.texture());
    glBindImageTexture(binding::imageGradientVolume, texture_.name(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16_SNORM);
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

std::size_t GradientVolume::gpuBytes(glm::ivec3 size) {
    return static_cast<std::size_t>(size.x) * static_cast<std::size_t>(size.y) * static_cast<std::size_t>(size.z) * 8u;
}

std::size_t GradientVolume::gpuBytes() const { return texture_ ? gpuBytes(dims_ + 2) : 0; }

}  // namespace curette
