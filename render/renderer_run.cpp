// The renderer's one executor (render/frame_run.h): exact frames, previews and exact frames in slices run the
// same loop over their plan's passes, each pass from its run's context.
#include "render/renderer.h"

#include "base/error.h"
#include "gl/bindings.h"
#include "render/lighting.h"
#include "render/shader_pieces.h"

#include <algorithm>
#include <chrono>

namespace curette {

namespace {
using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point start) { return std::chrono::duration<double, std::milli>(Clock::now() - start).count(); }

bool writesImage(Pass pass) {
    const std::vector<Resource>& writes = passInfo(pass).writes;
    return std::find(writes.begin(), writes.end(), Resource::OutputImage) != writes.end();
}

// A unit of the tube G-buffer in slices: this many triangles (or line segments), drawn in index order.
constexpr std::size_t kTubePrimitivesPerUnit = 16384;
std::int64_t tubeUnits(std::size_t primitives) {
    return static_cast<std::int64_t>((primitives + kTubePrimitivesPerUnit - 1) / kTubePrimitivesPerUnit);
}

// A unit of the composite in slices: a band of this many rows (eight work-group rows).
constexpr int kCompositeRowsPerUnit = 64;

// Runs `n` units of a sliced pass with `run`, waits for the GPU and tells the sizer how long they took.
template <typename Run>
void timedSlice(SliceSizer& sizer, std::uint32_t n, Run run) {
    auto start = Clock::now();
    run(n);
    glFinish();
    sizer.measured(n, msSince(start));
}
}  // namespace

// ---- What the image shown is ----

bool Renderer::showing(const FrameDescription& frame) const { return shown_ && shown_->exact && shown_->stamp == stampOf(frame); }

bool Renderer::showingPreview(const FrameDescription& frame) const {
    return shown_ && !shown_->exact && shown_->stamp == stampOf(frame) && shown_->ambient == previewAmbient();
}

std::optional<glm::ivec2> Renderer::shownPreviewSize() const {
    if (!shown_ || shown_->exact) return std::nullopt;
    return shown_->stamp.frame.size;
}

bool Renderer::exactJobCurrent(const FrameDescription& frame) const {
    return exactJob_ && exactJob_->stamp == stampOf(frame) && exactJob_->previews == previewsRendered_;
}

Renderer::PreviewAmbient Renderer::previewAmbient() const {
    if (!ao_ || !freshness_.precomputedCurrent(currentVersions())) return PreviewAmbient::None;
    return ambientWritten_ ? PreviewAmbient::LastExact : PreviewAmbient::Precomputed;
}

std::optional<PixelRegion> Renderer::recastRegion(const FrameDescription& frame, const FramePlan& plan) const {
    if (!recastOnlyChanged_ || !exactImage_ || exactImage_->stamp.frame != frame || exactImage_->stamp.appearance != appearanceVersion_ ||
        exactImage_->diagnostics != diagnostics())
        return std::nullopt;
    InputVersions now = currentVersions(), before = exactImage_->stamp.versions;
    before.clipMeshes = now.clipMeshes;
    // Drilling since: the voxels it changed are known (the removal's brick versions), so is how far their change
    // reaches; but a first drilled frame compiles the drill into the shaders, and then every pixel is cast.
    const std::uint64_t removalBefore = before.removal;
    bool drilled = removalBefore != now.removal;
    if (drilled && !(removalTexture_ && exactImage_->drillCompiled)) return std::nullopt;
    before.removal = now.removal;
    if (!(before == now)) return std::nullopt;
    // The ray cast must be the only image pass (tubes in dos bring the slab pass and the compositor), the maps
    // not drawn again (a rigid motion only moves their cameras), and no tubes in view (the region is argued for
    // the volume's samples alone: docs/subsystems.md, "Pixels an exact frame casts again").
    for (const PlannedPass& p : plan.passes)
        if (p.pass == Pass::ClipMaps || p.pass == Pass::TubeGBuffer || (writesImage(p.pass) && p.pass != Pass::RayCast)) return std::nullopt;
    auto boxes = changedRegions(exactImage_->clip, ClipSnapshot::of(clip_, volume_.geometry().cellDiagonalMm()),
                                traits(frame.shading).ambientOcclusion);
    if (boxes && drilled) {
        // A sample reads the drilled fraction trilinearly, within a cell diagonal of a changed voxel; V_AO changes
        // within R of one (the contract) and a sample reads it within a cell diagonal more.
        const double cell = volume_.geometry().cellDiagonalMm();
        double grow = cell + (traits(frame.shading).ambientOcclusion ? AmbientOcclusion::dilationRadiusMm(laoSettings_, volume_.geometry()) + cell : 0.0);
        if (std::optional<ChangedRegion> r = drilledRegion(*removal_, removalBefore, grow)) boxes->push_back(*r);
    }
    // No mesh moved: render() of an unchanged state is asked for on purpose (benchmarks time it), so it runs whole.
    if (!boxes || boxes->empty()) return std::nullopt;
    return pixelsMeeting(*boxes, frame);
}

// ---- The three ways in ----

void Renderer::render(const FrameDescription& frame) {
    validateSize(frame);
    abandonExactJob();
    FrameRun run = beginRun(frame, true);
    execute(run, -1.0);
    finishRun(run);
}

void Renderer::renderPreview(const FrameDescription& frame) {
    validateSize(frame);
    // Previews have their own image, so an exact frame in slices (advanceExact) is not drawn over.
    ++previewsRendered_;
    FrameRun run = beginRun(frame, false);
    execute(run, -1.0);
    finishRun(run);
}

bool Renderer::advanceExact(const FrameDescription& frame, double budgetMs, std::uint32_t sliceUnits) {
    validateSize(frame);
    if (exactJob_ && !exactJobCurrent(frame)) abandonExactJob();
    if (!exactJob_ && showing(frame)) return true;
    if (!exactJob_) exactJob_ = beginRun(frame, true);
    bool done = execute(*exactJob_, std::max(budgetMs, 0.0), sliceUnits);
    exactJob_->stamp = stampOf(frame);
    exactJob_->previews = previewsRendered_;
    if (!done) return false;
    finishRun(*exactJob_);
    exactJob_.reset();
    return true;
}

double Renderer::exactProgress() const {
    if (!exactJob_ || exactJob_->plan.passes.empty()) return 0.0;
    const FrameRun& job = *exactJob_;
    double within = 0;
    if (job.next < job.plan.passes.size()) {
        Pass pass = job.plan.passes[job.next].pass;
        if (pass == Pass::VoxelClipping && job.stepIVBegun && job.stepIVUnits > 0)
            within = 1.0 - double(ao_->clipUnitsLeft()) / job.stepIVUnits;
        if (pass == Pass::LaoRecompute && job.stepVBegun && job.stepVGroups > 0)
            within = 1.0 - double(ao_->recomputeGroupsLeft()) / job.stepVGroups;
        if (pass == Pass::RayCast && job.parts > 0) within = double(job.partsDone) / job.parts;
        if (pass == Pass::Composite && job.frame.size.y > 0) within = double(job.compositeRowsDone) / job.frame.size.y;
        if (pass == Pass::TubeGBuffer && job.tubeUnitsDone > 0 && tubes_) {
            within = std::min(1.0, double(job.tubeUnitsDone) / double(std::max<std::int64_t>(tubeUnits(tubes_->primitiveCount()), 1)));
        }
        if (pass == Pass::SlabPass && job.slab && job.slab->units() > 0) within = 1.0 - double(job.slab->left()) / double(job.slab->units());
    }
    return (double(job.next) + within) / double(job.plan.passes.size());
}

const char* Renderer::exactProgressLabel() const {
    if (!exactJob_ || exactJob_->next >= exactJob_->plan.passes.size()) return "";
    return passInfo(exactJob_->plan.passes[exactJob_->next].pass).activity;
}

// ---- The executor ----

FrameRun Renderer::beginRun(const FrameDescription& frame, bool exact) {
    syncRemoval();
    FrameRun run{.frame = frame, .shaded = frame, .exact = exact, .stamp = stampOf(frame), .previews = previewsRendered_};
    if (exact) {
        run.plan = plan(frame);
        for (SliceSizer* sizer : {&stepIVSizer_, &stepVSizer_, &rayCastSizer_, &slabSizer_, &tubeSizer_, &compositeSizer_}) sizer->newRun();
    } else {
        // A preview is the frame's plan without steps I, IV and V, shading with previewAmbient()'s volume, or
        // phong while V_PAO is not there. Its clip maps are the frame's own (cao wants the dilated ones), exactly as
        // the exact frame would draw them.
        run.ambient = previewAmbient();
        PlanInputs inputs = planInputs(frame);
        if (traits(frame.shading).ambientOcclusion) {
            inputs.precomputedCurrent = inputs.ambientCurrent = true;
            if (run.ambient == PreviewAmbient::None) run.shaded.shading = inputs.shading = ShadingMode::Phong;
        }
        // No slab pass in a preview: it marches every view-aligned slice over every pixel, seconds at any preview
        // size on a software renderer. dos previews as phong does. Tubes are left out but in ismos: the G-buffer
        // costs what its triangles cost at any preview size (a whole-brain set, seconds), so the preview would
        // not keep up with a motion.
        if (traits(inputs.shading).slabPass) run.shaded.shading = inputs.shading = ShadingMode::Phong;
        if (inputs.shading != ShadingMode::Ismos) inputs.tubesInView = false;
        run.plan = planFrame(inputs);
    }
    ensureOutput(exact ? kExactImage : kPreviewImage, frame.size);
    // A rigid motion changes only the clipping cameras: upload them when the maps are not redrawn anyway.
    if (!run.plan.runs(Pass::ClipMaps)) clip_.uploadCameras();
    if (exact)
        if (std::optional<PixelRegion> region = recastRegion(frame, run.plan)) run.recast = RecastTiles{std::move(*region), {}, {}};
    return run;
}

PassContext Renderer::contextOf(FrameRun& run) {
    // The ambient volume is looked up per pass: step I makes the AO pipeline within the run.
    GLuint ambient = 0;
    if (ao_) ambient = !run.exact && run.ambient == PreviewAmbient::Precomputed ? ao_->precomputedTexture() : ao_->ambientTexture();
    return PassContext{run.shaded, run.frame, run.plan, images_[run.exact ? kExactImage : kPreviewImage].texture.name(), ambient,
                       run.recast ? &*run.recast : nullptr};
}

bool Renderer::execute(FrameRun& run, double budgetMs, std::uint32_t sliceUnits) {
    bool whole = budgetMs < 0;
    auto start = Clock::now();
    for (bool first = true; run.next < run.plan.passes.size() && (whole || first || msSince(start) < budgetMs); first = false) {
        Pass pass = run.plan.passes[run.next].pass;
        if (run.exact && writesImage(pass)) beginExactImage(run);
        PassContext context = contextOf(run);
        std::optional<gl::ProgramUseLog> used;
        if (auditBindings_) used.emplace();
        timers_.begin(passInfo(pass).name);
        bool done = whole ? runWhole(pass, context, run) : runSlice(pass, context, run, budgetMs - msSince(start), sliceUnits);
        timers_.end();
        if (used) recordBindings(run, pass, used->programs());
        if (done) ++run.next;
    }
    return run.next == run.plan.passes.size();
}

void Renderer::recordBindings(FrameRun& run, Pass pass, const std::vector<GLuint>& programs) const {
    if (run.bound.empty() || run.bound.back().pass != pass) run.bound.push_back(BoundResources{pass, {}, {}});
    for (GLuint program : programs) addResourcesBound(run.bound.back(), gl::activeBindings(program));
}

void Renderer::finishRun(const FrameRun& run) {
    lastPlan_ = run.plan;
    lastPassBindings_ = run.bound;
    if (run.exact)
        exactImage_ = ExactImage{stampOf(run.frame), ClipSnapshot::of(clip_, volume_.geometry().cellDiagonalMm()), diagnostics(),
                                 removalTexture_ != nullptr};
    shown_ = ShownImage{stampOf(run.frame), run.exact, run.ambient};
}

void Renderer::beginExactImage(FrameRun& run) {
    if (run.imageBegun) return;
    exactImage_.reset();
    glm::ivec2 size = run.frame.size;
    lastRecastShare_ = run.recast ? double(run.recast->region.area()) / (double(size.x) * double(size.y)) : 1.0;
    run.imageBegun = true;
}

void Renderer::abandonExactJob() {
    // Finishing step V first (as before) cost the next exact frame up to the whole of this one's step V when the
    // user paused and moved on; abandoning it costs the next step IV the bricks of this one, voxel clipping and
    // copies outside the new meshes' reach. V_AO's freshness record still names the versions of the last finished
    // step V: this job's step IV ran because the versions had moved on from those, and they only grow, so the
    // record matches no later frame until a step V finishes.
    if (exactJob_ && exactJob_->stepIVBegun && !exactJob_->stepVDone && ao_) ao_->abandonUpdate();
    exactJob_.reset();
}

// ---- Passes: whole, or the next slice ----

bool Renderer::runWhole(Pass pass, const PassContext& context, FrameRun& run) {
    switch (pass) {
        case Pass::ClipMaps:
            clip_.setDilatedMapsNeeded(dilatedMapsWanted(context.mapsFrame.shading));
            clip_.update();
            return true;
        case Pass::LaoPrecompute:
            if (!ao_) ao_ = makeAmbientOcclusion();
            // A step I in slices for these inputs is finished where it is; anything else starts over.
            if (slicingFor_ && Freshness::samePrecomputeInputs(*slicingFor_, currentVersions()) && ao_->precomputeStarted()) {
                while (!ao_->precomputeDone()) ao_->advancePrecompute(*tf_, ao_->totalBricks());
            } else {
                ao_->precompute(*tf_);
            }
            slicingFor_.reset();
            ambientWritten_ = false;
            freshness_.markPrecomputed(currentVersions());
            return true;
        case Pass::VoxelClipping:
            run.ambientVersions = currentVersions();
            run.stepIVBegun = true;
            ao_->clipVoxels(*tf_, clip_, context.frame.shading);
            return true;
        case Pass::LaoRecompute:
            ao_->recomputeLao(*tf_);
            finishStepV(run);
            return true;
        case Pass::GradientVolume: gradients_.build(volume_); return true;
        case Pass::TubeGBuffer: tubes_->drawGBuffer(context.frame, clip_, gbuffer_); return true;
        case Pass::RayCast: runRayCast(context, false); return true;
        case Pass::SlabPass: runSlabPass(context); return true;
        case Pass::Composite: runComposite(context); return true;
        case Pass::IsmosRayCast:
            if (!ismos_) ismos_ = std::make_unique<IsmosPass>();
            runRayCast(context, true);
            return true;
        case Pass::IsmosOcclusion:
            ismos_->runOcclusion(context.frame, ismosSpaceOf(context.frame), volume_.geometry().worldCenter(), context.image);
            return true;
        case Pass::Count: break;
    }
    throw SystemError("frame plan: a pass without code");
}

bool Renderer::runSlice(Pass pass, const PassContext& context, FrameRun& run, double budgetMs, std::uint32_t sliceUnits) {
    switch (pass) {
        case Pass::VoxelClipping: return stepIVSlice(run, budgetMs, sliceUnits);
        case Pass::LaoRecompute: return stepVSlice(run, budgetMs, sliceUnits);
        case Pass::RayCast: return rayCastSlice(context, run, budgetMs, sliceUnits);
        case Pass::TubeGBuffer: return tubeGBufferSlice(context, run, budgetMs, sliceUnits);
        case Pass::Composite: return compositeSlice(context, run, budgetMs, sliceUnits);
        case Pass::SlabPass: return slabSlice(context, run, budgetMs, sliceUnits);
        default: return runWhole(pass, context, run);
    }
}

void Renderer::finishStepV(const FrameRun& run) {
    ambientWritten_ = true;
    freshness_.markAmbient(run.ambientVersions, run.frame.shading);
}

bool Renderer::stepIVSlice(FrameRun& run, double budgetMs, std::uint32_t sliceUnits) {
    if (!run.stepIVBegun) {
        // The bricks are decided and uploaded here; from now on an abandoned job leaves them to the next update.
        run.stepIVUnits = ao_->beginClipVoxels(clip_, run.frame.shading);
        run.stepIVBegun = true;
        run.ambientVersions = currentVersions();
    }
    if (std::uint32_t left = ao_->clipUnitsLeft(); left > 0) {
        // A probe of 1/64 of the work until a rate is known.
        std::uint32_t n = stepIVSizer_.next(budgetMs, left, std::max<std::uint32_t>(left / 64, 1), sliceUnits);
        timedSlice(stepIVSizer_, n, [&](std::uint32_t units) { ao_->advanceClipVoxels(*tf_, clip_, units); });
    }
    return ao_->clipUnitsLeft() == 0;
}

bool Renderer::stepVSlice(FrameRun& run, double budgetMs, std::uint32_t sliceUnits) {
    // The first slice builds the list (and waits for its length); later ones run its LAO rays.
    if (!run.stepVBegun) {
        run.stepVGroups = ao_->beginRecompute(*tf_);
        run.stepVBegun = true;
    } else if (std::uint32_t left = ao_->recomputeGroupsLeft(); left > 0) {
        std::uint32_t n = stepVSizer_.next(budgetMs, left, std::max<std::uint32_t>(run.stepVGroups / 64, 1), sliceUnits);
        timedSlice(stepVSizer_, n, [&](std::uint32_t units) { ao_->advanceRecompute(units); });
    }
    if (ao_->recomputeGroupsLeft() > 0) return false;
    finishStepV(run);
    run.stepVDone = true;
    return true;
}

bool Renderer::tubeGBufferSlice(const PassContext& context, FrameRun& run, double budgetMs, std::uint32_t sliceUnits) {
    const std::int64_t units = tubeUnits(tubes_->primitiveCount());
    if (run.tubeUnitsDone < 0) {
        tubes_->clearGBuffer(context.frame.size, gbuffer_);
        run.tubeUnitsDone = 0;
    }
    if (std::int64_t left = units - run.tubeUnitsDone; left > 0) {
        std::uint32_t n = tubeSizer_.next(budgetMs, static_cast<std::uint32_t>(left), 1, sliceUnits);
        timedSlice(tubeSizer_, n, [&](std::uint32_t drawn) {
            tubes_->drawGBuffer(context.frame, clip_, gbuffer_, static_cast<std::size_t>(run.tubeUnitsDone) * kTubePrimitivesPerUnit,
                                std::size_t{drawn} * kTubePrimitivesPerUnit);
            run.tubeUnitsDone += drawn;
        });
    }
    return run.tubeUnitsDone >= units;
}

bool Renderer::compositeSlice(const PassContext& context, FrameRun& run, double budgetMs, std::uint32_t sliceUnits) {
    const int height = context.frame.size.y;
    if (int left = (height - run.compositeRowsDone + kCompositeRowsPerUnit - 1) / kCompositeRowsPerUnit; left > 0) {
        std::uint32_t n = compositeSizer_.next(budgetMs, static_cast<std::uint32_t>(left), 1, sliceUnits);
        timedSlice(compositeSizer_, n, [&](std::uint32_t units) {
            int rows = std::min(static_cast<int>(units) * kCompositeRowsPerUnit, height - run.compositeRowsDone);
            runComposite(context, run.compositeRowsDone, rows);
            run.compositeRowsDone += rows;
        });
    }
    return run.compositeRowsDone >= height;
}

bool Renderer::rayCastSlice(const PassContext& context, FrameRun& run, double budgetMs, std::uint32_t sliceUnits) {
    if (run.parts < 0) {
        // The first slice: a probe of one part, which also says how many there are (none: every pixel is kept).
        auto start = Clock::now();
        run.parts = runRayCast(context, false, 0, 1);
        glFinish();
        run.partsDone = std::min(run.parts, 1);
        rayCastSizer_.next(budgetMs, 1, 1, 0);   // one part, whatever the rate: the count is not known before
        rayCastSizer_.measured(1, msSince(start));
    } else if (run.partsDone < run.parts) {
        auto left = static_cast<std::uint32_t>(run.parts - run.partsDone);
        std::uint32_t n = rayCastSizer_.next(budgetMs, left, 1, sliceUnits);
        timedSlice(rayCastSizer_, n, [&](std::uint32_t units) { runRayCast(context, false, run.partsDone, static_cast<int>(units)); });
        run.partsDone += static_cast<int>(n);
    }
    return run.partsDone >= run.parts;
}

// ---- The image passes ----

int Renderer::runRayCast(const PassContext& context, bool ismosLayers, int firstPart, int partCount) {
    const FrameDescription& frame = context.frame;
    // ISMOS pass 1 is this ray caster shading with the mode's base (phong or solid) plus the layer outputs;
    // every other mode compiles without ISMOS_LAYERS, so its program is unchanged.
    ShadingMode shading = ismosLayers ? frame.ismos.base : frame.shading;
    gl::Defines defines;
    SampleShadingPiece::addDefines(defines, shading);
    addLightingDefines(defines, frame);
    SampleShadingPiece::addCutFaceDefines(defines, frame.raycast.cutFace, clip_.count());
    clip_.addDefines(defines);
    // Tubes in view: ISMOS's pass 1 stops at them (its compositor lays them behind); every other mode's ray cast
    // stops at them and shades them itself (tube_surface.glsl).
    bool withTubes = context.plan.runs(Pass::TubeGBuffer);
    bool tubes = ismosLayers && withTubes;
    bool rayCastTubes = !ismosLayers && withTubes;
    if (ismosLayers) IsmosPass::addLayerDefines(defines, frame.ismos);
    if (tubes) defines.emplace_back("ISMOS_TUBES", "1");
    if (rayCastTubes) TubeSurfacePiece::addDefines(defines);
    if (countSamples_) defines.emplace_back("COUNT_SAMPLES", "1");
    if (phongShading(frame) == PhongShading::InLoop) defines.emplace_back("PHONG_SHADED_IN_LOOP", "1");
    bool gradientVolume = context.plan.reads(ismosLayers ? Pass::IsmosRayCast : Pass::RayCast, Resource::GradientVolume);
    if (gradientVolume) defines.emplace_back("GRADIENT_VOLUME", "1");
    tf_->addDefines(defines);
    tf_->addStepDefines(defines, resolveStepMm(frame.raycast));
    NoDataPiece{volume_}.addDefines(defines);
    VolumeLayoutPiece{volume_.layout()}.addDefines(defines);
    gl::Program& p = raycastPrograms_.get(defines);

    CameraRayPiece{frame}.apply(p);
    VolumePiece{volume_}.apply(p);
    if (gradientVolume) gradients_.apply(p);
    NoDataPiece{volume_}.apply(p);
    VolumeLayoutPiece{volume_.layout()}.apply(p);
    tf_->apply(p);
    clip_.apply(p);
    SampleShadingPiece{shading, laoSettings_.ambientScale, context.ambient, frame.raycast.cutFace}.apply(p);
    setLightingUniforms(p, frame, tf_->material());
    if (ismosLayers) ismos_->applyLayers(p, frame, ismosSpaceOf(frame), resolveStepMm(frame.raycast));
    if (tubes) {
        glBindTextureUnit(binding::tubeDepth, gbuffer_.depth());
        glBindTextureUnit(binding::tubeNormal, gbuffer_.normal());
        p.set("ismosTubeThicknessMm", static_cast<float>(tubeShading_.thicknessMm));
    }
    if (rayCastTubes) TubeSurfacePiece{frame, gbuffer_.depth(), gbuffer_.color(), gbuffer_.normal(), tubeShading_}.apply(p);
    p.set("stepMm", static_cast<float>(resolveStepMm(frame.raycast)));
    p.set("earlyTerminationAlpha", static_cast<float>(frame.raycast.earlyTerminationAlpha));
    p.set("jitterSeed", static_cast<unsigned>(frame.raycast.jitterSeed));
    p.set("skipEmptySpace", frame.raycast.skipEmptySpace ? 1 : 0);
    p.set("volumeSize", volume_.geometry().dims);
    p.set("brickSize", GpuVolume::brickSize);
    p.set("maxSkipBricks", emptySpaceJumpLimit_);
    glBindTextureUnit(binding::occupancy, occupancy_.name());
    glBindImageTexture(binding::imageOutput, context.image, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    if (countSamples_) {
        if (!sampleCounter_) {
            sampleCounter_ = gl::createBuffer();
            glNamedBufferStorage(sampleCounter_.name(), 16, nullptr, GL_DYNAMIC_STORAGE_BIT | GL_MAP_READ_BIT);
        }
        // Samples taken, loop steps, steps per half of the dispatch: zeroed at the frame's first part, so an
        // exact frame in slices counts all of its parts.
        const std::uint32_t zero[4] = {0, 0, 0, 0};
        if (firstPart == 0) glNamedBufferSubData(sampleCounter_.name(), 0, 16, zero);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding::ssboSampleCounter, sampleCounter_.name());
    }
    // An exact frame's ray cast covers its recast region; a preview's and ISMOS's, every pixel.
    TileOrderPiece tiles{frame.size, tileRowsPerBand_};
    if (context.recast && !ismosLayers) {
        RecastTiles& recast = *context.recast;
        glm::uvec2 tileSize(p.workGroupSize());
        if (!recast.spans || recast.spans->tileSize != tileSize) {
            recast.spans = tileSpansOf(recast.region, tileSize);
            recast.spanBuffer = gl::createBuffer();
            glNamedBufferStorage(recast.spanBuffer.name(), static_cast<GLsizeiptr>(std::max<std::size_t>(recast.spans->rows.size(), 1) * sizeof(glm::uvec2)),
                                 recast.spans->rows.data(), 0);
        }
        tiles.spans = &*recast.spans;
        tiles.spanBuffer = recast.spanBuffer.name();
    }
    int parts = tiles.partCount(p.workGroupSize());
    tiles.dispatchParts(p, firstPart, partCount < 0 ? parts : partCount);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    return parts;
}

SlabInputs Renderer::slabInputs(const PassContext& context) {
    // Without tubes only dos comes here (all rays advance slice by slice together); with tubes every mode.
    const FrameDescription& frame = context.frame;
    bool withTubes = context.plan.runs(Pass::TubeGBuffer);
    GLuint ambient = usesAmbientOcclusion(frame.shading) ? context.ambient : 0;
    return SlabInputs{frame, volume_, *tf_, clip_, SampleShadingPiece{frame.shading, laoSettings_.ambientScale, ambient, frame.raycast.cutFace}, context.image,
                      withTubes ? &gbuffer_ : nullptr, withTubes ? tubeShading_.geometryOpacity : 0.0, tubeShading_.thicknessMm};
}

void Renderer::runSlabPass(const PassContext& context) {
    slab_.run(slabInputs(context));
    slabUsed_ = true;
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
}

bool Renderer::slabSlice(const PassContext& context, FrameRun& run, double budgetMs, std::uint32_t sliceUnits) {
    SlabInputs in = slabInputs(context);
    // Units are bands of a view-aligned slice (SlabRun); one slice at full size can take longer than the budget on
    // a software renderer, so the probe is a single band.
    if (!run.slab) run.slab = slab_.begin(in);
    slabUsed_ = true;
    if (std::uint32_t left = static_cast<std::uint32_t>(run.slab->left()); left > 0) {
        std::uint32_t n = slabSizer_.next(budgetMs, left, 1, sliceUnits);
        timedSlice(slabSizer_, n, [&](std::uint32_t units) { slab_.advance(in, *run.slab, units); });
    }
    if (!run.slab->done()) return false;
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    return true;
}

void Renderer::runComposite(const PassContext& context, int firstRow, int rows) {
    const FrameDescription& frame = context.frame;
    if (poissonCount_ != tubeShading_.vicinitySamples) {
        std::vector<glm::vec2> disk = poissonDisk(tubeShading_.vicinitySamples);
        poissonDisk_ = gl::createBuffer();
        glNamedBufferStorage(poissonDisk_.name(), static_cast<GLsizeiptr>(std::max<std::size_t>(disk.size(), 1) * sizeof(glm::vec2)),
                             disk.data(), 0);
        poissonCount_ = tubeShading_.vicinitySamples;
    }
    gl::Defines defines;
    addLightingDefines(defines, frame);
    gl::Program& c = compositePrograms_.get(defines);
    CameraRayPiece{frame}.apply(c);
    setLightingUniforms(c, frame, tubeShading_.material);
    c.set("poissonCount", poissonCount_);
    // Section 3.1.5: the vicinity radius l_vicinity tan(theta), projected at the surface's depth.
    double pixelsPerMmAtUnitDepth = frame.camera.pixelsPerMmAtUnitDepth(frame.size.y);
    c.set("vicinityRadiusPixelsAtUnitDepth",
          static_cast<float>(tubeShading_.vicinityDistanceMm * std::tan(glm::radians(frame.dos.coneAngleDeg)) * pixelsPerMmAtUnitDepth));
    c.set("depthBiasMm", static_cast<float>(tubeShading_.depthBiasMm));
    c.set("useOcclusion", traits(frame.shading).tubesInSlabPass ? 1 : 0);
    c.set("lineDiffuseExponent", static_cast<float>(tubeShading_.lineDiffuseExponent));
    glBindImageTexture(binding::imageOutput, context.image, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    glBindTextureUnit(binding::tubeDepth, gbuffer_.depth());
    glBindTextureUnit(binding::tubeColor, gbuffer_.color());
    glBindTextureUnit(binding::tubeNormal, gbuffer_.normal());
    glBindTextureUnit(binding::partialOcclusion, gbuffer_.partialOcclusion());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding::ssboPoissonDisk, poissonDisk_.name());
    if (rows < 0) rows = frame.size.y - firstRow;
    c.set("firstRow", firstRow);
    c.dispatchCovering(glm::uvec3(static_cast<unsigned>(frame.size.x), static_cast<unsigned>(std::max(rows, 0)), 1u));
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
}

// ---- Step I in slices ----

bool Renderer::precomputePending(const FrameDescription& frame) const {
    return traits(frame.shading).ambientOcclusion && !(ao_ && freshness_.precomputedCurrent(currentVersions()));
}

double Renderer::precomputeProgress() const {
    if (ao_ && freshness_.precomputedCurrent(currentVersions())) return 1.0;
    if (!ao_ || !slicingFor_ || !Freshness::samePrecomputeInputs(*slicingFor_, currentVersions())) return 0.0;
    return ao_->precomputeProgress();
}

double Renderer::advancePrecompute(double budgetMs, std::uint32_t sliceBricks) {
    InputVersions now = currentVersions();
    if (ao_ && freshness_.precomputedCurrent(now)) return 1.0;
    if (!ao_) ao_ = makeAmbientOcclusion();
    if (!slicingFor_ || !Freshness::samePrecomputeInputs(*slicingFor_, now) || !ao_->precomputeStarted()) {
        ao_->beginPrecompute();
        ambientWritten_ = false;
        slicingFor_ = now;
    }
    // Slices sized from the slowest rate measured so far to fill the budget (SliceSizer::Rate::Slowest); the
    // first of each phase is a small probe (1/512 of the grid), so a budget is overrun at most by a probe or by
    // bricks slower than any before.
    auto start = Clock::now();
    timers_.begin(passInfo(Pass::LaoPrecompute).name);
    for (bool first = true; !ao_->precomputeDone() && (first || msSince(start) < budgetMs); first = false) {
        SliceSizer& sizer = precomputeSizers_[ao_->precomputePhase()];
        std::uint32_t bricks = sizer.next(budgetMs - msSince(start), ao_->totalBricks(), std::max<std::uint32_t>(ao_->totalBricks() / 512, 1), sliceBricks);
        auto sliceStart = Clock::now();
        std::uint32_t ran = ao_->advancePrecompute(*tf_, bricks);
        glFinish();
        sizer.measured(ran, msSince(sliceStart));
    }
    timers_.end();
    if (ao_->precomputeDone()) {
        freshness_.markPrecomputed(now);
        slicingFor_.reset();
        return 1.0;
    }
    return ao_->precomputeProgress();
}

}  // namespace curette
