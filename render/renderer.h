#pragma once
// The renderer of one scene: it owns the GPU resources the scene needs (allocated when a pass first needs
// them, only those its shading modes use) and runs each frame as the plan of passes render/model/frame_plan.h
// makes from the frame, what the scene has and what is up to date (docs/architecture.md, "The frame and its plan").

#include "render/passes/clip_mesh_set.h"
#include "render/frame_run.h"
#include "gl/context.h"
#include "gl/program.h"
#include "gl/timer.h"
#include "render/passes/ambient_occlusion.h"
#include "render/model/frame.h"
#include "render/model/frame_plan.h"
#include "render/model/gpu_resources.h"
#include "render/gpu_volume.h"
#include "render/gradient_volume.h"
#include "render/model/image.h"
#include "render/model/phong_shading_placement.h"
#include "render/passes/ismos_pass.h"
#include "render/recast_region.h"
#include "render/shader_pieces.h"
#include "render/passes/slab_pass.h"
#include "render/transfer_function_texture.h"
#include "render/model/tube_geometry.h"
#include "render/passes/tube_set.h"

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
    // The drill's accumulated removal (plan/removal_volume.h; null: none): classification keeps (1 - drilled
    // fraction) of each sample, step IV of each voxel. An input of V_o and V_AO (a change reruns IV and V over
    // the bricks it reaches), not of V_PAO. The renderer reads it at each frame's start; it must stay alive.
    // A scene compiles the drill into its shaders from the first frame the removal is not empty.
    void setRemoval(std::shared_ptr<const plan::RemovalVolume> removal);
    const plan::RemovalVolume* removal() const { return removal_.get(); }
    // LAO settings for lao/cao shading; a change recomputes V_PAO on the next AO frame.
    void setLaoSettings(const LaoSettings& settings);
    const LaoSettings& laoSettings() const { return laoSettings_; }
    // The clip meshes; the session step (session/session_step.h) makes them match the interaction state.
    clip::ClipMeshSet& clipMeshes() { return clip_; }
    const clip::ClipMeshSet& clipMeshes() const { return clip_; }
    // The AO pipeline, allocated at the first lao/cao frame (null before: a scene allocates what it uses).
    const AmbientOcclusion* ambientOcclusion() const { return ao_.get(); }
    const SlabPass& slabPass() const { return slab_; }
    // The ISMOS passes' state (layers, light samples), allocated at the first ismos frame (null before).
    const IsmosPass* ismos() const { return ismos_.get(); }
    IsmosPass* ismos() { return ismos_.get(); }
    // The frame's ISMOS texture-space box (render/model/ismos_model.h).
    IsmosSpace ismosSpaceOf(const FrameDescription& frame) const;
    // Tubes (or illuminated lines) in world millimetres; a scene with tubes in view renders through the
    // G-buffer, the slab pass and the compositor in every shading mode.
    void setTubes(const TubeVertices& vertices, const TubeShading& shading);
    // Tubes expanded from their swept rings on the GPU (render/passes/gpu_tube_builder.h): setTubes(expandTubeRings(
    // rings)) within float rounding, with no vertex stream on the CPU.
    void setTubeRings(const TubeRings& rings, const TubeShading& shading);
    // Impostor tubes (render/model/tube_impostors.h): only the swept points go to the GPU.
    void setTubeImpostors(const TubeImpostors& impostors, const TubeShading& shading);
    const TubeSet* tubes() const { return tubes_.get(); }
    void setTubeShading(const TubeShading& shading);
    void clearTubes();
    bool hasTubes() const { return tubes_ != nullptr; }
    std::size_t tubeTriangleCount() const { return tubes_ ? tubes_->triangleCount() : 0; }
    const GBuffer& gbuffer() const { return gbuffer_; }
    const VolumeGeometry& geometry() const { return volume_.geometry(); }
    const VolumeLayout& volumeLayout() const { return volume_.layout(); }   // how its textures store the voxels
    double resolveStepMm(const RaycastSettings& settings) const;

    // The passes render(frame) would run now, in order, with what each reads and writes.
    FramePlan plan(const FrameDescription& frame) const;
    const FramePlan& lastPlan() const { return lastPlan_; }
    // Whether the last frame ran steps IV and V (they run only when something they read changed).
    bool lastFrameUpdatedAmbient() const { return lastPlan_.runs(Pass::LaoRecompute); }
    // Whether the image in outputTexture() is already `frame` under the current scene (nothing to render).
    bool showing(const FrameDescription& frame) const;

    // Runs the frame's plan on the GPU; the result stays in outputTexture() until read. The exact frame: what
    // `curette render` gives for this state, bit for bit, whatever previews came before.
    void render(const FrameDescription& frame);

    // Preview and exact frames (docs/architecture.md, "Preview and exact frames"): what a viewer shows while
    // something moves or while step I runs, at whatever size it asks.
    using PreviewAmbient = curette::PreviewAmbient;   // render/frame_run.h
    // The frame's plan without steps I, IV and V: the clip maps (the frame's own, as the exact frame would draw
    // them) and the image passes, shading with `previewAmbient()`. A preview never runs the slab pass (seconds
    // on a software renderer even at a preview's size): dos previews as phong, and tubes are left out of the
    // preview (their G-buffer costs its triangles at any size; ismos keeps them). It writes the output image and nothing any
    // exact frame reads, so the next render() is unchanged by it (Preview.NeverChangesTheExactFrame).
    void renderPreview(const FrameDescription& frame);
    PreviewAmbient previewAmbient() const;
    // The exact frame in slices, for a viewer that keeps presenting while it is computed: each call runs the
    // next part of render(frame)'s plan for about budgetMs of wall time (at least one slice) and returns true
    // once the frame is done. Then showing(frame) holds and the image shown is render(frame)'s, bit for bit;
    // until then the image shown stays the last one (previews have their own image). Step IV runs in slices of
    // its bricks (AmbientOcclusion::advanceClipVoxels), step V in slices of its recompute list
    // (AmbientOcclusion::advanceRecompute), the ray cast in parts of bands of tile rows
    // (TileOrderPiece::dispatchParts), the tube G-buffer in index ranges, the slab pass in its view-aligned
    // slices (SlabPass::advance), the composite in bands of rows, every other pass whole. A call for another frame, or after the scene
    // changed or a preview was drawn, starts over; a step IV or V under way is abandoned, and the next update visits
    // the bricks its step IV visited as well as its own (AmbientOcclusion::abandonUpdate), so it rewrites
    // whatever the abandoned one left stale (render() does the same). sliceUnits > 0 fixes the slice size (step
    // IV: its work units, AmbientOcclusion::beginClipVoxels; step V: work groups of the list; the ray cast: parts;
    // the slab pass: slices), for tests.
    bool advanceExact(const FrameDescription& frame, double budgetMs, std::uint32_t sliceUnits = 0);
    // How far the exact frame in slices is, in [0, 1] (passes done, the sliced ones by their share done; 0 when
    // none is under way), and what its pass under way computes, in a planner's words (PassInfo::activity: "shadows
    // (directional occlusion)", "full-quality image"; empty when none is under way).
    double exactProgress() const;
    const char* exactProgressLabel() const;
    // Whether the image shown is a preview of `frame` under the current scene (showing() is for exact ones).
    bool showingPreview(const FrameDescription& frame) const;
    // The size of the preview shown (none when the image shown is exact, or there is none).
    std::optional<glm::ivec2> shownPreviewSize() const;
    bool lastFrameExact() const { return shown_ && shown_->exact; }
    // Whether any image is shown yet (none before the first frame, exact or preview, is done).
    bool showsAnImage() const { return shown_.has_value(); }
    // Step I in slices: whether `frame` needs V_PAO and it is not for the current volume, TF and LAO settings;
    // then advancePrecompute(budget) runs slices of it (AmbientOcclusion::advancePrecompute) for about budgetMs
    // of GPU time (at least one slice; it waits for the GPU to time them, and sizes the next slice from the
    // last one's rate) and returns how far step I is, in [0, 1]. At 1 V_PAO is current and the next exact frame
    // runs no step I; an exact frame before that finishes the remaining slices itself.
    bool precomputePending(const FrameDescription& frame) const;
    // sliceBricks > 0 fixes the slice size instead (tests: slices that are neither rows nor slabs of bricks).
    double advancePrecompute(double budgetMs, std::uint32_t sliceBricks = 0);
    double precomputeProgress() const;
    // What step I computes, in a planner's words ("occlusion of the scan"; PassInfo::activity).
    static const char* precomputeProgressLabel() { return passInfo(Pass::LaoPrecompute).activity; }
    // The label field in slices (LabelOverlay::advanceField): the viewer runs it before it draws, so a new scene or
    // a label style edit never freezes the window; a frame that binds the labels finishes whatever is left, so
    // the image does not depend on it. advanceLabelField returns how far the field is, in [0, 1].
    bool labelFieldPending() const;
    double advanceLabelField(double budgetMs, int planesPerSlice = 0);
    double labelFieldProgress() const;
    static const char* labelFieldProgressLabel() { return "the labels' surfaces"; }
    // Steps II-III a mesh at a time (ClipMeshSet::update): how many meshes' clip maps `frame` still needs drawn,
    // and drawing the next one's; a frame draws whatever is left.
    int clipMapsToDraw(const FrameDescription& frame) const;
    void advanceClipMaps(const FrameDescription& frame);
    static const char* clipMapsProgressLabel() { return passInfo(Pass::ClipMaps).activity; }
    // A number that changes whenever step I's inputs (volume, TF and labels, LAO settings) change: the frame loop
    // holds step I back while they are being edited (viewer/view_frame_loop.h).
    std::uint64_t precomputeInputsVersion() const { return versions_.volume + versions_.transferFunction + versions_.laoSettings; }
    // Waits until the GPU has finished every pass submitted so far (for wall-clock timing).
    void finish() const;
    // The image shown: the last exact frame or preview (a preview is kept in an image of its own).
    GLuint outputTexture() const { return images_[shownImageIndex()].texture.name(); }
    glm::ivec2 outputSize() const { return images_[shownImageIndex()].size; }
    Image readImage() const;

    // Count the volume samples the ray caster takes (for `bench`; slows the frame slightly when on).
    void setCountSamples(bool on) { countSamples_ = on; }
    std::uint64_t samplesLastFrame() const;
    // ... and the steps of the rays' loops (a sample taken, or a jump over empty bricks).
    std::uint64_t rayStepsLastFrame() const;
    // The most bricks (Chebyshev radius) one empty-space jump may cross: 255 (the distance map's cap) by
    // default; 1 jumps one empty brick at a time (as before the distance map; for `bench` and tests).
    void setEmptySpaceJumpLimit(int bricks) { emptySpaceJumpLimit_ = bricks; }
    // ... and of the groups in the first and the second half of the ray caster's dispatch, which is how two
    // llvmpipe worker threads share it (shaders/tile_order.glsl): their ratio is the frame's thread balance.
    glm::dvec2 rayStepsByDispatchHalf() const;
    // The ray caster's tile order (render/shader_pieces.h TileOrderPiece): rows per band, 1 = scanline order.
    void setTileRowsPerBand(int rows) { tileRowsPerBand_ = rows; }
    // Where the ray cast shades phong's visible samples (render/model/phong_shading_placement.h): chosen from
    // the TF and the volume's values unless set here (for `bench` and tests; the image is the same either way).
    void setPhongShading(std::optional<PhongShading> placement) { phongShadingOverride_ = placement; }
    PhongShading phongShading(const FrameDescription& frame) const;
    // Whether phong reads its gradients from the gradient volume where the scan has one (render/gradient_volume.h;
    // on by default); off takes the six reads (for `bench` and tests).
    void setGradientVolume(bool on) { gradientVolumeOn_ = on; }
    bool gradientVolumeSupported() const { return GradientVolume::supports(volume_); }
    // Whether an exact frame after rigid motions of clip meshes alone casts only the pixels they can change and
    // keeps the others of the last exact image (render/recast_region.h; on by default, the image is the same bit
    // for bit); off casts every pixel (for `bench` and tests).
    void setRecastOnlyChangedPixels(bool on) { recastOnlyChanged_ = on; }
    // The share of the image the last exact frame's ray cast covered (1: all of it; 0: it kept every pixel).
    double lastRecastShare() const { return lastRecastShare_; }

    // Whether every frame records which resources each pass's programs really bind (the GL's introspection of
    // the programs it used, render/pass_bindings.h); lastPassBindings() holds the image shown's, in plan order.
    // For the test that holds the passes' declared reads and writes against them.
    void setAuditBindings(bool on) { auditBindings_ = on; }
    const std::vector<BoundResources>& lastPassBindings() const { return lastPassBindings_; }

    // Time per pass of the frames rendered since the last call.
    FrameTimings collectTimings();
    // Every GPU resource allocated now, named by the descriptor table (render/model/gpu_resources.h).
    std::vector<GpuAllocation> gpuAllocations() const;

private:
    PlanInputs planInputs(const FrameDescription& frame) const;
    // The versions of everything V_PAO and V_AO are computed from; the clip meshes' from the set itself.
    InputVersions currentVersions() const;
    ImageStamp stampOf(const FrameDescription& frame) const { return {frame, currentVersions(), appearanceVersion_}; }
    // Whether this frame wants the dilated maps (ShadingModeTraits::dilatedMaps in the AO modes; the other modes
    // keep what is drawn).
    bool dilatedMapsWanted(ShadingMode mode) const;
    bool tubesInView(const FrameDescription& frame) const;

    // The one executor (render/frame_run.h). beginRun plans an exact frame or a preview; execute runs its passes
    // from the run's context, each whole (budgetMs < 0) or as the next slice of it, and returns true once every
    // pass is done; finishRun shows its image.
    FrameRun beginRun(const FrameDescription& frame, bool exact);
    bool execute(FrameRun& run, double budgetMs, std::uint32_t sliceUnits = 0);
    void finishRun(const FrameRun& run);
    PassContext contextOf(FrameRun& run);
    // One pass, whole; or its next slice (step IV, step V and the ray cast have slices; the others run whole).
    // Both return whether the pass is done.
    bool runWhole(Pass pass, const PassContext& context, FrameRun& run);
    bool runSlice(Pass pass, const PassContext& context, FrameRun& run, double budgetMs, std::uint32_t sliceUnits);
    bool stepIVSlice(FrameRun& run, double budgetMs, std::uint32_t sliceUnits);
    bool stepVSlice(FrameRun& run, double budgetMs, std::uint32_t sliceUnits);
    bool rayCastSlice(const PassContext& context, FrameRun& run, double budgetMs, std::uint32_t sliceUnits);
    bool tubeGBufferSlice(const PassContext& context, FrameRun& run, double budgetMs, std::uint32_t sliceUnits);
    bool slabSlice(const PassContext& context, FrameRun& run, double budgetMs, std::uint32_t sliceUnits);
    void beginStepIV(FrameRun& run);
    void finishStepV(const FrameRun& run);
    // The ray cast of the context's frame: the whole image, or (bandCount >= 0) its bands [firstBand, firstBand +
    // bandCount) of tile rows; returns the image's number of bands.
    int runRayCast(const PassContext& context, bool ismosLayers, int firstPart = 0, int partCount = -1);
    void runSlabPass(const PassContext& context);
    SlabInputs slabInputs(const PassContext& context);
    // The composite over rows [firstRow, firstRow + rows) (all: the whole image). Each pixel reads only the G-buffer
    // and its own image pixel, so bands give one dispatch's image.
    void runComposite(const PassContext& context, int firstRow = 0, int rows = -1);
    bool compositeSlice(const PassContext& context, FrameRun& run, double budgetMs, std::uint32_t sliceUnits);
    // The pixels the exact frame `frame` with plan `plan` must cast (none: all of them): those the meshes' motion
    // since the last exact image can change, when nothing else changed (render/recast_region.h).
    std::optional<PixelRegion> recastRegion(const FrameDescription& frame, const FramePlan& plan) const;
    // Called as an exact run starts writing the exact image: from then on it is no longer the last one's.
    void beginExactImage(FrameRun& run);
    // The exact frame in slices is given up: if its step IV ran and its step V is unfinished, step V is abandoned
    // (AmbientOcclusion::abandonUpdate), and the next exact frame's IV and V visit this one's bricks too.
    void abandonExactJob();
    bool exactJobCurrent(const FrameDescription& frame) const;
    std::optional<FrameRun> exactJob_;
    bool auditBindings_ = false;
    std::vector<BoundResources> lastPassBindings_;
    void recordBindings(FrameRun& run, Pass pass, const std::vector<GLuint>& programs) const;
    std::uint64_t previewsRendered_ = 0;
    SliceSizer stepIVSizer_{SliceSizer::Rate::Last}, stepVSizer_{SliceSizer::Rate::Last}, rayCastSizer_{SliceSizer::Rate::Last},
        slabSizer_{SliceSizer::Rate::Last}, tubeSizer_{SliceSizer::Rate::Last},
        compositeSizer_{SliceSizer::Rate::Last};
    SliceSizer precomputeSizers_[2] = {SliceSizer{SliceSizer::Rate::Slowest}, SliceSizer{SliceSizer::Rate::Slowest}};   // step I's phases
    void validateSize(const FrameDescription& frame) const;
    void updateOccupancy();
    void updateSeenBricks();
    std::unique_ptr<AmbientOcclusion> makeAmbientOcclusion();   // and the seen bricks it reads, made with the first one
    void ensureOutput(int image, glm::ivec2 size);

    gl::Context& context_;
    GpuVolume volume_;
    ValueHistogram valueHistogram_;            // of the volume's values, for phongShading()
    std::unique_ptr<TransferFunctionTexture> tf_;
    double medianExtinctionPerMm_ = 0;         // the TF's over the histogram's visible voxels
    std::optional<PhongShading> phongShadingOverride_;
    std::unique_ptr<LabelOverlay> labels_;
    std::shared_ptr<const plan::RemovalVolume> removal_;
    std::unique_ptr<RemovalTexture> removalTexture_;   // made at the first frame with a non-empty removal
    void syncRemoval();   // brings the texture to the removal's version (Renderer::beginRun)
    clip::ClipMeshSet clip_;
    LaoSettings laoSettings_;
    std::unique_ptr<AmbientOcclusion> ao_;
    InputVersions versions_;         // volume, classification (TF and labels) and LAO settings (clipMeshes
                                     // unused: see currentVersions)
    Freshness freshness_;            // what V_PAO and V_AO were computed from
    // Inputs of the image that no AO product depends on (tubes, tube shading, the ambient scale): with the
    // frame and currentVersions(), what showing() compares.
    std::uint64_t appearanceVersion_ = 1;
    FramePlan lastPlan_;             // the plan of the image shown
    // The image shown: which one, what it shows, and for a preview its ambient source.
    struct ShownImage {
        ImageStamp stamp;
        bool exact = false;
        PreviewAmbient ambient = PreviewAmbient::None;
    };
    std::optional<ShownImage> shown_;
    int shownImageIndex() const { return shown_ && !shown_->exact ? kPreviewImage : kExactImage; }
    // The exact image (images_[kExactImage]) as the last exact frame left it, and what it was rendered from:
    // none while an exact frame is writing it, or before the first.
    struct ExactImage {
        ImageStamp stamp;
        ClipSnapshot clip;
        glm::ivec3 diagnostics{0};
        bool drillCompiled = false;   // the drilled removal was in the shaders (Renderer::syncRemoval)
    };
    // The settings that change what a frame counts or how it is dispatched, not its image: a frame after one of
    // them changed casts every pixel, so what it counts is the whole image's.
    glm::ivec3 diagnostics() const { return {countSamples_ ? 1 : 0, emptySpaceJumpLimit_, tileRowsPerBand_}; }
    std::optional<ExactImage> exactImage_;
    bool recastOnlyChanged_ = true;
    double lastRecastShare_ = 1.0;
    bool ambientWritten_ = false;                // V_AO written (step V) since the current V_PAO's step I
    std::optional<InputVersions> slicingFor_;    // the inputs the step I in slices is computing V_PAO for
    gl::Texture occupancy_;
    // Per brick of GpuVolume::seenBrickSize: 0 where a sample may have opacity, else 255; steps I and V cast
    // LAO rays only in bricks marked 0 (LaoSettings::onlyWhereSeen).
    gl::Texture seenBricks_;
    struct OutputImage {
        gl::Texture texture;
        glm::ivec2 size{0};
    };
    static constexpr int kExactImage = 0, kPreviewImage = 1;
    OutputImage images_[2];          // exact frames (render, advanceExact) and previews (renderPreview)
    gl::Buffer sampleCounter_;
    bool countSamples_ = false;
    int emptySpaceJumpLimit_ = 255;
    int tileRowsPerBand_ = TileOrderPiece::defaultRowsPerBand();
    gl::ComputeVariants raycastPrograms_{"raycast.comp"};
    GradientVolume gradients_;
    bool gradientVolumeOn_ = true;
    gl::TimerSet timers_;
    SlabPass slab_;
    bool slabUsed_ = false;
    std::unique_ptr<TubeSet> tubes_;
    TubeShading tubeShading_;
    GBuffer gbuffer_;
    gl::ComputeVariants compositePrograms_{"tube_composite.comp"};   // by light count
    gl::Buffer poissonDisk_;
    std::unique_ptr<IsmosPass> ismos_;
    int poissonCount_ = 0;
};

}  // namespace curette
