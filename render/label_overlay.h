#pragma once
// Label volumes on the GPU (the binder of shaders/labels.glsl): one R16UI 3-D texture of label ids on the
// scan grid, a 1-D RGBA32F table of styles per id (rgb, opacity per unit length; 0 hides the label), and the
// label field the ray caster reads: per voxel its shown indicator, the shown colour and the opacity through a
// separable Gaussian (kLabelSmoothingVoxels; RGBA8 and R8), redrawn when a pass first binds the labels after
// the styles changed (a report that renders nothing never pays for it), so label surfaces are smooth.
// Several label sets share one id space (scene/scene_labels.h assigns each set a range). Attached to the
// TransferFunctionTexture, whose binder adds LABELS and binds these: every pass that classifies samples
// (ray cast, slab pass, step IV) carries the labels, and a scene without labels compiles none of it.

#include "gl/objects.h"
#include "gl/program.h"
#include "render/volume_texture.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <vector>

namespace curette {

// The Gaussian's standard deviation and reach, in voxels: enough to round a voxel staircase into a surface,
// little enough to keep a 2-voxel structure.
inline constexpr double kLabelSmoothingVoxels = 0.75;
inline constexpr int kLabelSmoothingReach = 2;

class LabelOverlay {
public:
    // ids: dims.x * dims.y * dims.z label ids on the scan grid, i fastest. styles: one per id (index = id),
    // id 0 (no label) must be transparent.
    LabelOverlay(glm::ivec3 dims, const std::vector<std::uint16_t>& ids, const std::vector<glm::vec4>& styles);
    ~LabelOverlay();
    // The layout of the volume's textures (render/model/volume_layout.h); unfolded until the renderer sets it.
    void setLayout(const VolumeLayout& layout);

    void setStyles(const std::vector<glm::vec4>& styles);
    const std::vector<glm::vec4>& styles() const { return styles_; }

    void addDefines(gl::Defines& defines) const;
    void apply(gl::Program& program) const;   // finishes a field still to build, then binds

    // The label field in slices: whether it is still to build for the current styles; advanceField runs the build
    // for about budgetMs of wall time (planesPerSlice > 0: that many planes of one stage instead, for tests;
    // at least one slice either way); how far it is, in [0, 1].
    bool fieldPending() const { return fieldStale_; }
    void advanceField(double budgetMs, int planesPerSlice = 0) const;
    double fieldProgress() const;

    // For empty-space skipping: per brick of `brickSize` voxels (render/gpu_volume.h, grid `brickGrid`),
    // whether a shown label's smoothed field reaches into the brick or its one-voxel apron.
    std::vector<std::uint8_t> occupiedBricks(glm::ivec3 brickGrid, int brickSize) const;
    std::size_t gpuBytes() const;

private:
    glm::ivec3 dims_;
    VolumeLayout layout_;
    std::vector<std::uint16_t> ids_;
    std::vector<glm::vec4> styles_;
    // The label field is a cache of the styles, built when stale: hence mutable. Its build runs in stages, each
    // over the grid's planes of k: classify each voxel by its style, blur along x, y and z, pack to bytes; then
    // the upload.
    struct FieldBuild;
    void runFieldPlanes(FieldBuild& build, int planes) const;
    void uploadField(const FieldBuild& build) const;
    void uploadIds();
    mutable std::unique_ptr<FieldBuild> build_;
    gl::Texture idsTexture_, stylesTexture_;
    mutable gl::Texture fieldTexture_, opacityTexture_;
    mutable bool fieldStale_ = true;
    int styleTexels_ = 0;
};

}  // namespace curette
