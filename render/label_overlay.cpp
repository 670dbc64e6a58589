#include "render/label_overlay.h"

#include "base/error.h"
#include "gl/bindings.h"
#include "render/gpu_volume.h"

#include <algorithm>

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
}

void LabelOverlay::addDefines(gl::Defines& defines) const { defines.emplace_back("LABELS", "1"); }

void LabelOverlay::apply(gl::Program&) const {
    glBindTextureUnit(binding::labelIds, idsTexture_.name());
    glBindTextureUnit(binding::labelStyles, stylesTexture_.name());
}

std::vector<std::uint8_t> LabelOverlay::occupiedBricks(glm::ivec3 grid, int brickSize) const {
    std::vector<std::uint8_t> flags(std::size_t(grid.x) * std::size_t(grid.y) * std::size_t(grid.z), 0);
    std::size_t v = 0;
    for (int k = 0; k < dims_.z; ++k)
        for (int j = 0; j < dims_.y; ++j)
            for (int i = 0; i < dims_.x; ++i, ++v) {
                std::uint16_t id = ids_[v];
                if (id == 0 || styles_[id].a <= 0.0f) continue;
                // Every brick whose samples can land in this voxel.
                glm::ivec2 bx = GpuVolume::bricksHoldingVoxel(i, grid.x, brickSize), by = GpuVolume::bricksHoldingVoxel(j, grid.y, brickSize),
                           bz = GpuVolume::bricksHoldingVoxel(k, grid.z, brickSize);
                for (int b2 = bz.x; b2 <= bz.y; ++b2)
                    for (int b1 = by.x; b1 <= by.y; ++b1)
                        for (int b0 = bx.x; b0 <= bx.y; ++b0)
                            flags[(std::size_t(b2) * std::size_t(grid.y) + std::size_t(b1)) * std::size_t(grid.x) + std::size_t(b0)] = 255;
            }
    return flags;
}

std::size_t LabelOverlay::gpuBytes() const { return ids_.size() * 2 + styles_.size() * 16; }

}  // namespace curette
