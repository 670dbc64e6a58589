#include "render/label_overlay.h"

#include "base/error.h"
#include "base/parallel.h"
#include "gl/bindings.h"
#include "render/gpu_volume.h"

#include <algorithm>
#include <cmath>

namespace curette {

LabelOverlay::LabelOverlay(glm::ivec3 dims, const std::vector<std::uint16_t>& ids, const std::vector<glm::vec4>& styles)
    : dims_(dims), ids_(ids) {
    if (ids.size() != std::size_t(dims.x) * std::size_t(dims.y) * std::size_t(dims.z))
        throw std::logic_error("LabelOverlay: ids do not match the grid");
    idsTexture_ = gl::createTexture(GL_TEXTURE_3D);
    glTextureStorage3D(idsTexture_.name(), 1, GL_R16UI, dims.x, dims.y, dims.z);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 2);
    glTextureSubImage3D(idsTexture_.name(), 0, 0, 0, 0, dims.x, dims.y, dims.z, GL_RED_INTEGER, GL_UNSIGNED_SHORT, ids.data());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    for (GLenum p : {GL_TEXTURE_MIN_FILTER, GL_TEXTURE_MAG_FILTER}) glTextureParameteri(idsTexture_.name(), p, GL_NEAREST);
    glObjectLabel(GL_TEXTURE, idsTexture_.name(), -1, "label ids");
    if (glGetError() == GL_OUT_OF_MEMORY) throw SystemError("not enough GPU memory for the label volume");
    setStyles(styles);
}

void LabelOverlay::setStyles(const std::vector<glm::vec4>& styles) {
    std::uint16_t maxId = ids_.empty() ? 0 : *std::max_element(ids_.begin(), ids_.end());
    styles_ = styles;
    // Every id the volume holds has a style (unlisted ids are transparent); id 0 never shows.
    if (styles_.size() <= maxId) styles_.resize(std::size_t(maxId) + 1, glm::vec4(0.0f));
    if (!styles_.empty()) styles_[0] = glm::vec4(0.0f);
    for (glm::vec4& s : styles_) s = glm::clamp(s, glm::vec4(0.0f), glm::vec4(1.0f));
    if (!stylesTexture_ || std::size_t(styleTexels_) != styles_.size()) {
        stylesTexture_ = gl::createTexture(GL_TEXTURE_1D);
        styleTexels_ = static_cast<int>(styles_.size());
        glTextureStorage1D(stylesTexture_.name(), 1, GL_RGBA32F, styleTexels_);
        for (GLenum p : {GL_TEXTURE_MIN_FILTER, GL_TEXTURE_MAG_FILTER}) glTextureParameteri(stylesTexture_.name(), p, GL_NEAREST);
        glObjectLabel(GL_TEXTURE, stylesTexture_.name(), -1, "label styles");
    }
    glTextureSubImage1D(stylesTexture_.name(), 0, 0, styleTexels_, GL_RGBA, GL_FLOAT, styles_.data());
    fieldStale_ = true;
}

void LabelOverlay::uploadField() const {
    // Per voxel (rgb * shown, shown) and opacity * shown of its style, blurred along x, y and z in turn.
    const std::size_t n = ids_.size();
    std::vector<glm::vec4> field(n), scratch(n);
    std::vector<float> opacity(n), opacityScratch(n);
    bool anyShown = false;
    for (std::size_t v = 0; v < n; ++v) {
        const glm::vec4& style = styles_[ids_[v]];
        float shown = style.a > 0.0f ? 1.0f : 0.0f;
        field[v] = glm::vec4(glm::vec3(style) * shown, shown);
        opacity[v] = style.a;
        anyShown = anyShown || shown > 0.0f;
    }
    float weights[2 * kLabelSmoothingReach + 1], sum = 0.0f;
    for (int d = -kLabelSmoothingReach; d <= kLabelSmoothingReach; ++d)
        sum += weights[d + kLabelSmoothingReach] = static_cast<float>(std::exp(-0.5 * d * d / (kLabelSmoothingVoxels * kLabelSmoothingVoxels)));
    for (float& w : weights) w /= sum;
    const glm::ivec3 stride(1, dims_.x, dims_.x * dims_.y);
    for (int axis = 0; axis < 3 && anyShown; ++axis) {
        // Each output voxel reads only the last pass's arrays: planes of k split across threads.
        splitAcrossThreads(static_cast<std::size_t>(dims_.z), [&](std::size_t kFirst, std::size_t kEnd) {
            std::size_t v = kFirst * std::size_t(dims_.x) * std::size_t(dims_.y);
            for (int k = static_cast<int>(kFirst); k < static_cast<int>(kEnd); ++k)
                for (int j = 0; j < dims_.y; ++j)
                    for (int i = 0; i < dims_.x; ++i, ++v) {
                        int at = glm::ivec3(i, j, k)[axis];
                        glm::vec4 acc(0.0f);
                        float accOpacity = 0.0f;
                        // Clamped at the grid's edge, as the textures are.
                        for (int d = -kLabelSmoothingReach; d <= kLabelSmoothingReach; ++d) {
                            int q = std::clamp(at + d, 0, dims_[axis] - 1);
                            std::size_t u = v + static_cast<std::size_t>(static_cast<std::ptrdiff_t>(q - at) * stride[axis]);
                            acc += weights[d + kLabelSmoothingReach] * field[u];
                            accOpacity += weights[d + kLabelSmoothingReach] * opacity[u];
                        }
                        scratch[v] = acc;
                        opacityScratch[v] = accOpacity;
                    }
        });
        field.swap(scratch);
        opacity.swap(opacityScratch);
    }
    auto byte = [](float x) { return static_cast<std::uint8_t>(std::lround(std::clamp(x, 0.0f, 1.0f) * 255.0f)); };
    std::vector<std::uint8_t> rgba(4 * n), alpha(n);
    for (std::size_t v = 0; v < n; ++v) {
        for (int c = 0; c < 4; ++c) rgba[4 * v + static_cast<std::size_t>(c)] = byte(field[v][c]);
        alpha[v] = byte(opacity[v]);
    }
    auto make = [&](gl::Texture& t, GLenum format, const char* label) {
        if (t) return;
        t = gl::createTexture(GL_TEXTURE_3D);
        glTextureStorage3D(t.name(), 1, format, dims_.x, dims_.y, dims_.z);
        for (GLenum p : {GL_TEXTURE_MIN_FILTER, GL_TEXTURE_MAG_FILTER}) glTextureParameteri(t.name(), p, GL_LINEAR);
        for (GLenum p : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R}) glTextureParameteri(t.name(), p, GL_CLAMP_TO_EDGE);
        glObjectLabel(GL_TEXTURE, t.name(), -1, label);
        if (glGetError() == GL_OUT_OF_MEMORY) throw SystemError("not enough GPU memory for the label field");
    };
    make(fieldTexture_, GL_RGBA8, "label field (smoothed shown colour, shown)");
    make(opacityTexture_, GL_R8, "label field (smoothed opacity)");
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage3D(fieldTexture_.name(), 0, 0, 0, 0, dims_.x, dims_.y, dims_.z, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    glTextureSubImage3D(opacityTexture_.name(), 0, 0, 0, 0, dims_.x, dims_.y, dims_.z, GL_RED, GL_UNSIGNED_BYTE, alpha.data());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
}

void LabelOverlay::addDefines(gl::Defines& defines) const { defines.emplace_back("LABELS", "1"); }

void LabelOverlay::apply(gl::Program&) const {
    if (fieldStale_) {
        uploadField();
        fieldStale_ = false;
    }
    glBindTextureUnit(binding::labelIds, idsTexture_.name());
    glBindTextureUnit(binding::labelStyles, stylesTexture_.name());
    glBindTextureUnit(binding::labelField, fieldTexture_.name());
    glBindTextureUnit(binding::labelOpacity, opacityTexture_.name());
}

std::vector<std::uint8_t> LabelOverlay::occupiedBricks(glm::ivec3 grid, int brickSize) const {
    std::vector<std::uint8_t> flags(std::size_t(grid.x) * std::size_t(grid.y) * std::size_t(grid.z), 0);
    std::size_t v = 0;
    for (int k = 0; k < dims_.z; ++k)
        for (int j = 0; j < dims_.y; ++j)
            for (int i = 0; i < dims_.x; ++i, ++v) {
                std::uint16_t id = ids_[v];
                if (id == 0 || styles_[id].a <= 0.0f) continue;
                // Every brick whose samples can read this voxel's share of the smoothed field: the voxels
                // within the Gaussian's reach, and their bricks with the trilinear apron.
                auto bricks = [&](int at, int count, int extent) {
                    glm::ivec2 lo = GpuVolume::bricksHoldingVoxel(std::max(at - kLabelSmoothingReach, 0), count, brickSize);
                    glm::ivec2 hi = GpuVolume::bricksHoldingVoxel(std::min(at + kLabelSmoothingReach, extent - 1), count, brickSize);
                    return glm::ivec2(lo.x, hi.y);
                };
                glm::ivec2 bx = bricks(i, grid.x, dims_.x), by = bricks(j, grid.y, dims_.y), bz = bricks(k, grid.z, dims_.z);
                for (int b2 = bz.x; b2 <= bz.y; ++b2)
                    for (int b1 = by.x; b1 <= by.y; ++b1)
                        for (int b0 = bx.x; b0 <= bx.y; ++b0)
                            flags[(std::size_t(b2) * std::size_t(grid.y) + std::size_t(b1)) * std::size_t(grid.x) + std::size_t(b0)] = 255;
            }
    return flags;
}

std::size_t LabelOverlay::gpuBytes() const { return ids_.size() * (2 + 4 + 1) + styles_.size() * 16; }

}  // namespace curette
