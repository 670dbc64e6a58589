#pragma once
// The slab pass: view-aligned slices marched front to back, one compute dispatch per slice, carrying an
// eye buffer and a ping-pong occlusion buffer (Directional Occlusion Shading, seed 001; with tubes, the
// combined occlusion of seed 000). Used for `dos` shading and, once tubes are in a scene, for every mode.

#include "clip/clip_mesh_set.h"
#include "render/frame.h"
#include "render/gl/program.h"
#include "render/gpu_volume.h"
#include "render/slice_lattice.h"
#include "render/transfer_function_texture.h"
#include "render/tube_set.h"

namespace curette {

class SlabPass {
public:
    static constexpr long maxSlices = kMaxSlabSlices;

    // Renders the volume into `eyeBuffer` (RGBA32F, `frame.size`). `ambient` is V_AO for cao/lao shading
    // (0 otherwise). With `tubes` (a filled G-buffer) the tubes take part in the occlusion and the partial
    // occlusion buffer is written.
    void run(const FrameDescription& frame, const DosSettings& settings, const GpuVolume& volume,
             const TransferFunctionTexture& tf, const clip::ClipMeshSet& clip, GLuint eyeBuffer, GLuint ambient,
             GBuffer* tubes = nullptr, double geometryOpacity = 0.0, double ambientScale = 2.0);

    double resolveSliceDistanceMm(const DosSettings& settings, const GpuVolume& volume) const;
    int slicesLastFrame() const { return slices_; }
    // The occlusion buffer after the last slice (tests: all channels must stay in [0, 1]).
    std::vector<glm::vec2> readOcclusion() const;
    std::size_t gpuBytes() const;

private:
    gl::Program& program(ShadingMode mode, bool tubes, const TransferFunctionTexture& tf);
    void ensureBuffers(glm::ivec2 size);

    gl::ComputeVariants programs_{"dos_slice.comp"};
    gl::Texture occlusion_[2];
    glm::ivec2 size_{0};
    int slices_ = 0;
    int last_ = 0;
};

}  // namespace curette
