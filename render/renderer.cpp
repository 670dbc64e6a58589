#include "render/renderer.h"

#include "render/passes/gpu_tube_builder.h"

#include "base/error.h"
#include "render/model/brick_distance.h"
#include "render/shader_pieces.h"

#include <algorithm>

namespace curette {

Renderer::Renderer(gl::Context& context, const VolumeData& volume, const TransferFunction& tf)
    : context_(context), volume_(context.info(), volume), valueHistogram_(ValueHistogram::of(volume, kPlacementHistogramBins, kPlacementHistogramVoxels)),
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
    for (SliceSizer& sizer : precomputeSizers_) sizer.restart();
    ++versions_.laoSettings;
    freshness_.forgetAmbientOcclusion();
}

void Renderer::setTransferFunction(const TransferFunction& tf) {
    tf_ = std::make_unique<TransferFunctionTexture>(tf, volume_.valueScale(), volume_.valueOffset(), volume_.hasNoData());
    tf_->attachLabels(labels_.get());
    tf_->attachRemoval(removalTexture_.get());
    ++versions_.transferFunction;  // V_PAO and V_AO depend on the TF (the reference implementation's bug 4)
    medianExtinctionPerMm_ = medianVisibleExtinctionPerMm(valueHistogram_, tf);
    updateOccupancy();
}

PhongShading Renderer::phongShading(const FrameDescription& frame) const {
    if (phongShadingOverride_) return *phongShadingOverride_;
    glm::dvec3 sides = glm::dvec3(volume_.geometry().dims) * volume_.geometry().spacing();
    return phongShadingPlacement(medianExtinctionPerMm_, frame.raycast.earlyTerminationAlpha, (sides.x + sides.y + sides.z) / 3.0);
}

void Renderer::setLabels(std::unique_ptr<LabelOverlay> labels) {
    labels_ = std::move(labels);
    if (labels_) labels_->setLayout(volume_.layout());
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

bool Renderer::labelFieldPending() const { return labels_ && labels_->fieldPending(); }

double Renderer::advanceLabelField(double budgetMs, int planesPerSlice) {
    if (labels_) labels_->advanceField(budgetMs, planesPerSlice);
    return labelFieldProgress();
}

double Renderer::labelFieldProgress() const { return labels_ ? labels_->fieldProgress() : 1.0; }

int Renderer::clipMapsToDraw(const FrameDescription& frame) const { return clip_.meshesNeedingMaps(dilatedMapsWanted(frame.shading)); }

void Renderer::advanceClipMaps(const FrameDescription& frame) {
    clip_.setDilatedMapsNeeded(dilatedMapsWanted(frame.shading));
    clip_.update(1);
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
    auto ao = std::make_unique<AmbientOcclusion>(volume_, laoSettings_, &seenBricks_);
    if (removalTexture_) ao->setRemoval(removal_.get(), removalTexture_.get());
    return ao;
}

void Renderer::setRemoval(std::shared_ptr<const plan::RemovalVolume> removal) {
    if (removal == removal_) return;
    if (removal && removal->dims() != volume_.geometry().dims)
        throw std::logic_error("Renderer::setRemoval: the removal is not on the scan grid");
    removal_ = std::move(removal);
    removalTexture_.reset();
    tf_->attachRemoval(nullptr);
    if (ao_) ao_->setRemoval(nullptr, nullptr);
    syncRemoval();
}

void Renderer::syncRemoval() {
    if (!removal_) return;
    if (!removalTexture_) {
        if (removal_->empty()) return;   // never drilled: no texture, no shader variant
        removalTexture_ = std::make_unique<RemovalTexture>(volume_.layout(), volume_.geometry().indexToWorld);
    }
    removalTexture_->update(*removal_, AmbientOcclusion::dilationRadiusMm(laoSettings_, volume_.geometry()));
    tf_->attachRemoval(removalTexture_.get());
    if (ao_) ao_->setRemoval(removal_.get(), removalTexture_.get());
}

void Renderer::ensureOutput(int index, glm::ivec2 size) {
    OutputImage& image = images_[index];
    if (size == image.size && image.texture) return;
    image.texture = gl::createTexture(GL_TEXTURE_2D);
    glTextureStorage2D(image.texture.name(), 1, GL_RGBA32F, size.x, size.y);
    glObjectLabel(GL_TEXTURE, image.texture.name(), -1, index == kExactImage ? "output image" : "preview image");
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

void Renderer::setTubeImpostors(const TubeImpostors& impostors, const TubeShading& shading) {
    tubes_.reset();
    tubes_ = std::make_unique<TubeSet>(impostors);
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
    v.removal = removal_ ? removal_->version() : 0;
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
    in.labels = labels_ != nullptr;
    in.drilled = removalTexture_ != nullptr || (removal_ && !removal_->empty());
    in.tubes = tubes_ != nullptr;
    in.tubesInView = tubesInView(frame);
    in.precomputedCurrent = ao_ && freshness_.precomputedCurrent(now);
    in.ambientCurrent = ao_ && freshness_.ambientCurrent(now, frame.shading);
    in.ismosExact = frame.ismos.partial && !frame.ismos.fit;
    in.ismosFit = frame.ismos.partial && frame.ismos.fit;
    in.gradientVolume = gradientVolumeOn_ && gradientVolumeSupported();
    in.gradientVolumeCurrent = gradients_.built();
    return in;
}

FramePlan Renderer::plan(const FrameDescription& frame) const { return planFrame(planInputs(frame)); }

void Renderer::validateSize(const FrameDescription& frame) const {
    if (frame.size.x < 1 || frame.size.y < 1 || frame.size.x > context_.info().maxTextureSize ||
        frame.size.y > context_.info().maxTextureSize)
        throw InputError("<frame>", "size", "between 1x1 and the GL maximum texture size",
                         std::to_string(frame.size.x) + "x" + std::to_string(frame.size.y));
}

IsmosSpace Renderer::ismosSpaceOf(const FrameDescription& frame) const {
    return ismosSpace(frame, volume_.geometry().worldCenter(), volume_.geometry().boundingRadiusMm());
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
    const OutputImage& shown = images_[shownImageIndex()];
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
    if (gradients_.built()) list.push_back({Resource::GradientVolume, gradients_.gpuBytes(), {}});
    if (labels_) list.push_back({Resource::LabelVolume, labels_->gpuBytes(), {}});
    if (removalTexture_) list.push_back({Resource::DrilledRemoval, removalTexture_->gpuBytes(), {}});
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
        list.push_back({Resource::TubeGeometry, tubes_->gpuBytes(), tubes_->impostors() ? "impostor points, RGBA32UI"
                                                             : tubes_->lines() ? "line vertex buffers" : "triangle vertex buffers"});
        list.push_back({Resource::GBuffer, gbuffer_.gpuBytes(), {}});
    }
    return list;
}

}  // namespace curette
