#pragma once
// The renderer of one scene: it owns the GPU resources the scene needs (allocated once, only those its
// shading modes use) and runs the frame's passes. See DESIGN.md "One frame, as data flows".

#include "clip/clip_mesh_set.h"
#include "render/ambient_occlusion.h"
#include "render/frame.h"
#include "render/gl/context.h"
#include "render/gl/program.h"
#include "render/gl/timer.h"
#include "render/gpu_volume.h"
#include "render/image.h"
#include "render/slab_pass.h"
#include "render/tube_set.h"
#include "render/transfer_function_texture.h"

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace curette {

struct GpuAllocation {
    std::string name;    // e.g. "V (data volume)"
    std::string format;  // e.g. "R8"
    std::size_t bytes = 0;
};

class Renderer {
public:
    Renderer(gl::Context& context, const VolumeData& volume, const TransferFunction& tf);
    ~Renderer();

    void setTransferFunction(const TransferFunction& tf);
    // LAO settings for lao/cao shading; a change recomputes V_PAO on the next AO frame.
    void setLaoSettings(const LaoSettings& settings);
    const LaoSettings& laoSettings() const { return laoSettings_; }
    // The clip meshes; the app adds them and sets their poses between frames.
    clip::ClipMeshSet& clipMeshes() { return clip_; }
    const clip::ClipMeshSet& clipMeshes() const { return clip_; }
    // The AO pipeline, allocated at the first lao/cao frame (null before: a scene allocates what it uses).
    const AmbientOcclusion* ambientOcclusion() const { return ao_.get(); }
    const SlabPass& slabPass() const { return slab_; }
    // Tubes (or illuminated lines) in world millimetres; a scene with tubes renders through the G-buffer,
    // the slab pass and the compositor in every shading mode.
    void setTubes(const TubeVertices& vertices, const TubeShading& shading);
    void setTubeShading(const TubeShading& shading) { tubeShading_ = shading; }
    void clearTubes();
    bool hasTubes() const { return tubes_ != nullptr; }
    std::size_t tubeTriangleCount() const { return tubes_ ? tubes_->triangleCount() : 0; }
    const GBuffer& gbuffer() const { return gbuffer_; }
    // Whether the last frame ran steps IV and V (they run only when something they read changed).
    bool lastFrameUpdatedAmbient() const { return lastFrameUpdatedAmbient_; }
    const VolumeGeometry& geometry() const { return volume_.geometry(); }
    double resolveStepMm(const RaycastSettings& settings) const;

    // Runs the frame on the GPU; the result stays in outputTexture() until read.
    void render(const FrameDescription& frame);
    GLuint outputTexture() const { return output_.name(); }
    glm::ivec2 outputSize() const { return outputSize_; }
    Image readImage() const;

    // Count the volume samples the ray caster takes (for `bench`; slows the frame slightly when on).
    void setCountSamples(bool on) { countSamples_ = on; }
    std::uint64_t samplesLastFrame() const;

    // GPU time per pass of the frames rendered since the last call (milliseconds).
    std::vector<std::pair<std::string, double>> collectTimings() { return timers_.collectMilliseconds(); }
    // The ambient-occlusion share of a frame's timings (steps I, IV and V).
    static double ambientOcclusionMs(const std::vector<std::pair<std::string, double>>& timings);
    std::vector<GpuAllocation> gpuAllocations() const;

private:
    gl::Program& raycastProgram(ShadingMode mode);
    void updateOccupancy();
    void ensureOutput(glm::ivec2 size);

    void updateAmbientOcclusion(ShadingMode mode);

    gl::Context& context_;
    GpuVolume volume_;
    std::unique_ptr<TransferFunctionTexture> tf_;
    std::uint64_t tfVersion_ = 0;
    clip::ClipMeshSet clip_;
    LaoSettings laoSettings_;
    std::unique_ptr<AmbientOcclusion> ao_;
    // What V_AO was last computed from (steps IV-V rerun only when one of these changes).
    std::uint64_t aoClipVersion_ = 0, aoTfVersion_ = 0;
    ShadingMode aoMode_ = ShadingMode::Solid;
    bool aoValid_ = false, aoPrecomputedValid_ = false, lastFrameUpdatedAmbient_ = false;
    gl::Texture occupancy_;
    gl::Texture output_;
    glm::ivec2 outputSize_{0};
    gl::Buffer sampleCounter_;
    bool countSamples_ = false;
    gl::ComputeVariants raycastPrograms_{"raycast.comp"};
    gl::TimerSet timers_;
    SlabPass slab_;
    bool slabUsed_ = false;
    std::unique_ptr<TubeSet> tubes_;
    TubeShading tubeShading_;
    GBuffer gbuffer_;
    gl::Program compositeProgram_;
    gl::Buffer poissonDisk_;
    int poissonCount_ = 0;
    void renderWithTubes(const FrameDescription& frame);
};

}  // namespace curette
