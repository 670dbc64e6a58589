#include "render/label_overlay.h"

#include "base/error.h"
#include "base/parallel.h"
#include "gl/bindings.h"
#include "render/gpu_volume.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace curette {

LabelOverlay::LabelOverlay(glm::ivec3 dims, const std::vector<std::uint16_t>& ids, const std::vector<glm::vec4>& styles)
    : dims_(dims), layout_(VolumeLayout::unfolded(dims)), ids_(ids) {
    if (ids.size() != std::size_t(dims.x) * std::size_t(dims.y) * std::size_t(dims.z))
        throw std::logic_error("LabelOverlay: ids do not match the grid");
    uploadIds();
    setStyles(styles);
}

namespace {
const VolumeTextureFormat kIdsFormat{GL_R16UI, GL_RED_INTEGER, GL_UNSIGNED_SHORT, 2, false, false};
const VolumeTextureFormat kFieldFormat{GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, 4, true, false};
const VolumeTextureFormat kOpacityFormat{GL_R8, GL_RED, GL_UNSIGNED_BYTE, 1, true, false};
}  // namespace

void LabelOverlay::uploadIds() {
    idsTexture_ = createVolumeTexture(layout_, kIdsFormat, "label ids");
    uploadVolumeBox(idsTexture_.name(), layout_, kIdsFormat, glm::ivec3(0), dims_, ids_.data());
    if (glGetError() == GL_OUT_OF_MEMORY) throw SystemError("not enough GPU memory for the label volume");
}

void LabelOverlay::setLayout(const VolumeLayout& layout) {
    if (layout.dims != dims_) throw std::logic_error("LabelOverlay: the layout is not the label grid's");
    if (layout == layout_) return;
    layout_ = layout;
    uploadIds();
    fieldTexture_ = gl::Texture();
    opacityTexture_ = gl::Texture();
    fieldStale_ = true;
    build_.reset();
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
    build_.reset();   // a build under way was for the old styles
}

LabelOverlay::~LabelOverlay() = default;

struct LabelOverlay::FieldBuild {
    enum Stage { Classify, BlurX, BlurY, BlurZ, Pack, Upload };
    int stage = Classify;
    int nextPlane = 0;
    bool anyShown = false;
    std::vector<glm::vec4> field, scratch;   // per voxel (rgb * shown, shown)
    std::vector<float> opacity, opacityScratch;   // opacity * shown of its style
    std::vector<std::uint8_t> rgba, alpha;
};

void LabelOverlay::runFieldPlanes(FieldBuild& b, int planes) const {
    const std::size_t n = ids_.size(), plane = std::size_t(dims_.x) * std::size_t(dims_.y);
    const int first = b.nextPlane, end = std::min(dims_.z, first + planes);
    auto overPlanes = [&](const auto& voxel) {
        splitAcrossThreads(static_cast<std::size_t>(end - first), [&](std::size_t a, std::size_t z) {
            for (std::size_t v = (first + a) * plane; v < (first + z) * plane; ++v) voxel(v);
        });
    };
    switch (b.stage) {
        case FieldBuild::Classify:
            if (b.field.empty()) b.field.resize(n), b.opacity.resize(n);
            overPlanes([&](std::size_t v) {
                const glm::vec4& style = styles_[ids_[v]];
                float shown = style.a > 0.0f ? 1.0f : 0.0f;
                b.field[v] = glm::vec4(glm::vec3(style) * shown, shown);
                b.opacity[v] = style.a;
            });
            for (std::size_t v = first * plane; v < end * plane && !b.anyShown; ++v) b.anyShown = b.field[v].w > 0.0f;
            break;
        case FieldBuild::BlurX:
        case FieldBuild::BlurY:
        case FieldBuild::BlurZ: {
            // A separable Gaussian, clamped at the grid's edge as the textures are. Each output voxel reads only the
            // last stage's arrays, so planes can run in any order.
            const int axis = b.stage - FieldBuild::BlurX;
            if (b.scratch.empty()) b.scratch.resize(n), b.opacityScratch.resize(n);
            float weights[2 * kLabelSmoothingReach + 1], sum = 0.0f;
            for (int d = -kLabelSmoothingReach; d <= kLabelSmoothingReach; ++d)
                sum += weights[d + kLabelSmoothingReach] = static_cast<float>(std::exp(-0.5 * d * d / (kLabelSmoothingVoxels * kLabelSmoothingVoxels)));
            for (float& w : weights) w /= sum;
            const glm::ivec3 stride(1, dims_.x, dims_.x * dims_.y);
            splitAcrossThreads(static_cast<std::size_t>(end - first), [&](std::size_t a, std::size_t z) {
                std::size_t v = (first + a) * plane;
                for (int k = first + static_cast<int>(a); k < first + static_cast<int>(z); ++k)
                    for (int j = 0; j < dims_.y; ++j)
                        for (int i = 0; i < dims_.x; ++i, ++v) {
                            const int at = glm::ivec3(i, j, k)[axis];
                            glm::vec4 acc(0.0f);
                            float accOpacity = 0.0f;
                            for (int d = -kLabelSmoothingReach; d <= kLabelSmoothingReach; ++d) {
                                int q = std::clamp(at + d, 0, dims_[axis] - 1);
                                std::size_t u = v + static_cast<std::size_t>(static_cast<std::ptrdiff_t>(q - at) * stride[axis]);
                                acc += weights[d + kLabelSmoothingReach] * b.field[u];
                                accOpacity += weights[d + kLabelSmoothingReach] * b.opacity[u];
                            }
                            b.scratch[v] = acc;
                            b.opacityScratch[v] = accOpacity;
                        }
            });
            break;
        }
        case FieldBuild::Pack: {
            if (b.rgba.empty()) b.rgba.resize(4 * n), b.alpha.resize(n);
            auto byte = [](float x) { return static_cast<std::uint8_t>(std::lround(std::clamp(x, 0.0f, 1.0f) * 255.0f)); };
            overPlanes([&](std::size_t v) {
                for (int c = 0; c < 4; ++c) b.rgba[4 * v + static_cast<std::size_t>(c)] = byte(b.field[v][c]);
                b.alpha[v] = byte(b.opacity[v]);
            });
            break;
        }
        case FieldBuild::Upload:
            uploadField(b);
            b.nextPlane = dims_.z;
            break;
    }
    if (b.stage != FieldBuild::Upload) b.nextPlane = end;
    if (b.nextPlane < dims_.z) return;
    // The stage is done: a blur's output becomes the next stage's input; with no label shown there is nothing to blur.
    if (b.stage >= FieldBuild::BlurX && b.stage <= FieldBuild::BlurZ) b.field.swap(b.scratch), b.opacity.swap(b.opacityScratch);
    b.stage = b.stage == FieldBuild::Classify && !b.anyShown ? int(FieldBuild::Pack) : b.stage + 1;
    b.nextPlane = 0;
    if (b.stage == FieldBuild::Pack) b.scratch = {}, b.opacityScratch = {};
}

void LabelOverlay::advanceField(double budgetMs, int planesPerSlice) const {
    if (!fieldStale_) return;
    if (!build_) build_ = std::make_unique<FieldBuild>();
    auto start = std::chrono::steady_clock::now();
    // Slices of a few planes, until the budget is spent (planesPerSlice: one slice of that many).
    const int planes = planesPerSlice > 0 ? planesPerSlice : std::max(1, dims_.z / 32);
    do {
        runFieldPlanes(*build_, planes);
        if (build_->stage > FieldBuild::Upload) {
            build_.reset();
            fieldStale_ = false;
            return;
        }
    } while (planesPerSlice == 0 && std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() < budgetMs);
}

double LabelOverlay::fieldProgress() const {
    if (!fieldStale_) return 1.0;
    if (!build_) return 0.0;
    // Five stages over the planes and the upload, counted as one plane.
    const double units = 5.0 * dims_.z + 1.0;
    const int stage = std::min(build_->stage, int(FieldBuild::Upload));
    return (stage * double(dims_.z) + build_->nextPlane) / units;
}

void LabelOverlay::uploadField(const FieldBuild& b) const {
    if (!fieldTexture_) fieldTexture_ = createVolumeTexture(layout_, kFieldFormat, "label field (smoothed shown colour, shown)");
    if (!opacityTexture_) opacityTexture_ = createVolumeTexture(layout_, kOpacityFormat, "label field (smoothed opacity)");
    uploadVolumeBox(fieldTexture_.name(), layout_, kFieldFormat, glm::ivec3(0), dims_, b.rgba.data());
    uploadVolumeBox(opacityTexture_.name(), layout_, kOpacityFormat, glm::ivec3(0), dims_, b.alpha.data());
    if (glGetError() == GL_OUT_OF_MEMORY) throw SystemError("not enough GPU memory for the label field");
}

void LabelOverlay::addDefines(gl::Defines& defines) const { defines.emplace_back("LABELS", "1"); }

void LabelOverlay::apply(gl::Program&) const {
    while (fieldStale_) advanceField(1e300);
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

std::size_t LabelOverlay::gpuBytes() const { return layout_.texelCount() * (2 + 4 + 1) + styles_.size() * 16; }

}  // namespace curette
