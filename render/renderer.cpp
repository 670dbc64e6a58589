#include "render/renderer.h"

#include "render/passes/gpu_tube_builder.h"

#include "base/error.h"
#include "gl/bindings.h"
#include "render/model/brick_distance.h"
#include "render/lighting.h"
#include "render/shader_pieces.h"

#include <glm/gtc/matrix_inverse.hpp>

#include <algorithm>
#include <chrono>

namespace curette {

Renderer::Renderer(gl::Context& context, const VolumeData& volume, const TransferFunction& tf)
    : context_(context), volume_(context.info(), volume),
      clip_(clip::ClipMapSettings{0.5 * volume_.geometry().minSpacing(), 64, 1024}) {
    timers_.setSynchronous(context.info().softwareRenderer);
    clip_.setDilationRadiusMm(AmbientOcclusion::dilationRadiusMm(laoSettings_, volume_.geometry()));
    setTransferFunction(tf);
}

Renderer::~Renderer() = default;

void Renderer::setLaoSettings(const LaoSettings& settings) {
    // The ambient scale only shades: changing it alone keeps every AO volume.
    LaoSettings comparable = settings;
    comparable.ambientScale = laoSettings_.ambientScale;
    bool aoChanged = !(comparable == laoSettings_);
    bool scaleChanged = settings.ambientScale != laoSettings_.ambientScale;
    laoSettings_ = settings;
    if (scaleChanged) ++appearanceVersion_;   // not an AO input, but the image changes
    if (!aoChanged) return;
    // The clip maps leave room for the LAO reach in every mode, so every mode clips identically.
    clip_.setDilationRadiusMm(AmbientOcclusion::dilationRadiusMm(laoSettings_, volume_.geometry()));
    ao_.reset();  // buffers depend on the settings (directions, list); reallocated at the next AO frame
    ambientWritten_ = false;
    slicingFor_.reset();
    precomputeBricksPerMs_[0] = precomputeBricksPerMs_[1] = 0;
    ++versions_.laoSettings;
    freshness_.forgetAmbientOcclusion();
}

void Renderer::setTransferFunction(const TransferFunction& tf) {
    tf_ = std::make_unique<TransferFunctionTexture>(tf, volume_.valueScale(), volume_.valueOffset(), volume_.hasNoData());
    tf_->attachLabels(labels_.get());
    ++versions_.transferFunction;  // V_PAO and V_AO depend on the TF (the reference implementation's bug 4)
    updateOccupancy();
}

void Renderer::setLabels(std::unique_ptr<LabelOverlay> labels) {
    labels_ = std::move(labels);
    tf_->attachLabels(labels_.get());
    ++versions_.transferFunction;  // the labels are part of the classification
    updateOccupancy();
}

void Renderer::setLabelStyles(const std::vector<glm::vec4>& styles) {
    if (!labels_) return;
    labels_->setStyles(styles);
    ++versions_.transferFunction;
    updateOccupancy();
}

double Renderer::resolveStepMm(const RaycastSettings& settings) const {
    return settings.stepMm > 0 ? settings.stepMm : 0.5 * volume_.geometry().minSpacing();
}

namespace {
// Whether a sample in each brick may have opacity: a brick may be skipped only if no texel value its samples
// can see has any opacity, and no shown label lies in it (a label raises the opacity of transparent tissue).
std::vector<std::uint8_t> occupiedBricks(const TransferFunctionTexture& tf, const LabelOverlay* labels,
                                         const std::vector<glm::vec2>& ranges, glm::ivec3 grid, int brickSize) {
    std::vector<std::uint8_t> occupied(ranges.size());
    for (std::size_t i = 0; i < ranges.size(); ++i) occupied[i] = tf.maxOpacity(ranges[i].x, ranges[i].y) > 0.0f;
    if (labels) {
        std::vector<std::uint8_t> labelled = labels->occupiedBricks(grid, brickSize);
        for (std::size_t i = 0; i < occupied.size(); ++i) occupied[i] = occupied[i] || labelled[i] != 0;
    }
    return occupied;
}

void uploadBricks(gl::Texture& texture, glm::ivec3 grid, const std::vector<std::uint8_t>& values, const char* label) {
    if (!texture) {
        texture = gl::createTexture(GL_TEXTURE_3D);
        glTextureStorage3D(texture.name(), 1, GL_R8, grid.x, grid.y, grid.z);
        glObjectLabel(GL_TEXTURE, texture.name(), -1, label);
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage3D(texture.name(), 0, 0, 0, 0, grid.x, grid.y, grid.z, GL_RED, GL_UNSIGNED_BYTE, values.data());
}
}  // namespace

void Renderer::updateOccupancy() {
    glm::ivec3 grid = volume_.brickGrid();
    std::vector<std::uint8_t> occupied = occupiedBricks(*tf_, labels_.get(), volume_.brickRanges(), grid, GpuVolume::brickSize);
    // Stored as the distance to the nearest occupied brick (render/model/brick_distance.h), so a ray jumps over
    // every empty brick around it at once.
    std::vector<bool> flags(occupied.begin(), occupied.end());
    uploadBricks(occupancy_, grid, chebyshevBrickDistance(flags, grid, 255), "occupancy (empty-space skipping)");
    if (seenBricks_) updateSeenBricks();
}

void Renderer::updateSeenBricks() {
    // The same on finer bricks, for the voxels whose LAO a visible sample can read (steps I and V only: made
    // with the first AO volume).
    glm::ivec3 grid = volume_.seenBrickGrid();
    std::vector<std::uint8_t> seen = occupiedBricks(*tf_, labels_.get(), volume_.seenBrickRanges(), grid, GpuVolume::seenBrickSize);
    for (std::uint8_t& s : seen) s = s ? 0 : 255;
    uploadBricks(seenBricks_, grid, seen, "seen bricks (LAO where a visible sample reads it)");
}

std::unique_ptr<AmbientOcclusion> Renderer::makeAmbientOcclusion() {
    if (!seenBricks_) updateSeenBricks();
    return std::make_unique<AmbientOcclusion>(volume_, laoSettings_, &seenBricks_);
}

void Renderer::ensureOutput(glm::ivec2 size) {
    OutputImage& image = images_[target_];
    if (size == image.size && image.texture) return;
    image.texture = gl::createTexture(GL_TEXTURE_2D);
    glTextureStorage2D(image.texture.name(), 1, GL_RGBA32F, size.x, size.y);
    glObjectLabel(GL_TEXTURE, image.texture.name(), -1, target_ == kExactImage ? "output image" : "preview image");
    image.size = size;
}

void Renderer::setTubes(const TubeVertices& vertices, const TubeShading& shading) {
    tubes_.reset();   // the old streams go first: at whole-brain scale two sets need not fit at once
    tubes_ = std::make_unique<TubeSet>(vertices);
    tubeShading_ = shading;
    ++appearanceVersion_;
}

void Renderer::setTubeRings(const TubeRings& rings, const TubeShading& shading) {
    tubes_.reset();
    tubes_ = std::make_unique<TubeSet>(buildTubeBuffersOnGpu(rings));
    tubeShading_ = shading;
    ++appearanceVersion_;
}

void Renderer::setTubeShading(const TubeShading& shading) {
    tubeShading_ = shading;
    ++appearanceVersion_;
}

void Renderer::clearTubes() {
    tubes_.reset();
    ++appearanceVersion_;
}

InputVersions Renderer::currentVersions() const {
    InputVersions v = versions_;
    v.clipMeshes = clip_.version();
    return v;
}

bool Renderer::dilatedMapsWanted(ShadingMode mode) const {
    const ShadingModeTraits& t = traits(mode);
    return t.ambientOcclusion ? t.dilatedMaps : clip_.dilatedMapsNeeded();
}

bool Renderer::tubesInView(const FrameDescription& frame) const {
    // Conservative: the tubes' world box is outside the view only when all eight corners lie beyond one plane
    // of the view frustum; then they cover no pixel and the frame is the one without tubes.
    if (!tubes_) return false;
    glm::dmat4 viewProjection = frame.camera.viewProjection(frame.size);
    glm::dvec3 lo = tubes_->boundsMin(), hi = tubes_->boundsMax();
    for (int plane = 0; plane < 6; ++plane) {
        int axis = plane / 2;
        double sign = plane % 2 == 0 ? 1.0 : -1.0;
        bool allOutside = true;
        for (int corner = 0; corner < 8 && allOutside; ++corner) {
            glm::dvec4 c = viewProjection * glm::dvec4((corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y, (corner & 4) ? hi.z : lo.z, 1.0);
            allOutside = sign * c[axis] > c.w;   // x > w, x < -w, and so on
        }
        if (allOutside) return false;
    }
    return true;
}

PlanInputs Renderer::planInputs(const FrameDescription& frame) const {
    InputVersions now = currentVersions();
    PlanInputs in;
    in.shading = frame.shading;
    in.clipMeshes = clip_.count();
    in.clipMapsCurrent = clip_.mapsCurrent(dilatedMapsWanted(frame.shading));
    in.tubes = tubes_ != nullptr;
    in.tubesInView = tubesInView(frame);
    in.precomputedCurrent = ao_ && freshness_.precomputedCurrent(now);
    in.ambientCurrent = ao_ && freshness_.ambientCurrent(now, frame.shading);
    in.ismosExact = frame.ismos.partial && !frame.ismos.fit;
    in.ismosFit = frame.ismos.partial && frame.ismos.fit;
    return in;
}

FramePlan Renderer::plan(const FrameDescription& frame) const { return planFrame(planInputs(frame)); }

bool Renderer::showing(const FrameDescription& frame) const {
    return shownFrame_ && shownExact_ && *shownFrame_ == frame && shownVersions_ == currentVersions() &&
           shownAppearanceVersion_ == appearanceVersion_;
}

void Renderer::validateSize(const FrameDescription& frame) const {
    if (frame.size.x < 1 || frame.size.y < 1 || frame.size.x > context_.info().maxTextureSize ||
        frame.size.y > context_.info().maxTextureSize)
        throw InputError("<frame>", "size", "between 1x1 and the GL maximum texture size",
                         std::to_string(frame.size.x) + "x" + std::to_string(frame.size.y));
}

namespace {
bool writesImage(Pass pass) {
    const std::vector<Resource>& writes = passInfo(pass).writes;
    return std::find(writes.begin(), writes.end(), Resource::OutputImage) != writes.end();
}
}  // namespace

std::optional<PixelRegion> Renderer::recastRegion(const FrameDescription& frame, const FramePlan& plan) const {
    if (!recastOnlyChanged_ || !exactImage_ || exactImage_->frame != frame || exactImage_->appearance != appearanceVersion_ ||
        exactImage_->diagnostics != diagnostics())
        return std::nullopt;
    InputVersions now = currentVersions(), before = exactImage_->versions;
    before.clipMeshes = now.clipMeshes;
    if (!(before == now)) return std::nullopt;
    // The ray cast must be the only image pass (tubes in view bring the slab pass and the compositor), and the maps
    // not drawn again (a rigid motion only moves their cameras).
    for (const PlannedPass& p : plan.passes)
        if (p.pass == Pass::ClipMaps || (writesImage(p.pass) && p.pass != Pass::RayCast)) return std::nullopt;
    auto boxes = changedRegions(exactImage_->clip, ClipSnapshot::of(clip_, volume_.geometry().cellDiagonalMm()),
                              traits(frame.shading).ambientOcclusion);
    // No mesh moved: render() of an unchanged state is asked for on purpose (benchmarks time it), so it runs whole.
    if (!boxes || boxes->empty()) return std::nullopt;
    return pixelsMeeting(*boxes, frame);
}

void Renderer::beginExactImage(const std::optional<PixelRegion>& region, glm::ivec2 size) {
    exactImage_.reset();
    recastRegion_ = region;
    recastSpans_.reset();
    lastRecastShare_ = region ? double(region->area()) / (double(size.x) * double(size.y)) : 1.0;
}

void Renderer::beginImage(ExactJob& job) {
    if (job.imageBegun) return;
    beginExactImage(job.recast, job.frame.size);
    job.imageBegun = true;
}

void Renderer::markShown(const FrameDescription& frame, bool exact) {
    if (exact)
        exactImage_ = ExactImage{frame, currentVersions(), appearanceVersion_, ClipSnapshot::of(clip_, volume_.geometry().cellDiagonalMm()), diagnostics()};
    shownImage_ = exact ? kExactImage : kPreviewImage;
    shownFrame_ = frame;
    shownVersions_ = currentVersions();
    shownAppearanceVersion_ = appearanceVersion_;
    shownExact_ = exact;
}

void Renderer::render(const FrameDescription& frame) {
    validateSize(frame);
    abandonExactJob();
    target_ = kExactImage;
    ensureOutput(frame.size);
    lastPlan_ = plan(frame);
    // A rigid motion changes only the clipping cameras: upload them when the maps are not redrawn anyway.
    if (!lastPlan_.runs(Pass::ClipMaps)) clip_.uploadCameras();
    beginExactImage(recastRegion(frame, lastPlan_), frame.size);
    for (const PlannedPass& p : lastPlan_.passes) {
        timers_.begin(passInfo(p.pass).name);
        run(p.pass, frame);
        timers_.end();
    }
    markShown(frame, true);
}

namespace {
using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point start) { return std::chrono::duration<double, std::milli>(Clock::now() - start).count(); }
// A slice's size: `rate` units per ms times the budget left, within [1, left]; a probe of `probe` units before the
// rate is known.
std::uint32_t sliceSize(double rate, double budgetMs, std::uint32_t left, std::uint32_t probe, std::uint32_t fixed) {
    if (fixed > 0) return std::min(fixed, left);
    if (!(rate > 0)) return std::clamp<std::uint32_t>(probe, 1, left);
    return static_cast<std::uint32_t>(std::clamp(rate * std::max(budgetMs, 1.0), 1.0, double(left)));
}

// One slice of a sliced pass (step IV's bricks, step V's list groups, the ray cast's bands): sliceSize's units,
// at most twice the last slice's (the rate comes from the last slice, whose units may have been cheap, air at
// the top of the image or far from the cut, so a wrong rate overruns the budget little), run by `run`; then the
// GPU is waited for and the rate measured again. Returns the units run.
template <typename Run>
std::uint32_t runTimedSlice(double& unitsPerMs, std::uint32_t& lastUnits, double budgetMs, std::uint32_t left, std::uint32_t probe,
                            std::uint32_t fixed, Run run) {
    std::uint32_t n = sliceSize(unitsPerMs, budgetMs, left, probe, fixed);
    if (fixed == 0 && lastUnits > 0) n = std::min(n, 2 * lastUnits);
    lastUnits = n;
    auto start = Clock::now();
    run(n);
    glFinish();
    if (double ms = msSince(start); ms > 0.5) unitsPerMs = n / ms;
    return n;
}
}  // namespace

bool Renderer::exactJobCurrent(const FrameDescription& frame) const {
    return exactJob_ && exactJob_->frame == frame && exactJob_->versionsSeen == currentVersions() &&
           exactJob_->appearanceSeen == appearanceVersion_ && exactJob_->previewsSeen == previewsRendered_;
}

void Renderer::beginStepV(ExactJob& job) {
    job.stepVGroups = ao_->beginRecompute(*tf_);
    job.stepVBegun = true;
}

bool Renderer::stepVSlice(ExactJob& job, double budgetMs, std::uint32_t sliceUnits) {
    // The first slice builds the list (and waits for its length); later ones run its LAO rays.
    if (!job.stepVBegun) {
        beginStepV(job);
    } else if (ao_->recomputeGroupsLeft() > 0) {
        runTimedSlice(stepVGroupsPerMs_, job.lastStepVGroups, budgetMs, ao_->recomputeGroupsLeft(),
                      std::max<std::uint32_t>(job.stepVGroups / 64, 1), sliceUnits, [&](std::uint32_t n) { ao_->advanceRecompute(n); });
    }
    if (ao_->recomputeGroupsLeft() > 0) return false;
    ambientWritten_ = true;
    freshness_.markAmbient(job.ambientVersions, job.frame.shading);
    job.stepVDone = true;
    return true;
}

void Renderer::abandonExactJob() {
    // Finishing step V first (as before) cost the next exact frame up to the whole of this one's step V
    // (0.8-0.9 s on the carved head at 1024x768) when the user paused and moved on; abandoning it costs the next
    // step IV the bricks of this one, voxel clipping and copies outside the new meshes' reach.
    // V_AO's freshness record still names the versions of the last finished step V: this job's step IV ran
    // because the versions had moved on from those, and they only grow, so the record matches no later frame
    // until a step V finishes.
    if (exactJob_ && exactJob_->stepIVBegun && !exactJob_->stepVDone && ao_) ao_->abandonUpdate();
    exactJob_.reset();
}

bool Renderer::stepIVSlice(ExactJob& job, double budgetMs, std::uint32_t sliceUnits) {
    if (!job.stepIVBegun) {
        // The bricks are decided and uploaded here; from now on an abandoned job leaves them to the next update.
        job.stepIVBricks = ao_->beginClipVoxels(clip_, job.frame.shading);
        job.stepIVBegun = true;
        job.ambientVersions = currentVersions();
    }
    if (std::uint32_t left = ao_->clipBricksLeft(); left > 0) {
        // A probe of 1/64 of the bricks until a rate is known.
        runTimedSlice(stepIVBricksPerMs_, job.lastStepIVBricks, budgetMs, left, std::max<std::uint32_t>(left / 64, 1), sliceUnits,
                      [&](std::uint32_t n) { ao_->advanceClipVoxels(*tf_, clip_, n); });
    }
    if (ao_->clipBricksLeft() > 0) return false;
    job.stepIVDone = true;
    return true;
}

void Renderer::runExactSlice(ExactJob& job, double budgetMs, std::uint32_t sliceUnits) {
    Pass pass = job.plan.passes[job.next].pass;
    timers_.begin(passInfo(pass).name);
    if (pass == Pass::VoxelClipping) {
        if (stepIVSlice(job, budgetMs, sliceUnits)) ++job.next;
    } else if (pass == Pass::LaoRecompute) {
        if (stepVSlice(job, budgetMs, sliceUnits)) ++job.next;
    } else if (pass == Pass::RayCast) {
        if (!job.rayCastBegun) {
            // The first slice: a probe of one band, which also says how many there are (none: every pixel is kept).
            beginImage(job);
            job.rayCastBegun = true;
            auto start = Clock::now();
            job.bands = runRayCast(job.frame, false, 0, 1);
            glFinish();
            job.bandsDone = std::min(job.bands, 1);
            job.lastBands = 1;
            if (double ms = msSince(start); ms > 0.5) rayCastBandsPerMs_ = 1 / ms;
        } else {
            auto left = static_cast<std::uint32_t>(job.bands - job.bandsDone);
            std::uint32_t ran = runTimedSlice(rayCastBandsPerMs_, job.lastBands, budgetMs, left, 1, sliceUnits,
                                              [&](std::uint32_t n) { runRayCast(job.frame, false, job.bandsDone, static_cast<int>(n)); });
            job.bandsDone += static_cast<int>(ran);
        }
        if (job.bandsDone >= job.bands) ++job.next;
    } else {
        if (writesImage(pass)) beginImage(job);
        run(pass, job.frame);
        ++job.next;
    }
    timers_.end();
}

bool Renderer::advanceExact(const FrameDescription& frame, double budgetMs, std::uint32_t sliceUnits) {
    validateSize(frame);
    auto start = Clock::now();
    if (exactJob_ && !exactJobCurrent(frame)) abandonExactJob();
    if (!exactJob_ && showing(frame)) return true;
    target_ = kExactImage;
    if (!exactJob_) {
        ensureOutput(frame.size);
        ExactJob job;
        job.frame = frame;
        job.plan = plan(frame);
        // As render(): a rigid motion changes only the clipping cameras.
        if (!job.plan.runs(Pass::ClipMaps)) clip_.uploadCameras();
        job.recast = recastRegion(frame, job.plan);
        exactJob_ = std::move(job);
    }
    ExactJob& job = *exactJob_;
    for (bool first = true; job.next < job.plan.passes.size() && (first || msSince(start) < budgetMs); first = false)
        runExactSlice(job, budgetMs - msSince(start), sliceUnits);
    job.versionsSeen = currentVersions();
    job.appearanceSeen = appearanceVersion_;
    job.previewsSeen = previewsRendered_;
    if (job.next < job.plan.passes.size()) return false;
    lastPlan_ = job.plan;
    markShown(frame, true);
    exactJob_.reset();
    return true;
}

double Renderer::exactProgress() const {
    if (!exactJob_ || exactJob_->plan.passes.empty()) return 0.0;
    const ExactJob& job = *exactJob_;
    double within = 0;
    if (job.next < job.plan.passes.size()) {
        Pass pass = job.plan.passes[job.next].pass;
        if (pass == Pass::VoxelClipping && job.stepIVBegun && job.stepIVBricks > 0)
            within = 1.0 - double(ao_->clipBricksLeft()) / job.stepIVBricks;
        if (pass == Pass::LaoRecompute && job.stepVBegun && job.stepVGroups > 0)
            within = 1.0 - double(ao_->recomputeGroupsLeft()) / job.stepVGroups;
        if (pass == Pass::RayCast && job.bands > 0) within = double(job.bandsDone) / job.bands;
    }
    return (double(job.next) + within) / double(job.plan.passes.size());
}

Renderer::PreviewAmbient Renderer::previewAmbient() const {
    if (!ao_ || !freshness_.precomputedCurrent(currentVersions())) return PreviewAmbient::None;
    return ambientWritten_ ? PreviewAmbient::LastExact : PreviewAmbient::Precomputed;
}

GLuint Renderer::shadedAmbientTexture() const {
    if (!ao_) return 0;
    if (previewing_ && *previewing_ == PreviewAmbient::Precomputed) return ao_->precomputedTexture();
    return ao_->ambientTexture();
}

void Renderer::renderPreview(const FrameDescription& frame) {
    validateSize(frame);
    // Previews have their own image, so an exact frame in slices (advanceExact) is not drawn over.
    target_ = kPreviewImage;
    ensureOutput(frame.size);
    ++previewsRendered_;
    PreviewAmbient source = previewAmbient();
    // The image passes shade `shaded`: the frame itself, or phong while V_PAO is not there. The clip maps are
    // drawn for the frame's own mode (cao wants the dilated ones), exactly as the exact frame would draw them.
    FrameDescription shaded = frame;
    PlanInputs inputs = planInputs(frame);
    if (traits(frame.shading).ambientOcclusion) {
        inputs.precomputedCurrent = inputs.ambientCurrent = true;   // steps I, IV, V are left out
        if (source == PreviewAmbient::None) shaded.shading = inputs.shading = ShadingMode::Phong;
    }
    lastPlan_ = planFrame(inputs);
    if (!lastPlan_.runs(Pass::ClipMaps)) clip_.uploadCameras();
    previewing_ = source;
    try {
        for (const PlannedPass& p : lastPlan_.passes) {
            timers_.begin(passInfo(p.pass).name);
            run(p.pass, p.pass == Pass::ClipMaps ? frame : shaded);
            timers_.end();
        }
    } catch (...) {
        previewing_.reset();
        target_ = kExactImage;
        throw;
    }
    previewing_.reset();
    target_ = kExactImage;
    markShown(frame, false);
    shownPreviewAmbient_ = source;
}

bool Renderer::showingPreview(const FrameDescription& frame) const {
    return shownFrame_ && !shownExact_ && *shownFrame_ == frame && shownVersions_ == currentVersions() &&
           shownAppearanceVersion_ == appearanceVersion_ && shownPreviewAmbient_ == previewAmbient();
}

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
    // Slices sized from the slowest rate measured so far to fill the budget; the first of each phase is a small
    // probe (1/512 of the grid), so a budget is overrun at most by a probe or by bricks slower than any before.
    using Clock = std::chrono::steady_clock;
    auto start = Clock::now();
    auto elapsedMs = [&] { return std::chrono::duration<double, std::milli>(Clock::now() - start).count(); };
    timers_.begin(passInfo(Pass::LaoPrecompute).name);
    bool first = true;
    while (!ao_->precomputeDone() && (first || elapsedMs() < budgetMs)) {
        int phase = ao_->precomputePhase();
        double rate = precomputeBricksPerMs_[phase];
        double left = std::max(budgetMs - elapsedMs(), 1.0);
        std::uint32_t bricks = sliceBricks > 0 ? sliceBricks
                               : rate > 0     ? static_cast<std::uint32_t>(std::clamp(rate * left, 1.0, double(ao_->totalBricks())))
                                              : std::max<std::uint32_t>(ao_->totalBricks() / 512, 1);
        auto sliceStart = Clock::now();
        std::uint32_t ran = ao_->advancePrecompute(*tf_, bricks);
        glFinish();
        double ms = std::chrono::duration<double, std::milli>(Clock::now() - sliceStart).count();
        double measured = ran / ms;
        double& slowest = precomputeBricksPerMs_[phase];
        if (ms > 0.5) slowest = slowest > 0 ? std::min(slowest, measured) : measured;
        first = false;
    }
    timers_.end();
    if (ao_->precomputeDone()) {
        freshness_.markPrecomputed(now);
        slicingFor_.reset();
        return 1.0;
    }
    return ao_->precomputeProgress();
}

void Renderer::run(Pass pass, const FrameDescription& frame) {
    switch (pass) {
        case Pass::ClipMaps:
            clip_.setDilatedMapsNeeded(dilatedMapsWanted(frame.shading));
            clip_.update();
            return;
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
            return;
        case Pass::VoxelClipping: ao_->clipVoxels(*tf_, clip_, frame.shading); return;
        case Pass::LaoRecompute:
            ao_->recomputeLao(*tf_);
            ambientWritten_ = true;
            freshness_.markAmbient(currentVersions(), frame.shading);
            return;
        case Pass::TubeGBuffer: tubes_->drawGBuffer(frame, clip_, gbuffer_); return;
        case Pass::RayCast: runRayCast(frame); return;
        case Pass::SlabPass: runSlabPass(frame, lastPlan_.runs(Pass::TubeGBuffer)); return;
        case Pass::Composite: runComposite(frame); return;
        case Pass::IsmosRayCast:
            if (!ismos_) ismos_ = std::make_unique<IsmosPass>();
            runRayCast(frame, true);
            return;
        case Pass::IsmosOcclusion:
            ismos_->runOcclusion(frame, ismosSpaceOf(frame), volume_.geometry().worldCenter(), targetTexture());
            return;
        case Pass::Count: break;
    }
    throw SystemError("frame plan: a pass without code");
}

IsmosSpace Renderer::ismosSpaceOf(const FrameDescription& frame) const {
    return ismosSpace(frame, volume_.geometry().worldCenter(), volume_.geometry().boundingRadiusMm());
}

int Renderer::runRayCast(const FrameDescription& frame, bool ismosLayers, int firstBand, int bandCount) {
    // ISMOS pass 1 is this ray caster shading with the mode's base (phong or solid) plus the layer outputs;
    // every other mode compiles without ISMOS_LAYERS, so its program is unchanged.
    ShadingMode shading = ismosLayers ? frame.ismos.base : frame.shading;
    gl::Defines defines;
    SampleShadingPiece::addDefines(defines, shading);
    SampleShadingPiece::addCutFaceDefines(defines, frame.raycast.cutFace, clip_.count());
    clip_.addDefines(defines);
    bool tubes = ismosLayers && lastPlan_.runs(Pass::TubeGBuffer);
    if (ismosLayers) IsmosPass::addLayerDefines(defines, frame.ismos);
    if (tubes) defines.emplace_back("ISMOS_TUBES", "1");
    if (countSamples_) defines.emplace_back("COUNT_SAMPLES", "1");
    tf_->addDefines(defines);
    gl::Program& p = raycastPrograms_.get(defines);

    CameraRayPiece{frame}.apply(p);
    VolumePiece{volume_}.apply(p);
    tf_->apply(p);
    clip_.apply(p);
    SampleShadingPiece{shading, laoSettings_.ambientScale, shadedAmbientTexture(), frame.raycast.cutFace}.apply(p);
    setLightingUniforms(p, frame, tf_->material());
    if (ismosLayers) ismos_->applyLayers(p, frame, ismosSpaceOf(frame), resolveStepMm(frame.raycast));
    if (tubes) glBindTextureUnit(binding::tubeDepth, gbuffer_.depth());
    p.set("stepMm", static_cast<float>(resolveStepMm(frame.raycast)));
    p.set("earlyTerminationAlpha", static_cast<float>(frame.raycast.earlyTerminationAlpha));
    p.set("jitterSeed", static_cast<unsigned>(frame.raycast.jitterSeed));
    p.set("skipEmptySpace", frame.raycast.skipEmptySpace ? 1 : 0);
    p.set("volumeSize", volume_.geometry().dims);
    p.set("brickSize", GpuVolume::brickSize);
    p.set("maxSkipBricks", emptySpaceJumpLimit_);
    glBindTextureUnit(binding::occupancy, occupancy_.name());
    glBindImageTexture(binding::imageOutput, targetTexture(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    if (countSamples_) {
        if (!sampleCounter_) {
            sampleCounter_ = gl::createBuffer();
            glNamedBufferStorage(sampleCounter_.name(), 16, nullptr, GL_DYNAMIC_STORAGE_BIT | GL_MAP_READ_BIT);
        }
        // Samples taken, loop steps, steps per half of the dispatch: zeroed at the frame's first band, so an
        // exact frame in slices counts all of its bands.
        const std::uint32_t zero[4] = {0, 0, 0, 0};
        if (firstBand == 0) glNamedBufferSubData(sampleCounter_.name(), 0, 16, zero);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding::ssboSampleCounter, sampleCounter_.name());
    }
    // An exact frame's ray cast covers its recast region; a preview's and ISMOS's, every pixel.
    TileOrderPiece tiles{frame.size, tileRowsPerBand_};
    if (target_ == kExactImage && !ismosLayers && recastRegion_) {
        glm::uvec2 tileSize(p.workGroupSize());
        if (!recastSpans_ || recastSpans_->tileSize != tileSize) {
            recastSpans_ = tileSpansOf(*recastRegion_, tileSize);
            recastSpanBuffer_ = gl::createBuffer();
            glNamedBufferStorage(recastSpanBuffer_.name(), static_cast<GLsizeiptr>(std::max<std::size_t>(recastSpans_->rows.size(), 1) * sizeof(glm::uvec2)),
                                 recastSpans_->rows.data(), 0);
        }
        tiles.spans = &*recastSpans_;
        tiles.spanBuffer = recastSpanBuffer_.name();
    }
    int bands = tiles.bandCount(p.workGroupSize());
    tiles.dispatchBands(p, firstBand, bandCount < 0 ? bands : bandCount);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    return bands;
}

void Renderer::runSlabPass(const FrameDescription& frame, bool withTubes) {
    // Without tubes only dos comes here (all rays advance slice by slice together); with tubes every mode.
    GLuint ambient = usesAmbientOcclusion(frame.shading) ? shadedAmbientTexture() : 0;
    slab_.run(SlabInputs{frame, volume_, *tf_, clip_, SampleShadingPiece{frame.shading, laoSettings_.ambientScale, ambient, frame.raycast.cutFace}, targetTexture(),
                         withTubes ? &gbuffer_ : nullptr, withTubes ? tubeShading_.geometryOpacity : 0.0, tubeShading_.thicknessMm});
    slabUsed_ = true;
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
}

void Renderer::runComposite(const FrameDescription& frame) {
    if (!compositeProgram_) compositeProgram_ = gl::Program::compute("tube_composite.comp");
    if (poissonCount_ != tubeShading_.vicinitySamples) {
        std::vector<glm::vec2> disk = poissonDisk(tubeShading_.vicinitySamples);
        poissonDisk_ = gl::createBuffer();
        glNamedBufferStorage(poissonDisk_.name(), static_cast<GLsizeiptr>(std::max<std::size_t>(disk.size(), 1) * sizeof(glm::vec2)),
                             disk.data(), 0);
        poissonCount_ = tubeShading_.vicinitySamples;
    }
    gl::Program& c = compositeProgram_;
    CameraRayPiece{frame}.apply(c);
    setLightingUniforms(c, frame, tubeShading_.material);
    c.set("poissonCount", poissonCount_);
    // Section 3.1.5: the vicinity radius l_vicinity tan(theta), projected at the surface's depth.
    double pixelsPerMmAtUnitDepth = frame.camera.pixelsPerMmAtUnitDepth(frame.size.y);
    c.set("vicinityRadiusPixelsAtUnitDepth",
          static_cast<float>(tubeShading_.vicinityDistanceMm * std::tan(glm::radians(frame.dos.coneAngleDeg)) * pixelsPerMmAtUnitDepth));
    c.set("depthBiasMm", static_cast<float>(tubeShading_.depthBiasMm));
    c.set("useOcclusion", traits(frame.shading).occludesTubes ? 1 : 0);
    c.set("lineDiffuseExponent", static_cast<float>(tubeShading_.lineDiffuseExponent));
    glBindImageTexture(binding::imageOutput, targetTexture(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    glBindTextureUnit(binding::tubeDepth, gbuffer_.depth());
    glBindTextureUnit(binding::tubeColor, gbuffer_.color());
    glBindTextureUnit(binding::tubeNormal, gbuffer_.normal());
    glBindTextureUnit(binding::partialOcclusion, gbuffer_.partialOcclusion());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding::ssboPoissonDisk, poissonDisk_.name());
    c.dispatchCovering(glm::uvec3(static_cast<unsigned>(frame.size.x), static_cast<unsigned>(frame.size.y), 1u));
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
}

void Renderer::finish() const { glFinish(); }

std::uint64_t Renderer::samplesLastFrame() const {
    if (!sampleCounter_) return 0;
    std::uint32_t count = 0;  // one 32-bit counter: ample for a frame (4e9 samples)
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);   // written by shader atomics
    glGetNamedBufferSubData(sampleCounter_.name(), 0, 4, &count);
    return count;
}

std::uint64_t Renderer::rayStepsLastFrame() const {
    if (!sampleCounter_) return 0;
    std::uint32_t count = 0;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(sampleCounter_.name(), 4, 4, &count);
    return count;
}

glm::dvec2 Renderer::rayStepsByDispatchHalf() const {
    if (!sampleCounter_) return glm::dvec2(0.0);
    std::uint32_t halves[2] = {0, 0};
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(sampleCounter_.name(), 8, 8, halves);
    return {halves[0], halves[1]};
}

Image Renderer::readImage() const {
    Image image;
    const OutputImage& shown = images_[shownImage_];
    image.width = shown.size.x;
    image.height = shown.size.y;
    image.pixels.resize(static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height));
    // The shader writes row 0 as the top of the picture, which is also Image's convention.
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);  // written by image stores
    glGetTextureImage(shown.texture.name(), 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(image.pixels.size() * sizeof(glm::vec4)),
                      image.pixels.data());
    return image;
}

FrameTimings Renderer::collectTimings() {
    FrameTimings timings;
    for (const auto& [name, ms] : timers_.collectMilliseconds())
        for (const PassInfo& info : allPasses())
            if (name == info.name) timings.passes.push_back({info.id, ms});
    return timings;
}

std::vector<GpuAllocation> Renderer::gpuAllocations() const {
    const char* volumeFormat = volume_.format() == StorageFormat::UNorm8    ? "R8 3D"
                               : volume_.format() == StorageFormat::UNorm16 ? "R16 3D"
                                                                            : "R32F 3D";
    glm::ivec3 grid = volume_.brickGrid(), seen = volume_.seenBrickGrid();
    std::vector<GpuAllocation> list{
        {Resource::Volume, volume_.gpuBytes(), volumeFormat},
        {Resource::TransferFunction, static_cast<std::size_t>(tf_->tableSize()) * 16u, {}},
        {Resource::GradientOpacity, TransferFunctionTexture::gradientTableSize * 4u, {}},
        {Resource::Occupancy, static_cast<std::size_t>(grid.x) * static_cast<std::size_t>(grid.y) * static_cast<std::size_t>(grid.z), {}},
        {Resource::OutputImage, static_cast<std::size_t>(images_[kExactImage].size.x) * static_cast<std::size_t>(images_[kExactImage].size.y) * 16u, {}},
    };
    if (images_[kPreviewImage].texture)
        list.push_back({Resource::PreviewImage,
                        static_cast<std::size_t>(images_[kPreviewImage].size.x) * static_cast<std::size_t>(images_[kPreviewImage].size.y) * 16u, {}});
    if (labels_) list.push_back({Resource::LabelVolume, labels_->gpuBytes(), {}});
    if (seenBricks_)
        list.push_back({Resource::SeenBricks, static_cast<std::size_t>(seen.x) * static_cast<std::size_t>(seen.y) * static_cast<std::size_t>(seen.z), {}});
    if (clip_.count() > 0) {
        list.push_back({Resource::ClipMeshGeometry, clip_.geometryBytes(), {}});
        list.push_back({Resource::ClipMaps, clip_.gpuBytes(), {}});
    }
    if (ao_)
        for (const GpuAllocation& a : ao_->allocations()) list.push_back(a);
    if (slabUsed_) list.push_back({Resource::OcclusionBuffers, slab_.gpuBytes(), {}});
    if (ismos_)
        for (const GpuAllocation& a : ismos_->allocations()) list.push_back(a);
    if (tubes_) {
        list.push_back({Resource::TubeGeometry, tubes_->gpuBytes(), tubes_->lines() ? "line vertex buffers" : "triangle vertex buffers"});
        list.push_back({Resource::GBuffer, gbuffer_.gpuBytes(), {}});
    }
    return list;
}

}  // namespace curette
