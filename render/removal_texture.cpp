#include "render/removal_texture.h"

#include "base/error.h"
#include "gl/bindings.h"

#include <algorithm>
#include <cmath>

namespace curette {

namespace {
const VolumeTextureFormat kFractionFormat{GL_R8, GL_RED, GL_UNSIGNED_BYTE, 1, true, false};
}  // namespace

RemovalTexture::RemovalTexture(const VolumeLayout& layout, const glm::dmat4& indexToWorld) : dims_(layout.dims), layout_(layout) {
    const glm::ivec3 dims = layout.dims;
    bricks_ = (dims + plan::kRemovalBrickSize - 1) / plan::kRemovalBrickSize;
    minStretchMm_ = plan::smallestStretchMm(indexToWorld);
    drilledBricks_.assign(std::size_t(bricks_.x) * std::size_t(bricks_.y) * std::size_t(bricks_.z), 0);

    auto make = [&](gl::Texture& t, GLenum format, glm::ivec3 size, GLenum filter, const char* label) {
        t = gl::createTexture(GL_TEXTURE_3D);
        glTextureStorage3D(t.name(), 1, format, size.x, size.y, size.z);
        for (GLenum p : {GL_TEXTURE_MIN_FILTER, GL_TEXTURE_MAG_FILTER}) glTextureParameteri(t.name(), p, static_cast<GLint>(filter));
        for (GLenum p : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R}) glTextureParameteri(t.name(), p, GL_CLAMP_TO_EDGE);
        glObjectLabel(GL_TEXTURE, t.name(), -1, label);
        if (glGetError() == GL_OUT_OF_MEMORY) throw SystemError("not enough GPU memory for the drilled removal");
    };
    fraction_ = createVolumeTexture(layout, kFractionFormat, "drilled fraction");
    glClearTexImage(fraction_.name(), 0, GL_RED, GL_UNSIGNED_BYTE, nullptr);   // nothing drilled
    make(near_, GL_R8UI, bricks_, GL_NEAREST, "near-drill bricks");
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage3D(near_.name(), 0, 0, 0, 0, bricks_.x, bricks_.y, bricks_.z, GL_RED_INTEGER, GL_UNSIGNED_BYTE, drilledBricks_.data());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
}

std::vector<std::uint8_t> RemovalTexture::dilateBricks(const std::vector<std::uint8_t>& bricks, double radiusMm) const {
    // Bricks whose index boxes lie within radius / minStretch index units of each other, in whole bricks plus
    // one for the voxels' own extent: separable, so a box dilation (a superset of the ball's).
    int k = static_cast<int>(std::ceil(radiusMm / minStretchMm_ / plan::kRemovalBrickSize)) + 1;
    std::vector<std::uint8_t> a = bricks, b(bricks.size(), 0);
    auto at = [&](int x, int y, int z) { return (std::size_t(z) * std::size_t(bricks_.y) + std::size_t(y)) * std::size_t(bricks_.x) + std::size_t(x); };
    for (int axis = 0; axis < 3; ++axis) {
        std::fill(b.begin(), b.end(), 0);
        for (int z = 0; z < bricks_.z; ++z)
            for (int y = 0; y < bricks_.y; ++y)
                for (int x = 0; x < bricks_.x; ++x) {
                    if (!a[at(x, y, z)]) continue;
                    glm::ivec3 p(x, y, z);
                    int lo = std::max(0, p[axis] - k), hi = std::min(bricks_[axis] - 1, p[axis] + k);
                    for (int i = lo; i <= hi; ++i) {
                        glm::ivec3 q = p;
                        q[axis] = i;
                        b[at(q.x, q.y, q.z)] = 1;
                    }
                }
        std::swap(a, b);
    }
    return a;
}

void RemovalTexture::update(const plan::RemovalVolume& removal, double dilationRadiusMm) {
    if (removal.dims() != dims_) throw std::logic_error("RemovalTexture: the removal is not on the scan grid");
    bool changed = removal.version() != version_;
    if (changed) {
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        for (std::uint32_t brick : removal.bricksChangedSince(version_)) {
            std::array<std::uint8_t, plan::kRemovalBrickVoxels> bytes = removal.brickBytes(brick);
            glm::ivec3 o = removal.brickOrigin(brick);
            glm::ivec3 size = glm::min(glm::ivec3(plan::kRemovalBrickSize), dims_ - o);
            // The brick's bytes are 4 x 4 x 4 with x fastest; upload the part inside the grid.
            uploadVolumeBox(fraction_.name(), layout_, kFractionFormat, o, size, bytes.data(),
                            glm::ivec2(plan::kRemovalBrickSize));
            drilledBricks_[brick] = std::any_of(bytes.begin(), bytes.end(), [](std::uint8_t v) { return v != 0; }) ? 1 : 0;
        }
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        version_ = removal.version();
    }
    if (changed || dilationRadiusMm != nearRadiusMm_) {
        std::vector<std::uint8_t> near = dilateBricks(drilledBricks_, dilationRadiusMm);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        glTextureSubImage3D(near_.name(), 0, 0, 0, 0, bricks_.x, bricks_.y, bricks_.z, GL_RED_INTEGER, GL_UNSIGNED_BYTE, near.data());
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        nearRadiusMm_ = dilationRadiusMm;
    }
}

void RemovalTexture::addDefines(gl::Defines& defines) const { defines.emplace_back("DRILL_REMOVAL", "1"); }

void RemovalTexture::apply(gl::Program&) const {
    glBindTextureUnit(binding::drilledFraction, fraction_.name());
    glBindTextureUnit(binding::drillNearBricks, near_.name());
}

std::size_t RemovalTexture::gpuBytes() const {
    return layout_.texelCount() + drilledBricks_.size();
}

}  // namespace curette
