#pragma once
// The renderer of one scene: it owns the GPU resources the scene needs (allocated when a pass first needs
// them, only those its shading modes use) and runs each frame as the plan of passes render/frame_plan.h
// makes from the frame, what the scene has and what is up to date (docs/architecture.md, "The frame plan").

#include "clip/clip_mesh_set.h"
#include "gl/context.h"
#include "gl/program.h"
#include "gl/timer.h"
#include "render/ambient_occlusion.h"
#include "render/frame.h"
#include "render/frame_plan.h"
#include "render/gpu_resources.h"
#include "render/gpu_volume.h"
#include "render/image.h"
#include "render/ismos_pass.h"
#include "render/slab_pass.h"
#include "render/transfer_function_texture.h"
#include "render/tube_geometry.h"
#include "render/tube_set.h"

#include <memory>
#include <optional>
#include <vector>

namespace curette {

class Renderer {
public:
    Renderer(gl::Context& context, const VolumeData& volume, const TransferFunction& tf);
    ~Renderer();

    void setTransferFunction(const TransferFunction& tf);
    // Label volumes in the classification (shaders/labels.glsl): ids on the scan grid and a style per id.
    // Like the TF, they are inputs of V_PAO and V_AO (the AO modes see the labels' opacity).
    void setLabels(std::unique_ptr<LabelOverlay> labels);
    void setLabelStyles(const std::vector<glm::vec4>& styles);
    const LabelOverlay* labels() const { return labels_.get(); }
    // LAO settings for lao/cao shading; a change recomputes V_PAO on the next AO frame.
    void setLaoSettings(const LaoSettings& settings);
    const LaoSettings& laoSettings() const { return laoSettings_; }
    // The clip meshes; the session step (app/session_step.h) makes them match the interaction state.
    clip::ClipMeshSet& clipMeshes() { return clip_; }
    const clip::ClipMeshSet& clipMeshes() const { return clip_; }
    // The AO pipeline, allocated at the first lao/cao frame (null before: a scene allocates what it uses).
    const AmbientOcclusion* ambientOcclusion() const { return ao_.get(); }
    const SlabPass& slabPass() const { return slab_; }
    // The ISMOS passes' state (layers, light samples), allocated at the first ismos frame (null before).
    const IsmosPass* ismos() const { return ismos_.get(); }
    IsmosPass* ismos() { return ismos_.get(); }
    // The frame's ISMOS texture-space box (render/ismos_model.h).
    IsmosSpace ismosSpaceOf(const FrameDescription& frame) const;
    // Tubes (or illuminated lines) in world millimetres; a scene with tubes in view renders through the
    // G-buffer, the slab pass and the compositor in every shading mode.
    void setTubes(const TubeVertices& vertices, const TubeShading& shading);
    // Tubes expanded from their swept rings on the GPU (render/gpu_tube_builder.h): setTubes(expandTubeRings(
    // rings)) within float rounding, with no vertex stream on the CPU.
    void setTubeRings(const TubeRings& rings, const TubeShading& shading);
    const TubeSet* tubes() const { return tubes_.get(); }
    void setTubeShading(const TubeShading& shading);
    void clearTubes();
    bool hasTubes() const { return tubes_ != nullptr; }
    std::size_t tubeTriangleCount() const { return tubes_ ? tubes_->triangleCount() : 0; }
    const GBuffer& gbuffer() const { return gbuffer_; }
    const VolumeGeometry& geometry() const { return volume_.geometry(); }
    double resolveStepMm(const RaycastSettings& settings) const;

    // The passes render(frame) would run now, in order, with what each reads and writes.
    FramePlan plan(const FrameDescription& frame) const;
    const FramePlan& lastPlan() const { return lastPlan_; }
    // Whether the last frame ran steps IV and V (they run only when something they read changed).
    bool lastFrameUpdatedAmbient() const { return lastPlan_.runs(Pass::LaoRecompute); }
    // Whether the image in outputTexture() is already `frame` under the current scene (nothing to render).
    bool showing(const FrameDescription& frame) const;

    // Runs the frame's plan on the GPU; the result stays in outputTexture() until read.
    void render(const FrameDescription& frame);
    // Waits until the GPU has finished every pass submitted so far (for wall-clock timing).
    void finish() const;
    GLuint outputTexture() const { return output_.name(); }
    glm::ivec2 outputSize() const { return outputSize_; }
    Image readImage() const;

    // Count the volume samples the ray caster takes (for `bench`; slows the frame slightly when on).
    void setCountSamples(bool on) { countSamples_ = on; }
    std::uint64_t samplesLastFrame() const;

    // Time per pass of the frames rendered since the last call.
    FrameTimings collectTimings();
    // Every GPU resource allocated now, named by the descriptor table (render/gpu_resources.h).
    std::vector<GpuAllocation> gpuAllocations() const;

private:
    PlanInputs planInputs(const FrameDescription& frame) const;
    // The versions of everything V_PAO and V_AO are computed from; the clip meshes' from the set itself.
    InputVersions currentVersions() const;
    // Whether this frame wants the dilated maps: cao does; lao does not; the other modes keep what is drawn.
    bool dilatedMapsWanted(ShadingMode mode) const;
    bool tubesInView(const FrameDescription& frame) const;
    void run(Pass pass, const FrameDescription& frame);
    void runRayCast(const FrameDescription& frame, bool ismosLayers = false);
    void runSlabPass(const FrameDescription& frame, bool withTubes);
    void runComposite(const FrameDescription& frame);
    void updateOccupancy();
    void ensureOutput(glm::ivec2 size);

    gl::Context& context_;
    GpuVolume volume_;
    std::unique_ptr<TransferFunctionTexture> tf_;
    std::unique_ptr<LabelOverlay> labels_;
    clip::ClipMeshSet clip_;
    LaoSettings laoSettings_;
    std::unique_ptr<AmbientOcclusion> ao_;
    InputVersions versions_;         // volume, classification (TF and labels) and LAO settings (clipMeshes
                                     // unused: see currentVersions)
    Freshness freshness_;            // what V_PAO and V_AO were computed from
    // Inputs of the image that no AO product depends on (tubes, tube shading, the ambient scale): with the
    // frame and currentVersions(), what showing() compares.
    std::uint64_t appearanceVersion_ = 1;
    FramePlan lastPlan_;
    std::optional<FrameDescription> shownFrame_;
    InputVersions shownVersions_;
    std::uint64_t shownAppearanceVersion_ = 0;
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
    std::unique_ptr<IsmosPass> ismos_;
    int poissonCount_ = 0;
};

}  // namespace curette
