#pragma once
// One C++ binder per shared GLSL piece (the Inviwo shader-component model): each owns its piece's defines,
// uniforms and texture units, so a pass that includes a piece calls its binder instead of spelling uniform
// names at the call site, and gl::Program rejects a name no piece declares. A new uniform means editing the
// piece and its binder, nothing else.
//
//   GLSL piece                   binder
//   pixel_ray.glsl               CameraRayPiece (below)
//   volume.glsl                  VolumePiece (below)
//   volume_layout.glsl           VolumeLayoutPiece (below)
//   no_data.glsl                 NoDataPiece (below)
//   transfer_function.glsl       TransferFunctionTexture::addDefines / apply (render/transfer_function_texture.h)
//   classify_sample.glsl         (no uniforms: volume.glsl + transfer_function.glsl)
//   shade_sample.glsl            SampleShadingPiece (below)
//   phong.glsl                   addLightingDefines / setLightingUniforms (render/lighting.h)
//   clip_test.glsl               clip::ClipMeshSet::apply (render/passes/clip_mesh_set.h)
//   tile_order.glsl              TileOrderPiece (below; it also dispatches)
//   ismos_layers.glsl            IsmosPass::applyLayers (render/passes/ismos_pass.h); ismos_occlusion.comp: IsmosPass
//   tube_surface.glsl            TubeSurfacePiece (below)

#include "gl/program.h"
#include "render/model/frame.h"
#include "render/gpu_volume.h"
#include "render/recast_region.h"
#include "render/model/shading_mode.h"
#include "render/model/tube_vertices.h"

#include <vector>

namespace curette {

// pixel_ray.glsl: the camera ray through each pixel of a frame.
struct CameraRayPiece {
    const FrameDescription& frame;
    void apply(gl::Program& program) const;
};

// The tiles a dispatch covers when not all of them: per row of tiles, a run of columns [x, y) (render/
// recast_region.h's pixels, in tiles), and the rows that have any.
struct TileSpans {
    glm::uvec2 tileSize{0};
    std::vector<glm::uvec2> rows;
    unsigned firstRow = 0, endRow = 0, widest = 0;
};
TileSpans tileSpansOf(const PixelRegion& region, glm::uvec2 tileSize);

// tile_order.glsl: the order in which the workgroups of a per-pixel pass take the image's rows of tiles;
// dispatches the pass over an image of `size` pixels, or over the tiles of `spans` only (uploaded in
// `spanBuffer`; each pixel is shaded by the same invocation code either way). rowsPerBand = 1: scanline order.
struct TileOrderPiece {
    glm::ivec2 size;
    int rowsPerBand = defaultRowsPerBand();
    const TileSpans* spans = nullptr;
    GLuint spanBuffer = 0;
    // One row per llvmpipe worker thread (render/model/worker_deal.h): each thread then gets one row of every band.
    static int defaultRowsPerBand();
    // The parts the dispatch covers: bands of rowsPerBand rows of tiles (the image's, the last may be partly past
    // it; with spans, from the band of their first row to that of their last), each cut across into runs of
    // kPartPixels columns, in band order.
    static constexpr unsigned kPartPixels = 128;
    int partCount(glm::uvec3 workGroupSize) const;
    // Every part, or the parts [firstPart, firstPart + parts) (clamped to their number); runs of whole bands go
    // in one dispatch.
    void dispatch(gl::Program& program) const;
    void dispatchParts(gl::Program& program, int firstPart, int parts) const;
};

// volume.glsl: the data volume, its world-to-texture map and the gradient's map to world units.
struct VolumePiece {
    const GpuVolume& volume;
    void apply(gl::Program& program) const;
};

// volume_layout.glsl: where the voxels of every volume-sized texture lie (render/model/volume_layout.h). Compiled
// in (VOLUME_FOLD and its axes) only for a folded volume; every pass that reads or writes a volume-sized texture
// adds its defines and applies it.
struct VolumeLayoutPiece {
    const VolumeLayout& layout;
    void addDefines(gl::Defines& defines) const;
    void apply(gl::Program& program) const;
};

// no_data.glsl: one-sided gradients next to no-data voxels, compiled in (NO_DATA) only for a volume that has
// them. Every pass that takes gradients of the volume adds its defines and applies it.
struct NoDataPiece {
    const GpuVolume& volume;
    void addDefines(gl::Defines& defines) const;
    void apply(gl::Program& program) const;
};

// shade_sample.glsl: the colour of a sample in `mode`; lao/cao read V_AO (`ambient`, a 3-D texture) scaled by
// `ambientScale`.
struct SampleShadingPiece {
    ShadingMode mode;
    double ambientScale = 1.0;
    GLuint ambient = 0;
    CutFaceSettings cutFace{};   // used only by passes compiled with CUT_FACES
    static void addDefines(gl::Defines& defines, ShadingMode mode);
    // CUT_FACES when the frame clips (`clipMeshes` > 0) and cut faces are on.
    static void addCutFaceDefines(gl::Defines& defines, const CutFaceSettings& settings, int clipMeshes);
    void apply(gl::Program& program) const;
};

// tube_surface.glsl: the ray cast's tubes (raycast.comp with TUBES): the G-buffer's depth, colour and normal
// textures, the tubes' material and line exponent, and the camera's forward axis. lao/cao read V_AO through
// SampleShadingPiece's binding.
struct TubeSurfacePiece {
    const FrameDescription& frame;
    GLuint depth = 0, color = 0, normal = 0;   // GBuffer's textures (render/passes/tube_set.h)
    const TubeShading& shading;
    static void addDefines(gl::Defines& defines);
    void apply(gl::Program& program) const;
};

}  // namespace curette
