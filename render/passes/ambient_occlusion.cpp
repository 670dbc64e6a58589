#include "render/passes/ambient_occlusion.h"

#include "mesh/coverage.h"

#include "base/error.h"
#include "base/progress.h"
#include "gl/bindings.h"
#include "render/model/setting_limits.h"
#include "render/model/worker_deal.h"
#include "render/shader_pieces.h"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cstdlib>
#include <limits>

namespace curette {

namespace {

// V_o reads zero beyond the volume (lao_ray.glsl); V_m holds integer categories; V_PAO and V_AO are unorm16.
const VolumeTextureFormat kOpacityFormat{GL_R16, GL_RED, GL_UNSIGNED_SHORT, 2, true, true};
const VolumeTextureFormat kMaskFormat{GL_R8UI, GL_RED_INTEGER, GL_UNSIGNED_BYTE, 1, false, false};
const VolumeTextureFormat kAmbientFormat{GL_R16, GL_RED, GL_UNSIGNED_SHORT, 2, true, false};

}  // namespace

AmbientOcclusion::AmbientOcclusion(const GpuVolume& volume, const LaoSettings& settings, const gl::Texture* seenBricks)
    : volume_(volume), settings_(settings), seenBricks_(settings.onlyWhereSeen ? seenBricks : nullptr), laoReach_(volume.geometry(), reachMm(settings)) {
    requireWithin(limits::laoSamples, settings.samples, "<lao settings>", "samples");
    requireWithin(limits::laoStepMm, settings.stepMm, "<lao settings>", "step_mm");
    requireWithin(limits::laoAntiAliasingSamples, settings.antiAliasingSamples, "<lao settings>", "antialiasing_samples");
    glm::ivec3 dims = volume.geometry().dims;
    // Step V numbers voxels as 32-bit uints (lao_common.glsl, the recompute list).
    if (std::uint64_t(dims.x) * std::uint64_t(dims.y) * std::uint64_t(dims.z) > 0xFFFFFFFFull)
        throw SystemError("the volume has more than 2^32 - 1 voxels, more than step V can number; lao and cao need a smaller volume");
    std::size_t bricks = BrickSet::none(dims).brickCount();
    // The visited-brick list numbers bricks in 30 bits (shaders/visit_bricks.glsl).
    if (bricks > 0x3FFFFFFFull) throw SystemError("the volume has more than 2^30 bricks of 4^3 voxels, more than steps IV and V can number");
    const VolumeLayout& layout = volume.layout();
    opacity_ = createVolumeTexture(layout, kOpacityFormat, "V_o (clipped opacity)");
    mask_ = createVolumeTexture(layout, kMaskFormat, "V_m (categories)");
    precomputed_ = createVolumeTexture(layout, kAmbientFormat, "V_PAO (unclipped LAO)");
    ambient_ = createVolumeTexture(layout, kAmbientFormat, "V_AO");

    std::vector<glm::vec4> aa;
    for (const glm::dvec3& o : antiAliasingOffsets(std::max(settings.antiAliasingSamples, 1))) aa.emplace_back(glm::vec3(o), 0.0f);
    antiAliasing_ = gl::createBuffer();
    glNamedBufferStorage(antiAliasing_.name(), static_cast<GLsizeiptr>(aa.size() * sizeof(glm::vec4)), aa.data(), 0);

    // Directions as one LAO step in texture coordinates, with w = w_k / (K * M) folding eq. 3's 1/K and
    // eq. 2's 1/M into one factor.
    std::vector<LaoDirection> list = settings.directions.build();
    directionCount_ = static_cast<int>(list.size());   // K: what the kernel loops over is what it is given
    glm::dmat3 worldToTexture(volume.geometry().worldToTexture());
    std::vector<glm::vec4> packed;
    for (const LaoDirection& d : list)
        packed.emplace_back(glm::vec3(worldToTexture * (d.direction * settings.stepMm)),
                            static_cast<float>(d.weight / (double(list.size()) * settings.samples)));
    directions_ = gl::createBuffer();
    glNamedBufferStorage(directions_.name(), static_cast<GLsizeiptr>(packed.size() * sizeof(glm::vec4)), packed.data(), 0);

    if (const char* forced = std::getenv("CURETTE_RECOMPUTE_LIST_BRICKS")) {
        long n = std::strtol(forced, nullptr, 10);
        if (n < 1) throw InputError("CURETTE_RECOMPUTE_LIST_BRICKS", "value", "a whole number of bricks, at least 1", forced);
        listChunkBricks_ = static_cast<std::uint32_t>(std::min<long>(n, kListChunkBricks));
    }
    if (settings.dispatch == LaoSettings::Dispatch::Compacted) {
        // A chunk's voxels, then every chunk's count (beginRecompute's counting pass builds the first chunk's list
        // while it counts the others).
        std::size_t chunks = (bricks + listChunkBricks_ - 1) / listChunkBricks_;
        chunkCountsAt_ = std::size_t(kVisitBrickSize * kVisitBrickSize * kVisitBrickSize) * std::min<std::size_t>(listChunkBricks_, bricks);
        listCapacity_ = chunkCountsAt_ + chunks;
        list_ = gl::createBuffer();
        glNamedBufferStorage(list_.name(), static_cast<GLsizeiptr>(8 + 4 * listCapacity_), nullptr, GL_DYNAMIC_STORAGE_BIT);
        dispatch_ = gl::createBuffer();
        glNamedBufferStorage(dispatch_.name(), 16, nullptr, GL_DYNAMIC_STORAGE_BIT);
    } else {
        list_ = gl::createBuffer();  // holds only the counters in the full-grid variant
        glNamedBufferStorage(list_.name(), 8, nullptr, GL_DYNAMIC_STORAGE_BIT);
    }
    visitBricks_ = gl::createBuffer();
    glNamedBufferStorage(visitBricks_.name(), static_cast<GLsizeiptr>(4 * bricks), nullptr, GL_DYNAMIC_STORAGE_BIT);
    gl::Defines defines;
    if (seenBricks_) defines.emplace_back("AO_ONLY_WHERE_SEEN", "1");
    VolumeLayoutPiece{volume.layout()}.addDefines(defines);
    compactProgram_ = gl::Program::compute("lao_compact.comp", defines);
}

AmbientOcclusion::~AmbientOcclusion() = default;

double AmbientOcclusion::reachMm(const LaoSettings& settings) { return (settings.samples - 1) * settings.stepMm; }

double AmbientOcclusion::dilationRadiusMm(const LaoSettings& settings, const VolumeGeometry& geometry) {
    // Derivation of the dilation radius: how far from a clipped point s can a voxel v be whose V_AO changes?
    //  - v's LAO (lao_ray.glsl) reads V_o trilinearly at points q with |q - v| <= (M - 1) * step  (reach);
    //  - V_o at q blends voxels u with |q - u| < 1 voxel step per axis (index space), so
    //    |u - q| <= cell diagonal = max over sign vectors of |A (+-1, +-1, +-1)|           (trilinear footprint);
    //  - V_o at u changes only if one of u's clip samples (the centre and the corners of u's own cell, at
    //    h = clip::kCellSampleHalfWidth steps along every axis; the N extra samples lie in that cell) changes side:
    //    |s - u| <= h * cell diagonal                                                      (anti-aliasing reach).
    // So R = reach + (1 + h) * cell diagonal. The maps add one more term, the map-pixel quantisation of both v
    // and s (sqrt(2) pixels) and a rounding epsilon, in clip::ClipMeshSet::kernelRadiusMm.
    return reachMm(settings) + (1.0 + clip::kCellSampleHalfWidth) * geometry.cellDiagonalMm();
}

gl::Defines AmbientOcclusion::laoDefines(float opacityExponent) const {
    // What lao_ray.glsl compiles in: K, M, and whether the opacity correction is the identity. The exponent is
    // compared as the float the shader would raise to, so the identity stands in for pow(x, 1.0) only.
    gl::Defines defines;
    if (seenBricks_) defines.emplace_back("AO_ONLY_WHERE_SEEN", "1");
    defines.emplace_back("LAO_DIRECTIONS", std::to_string(directionCount_));
    defines.emplace_back("LAO_SAMPLES", std::to_string(settings_.samples));
    if (opacityExponent == 1.0f) defines.emplace_back("LAO_UNIT_STEP", "1");
    VolumeLayoutPiece{volume_.layout()}.addDefines(defines);
    return defines;
}

gl::Program& AmbientOcclusion::laoProgram(float opacityExponent) { return laoPrograms_.get(laoDefines(opacityExponent)); }

void AmbientOcclusion::setLaoUniforms(gl::Program& p, float opacityExponent) {
    // lao_ray.glsl's uniforms (lao.comp only; the compaction pass casts no ray).
    glm::ivec3 dims = volume_.geometry().dims;
    p.set("laoTextureMargin", glm::vec3(0.5 / glm::dvec3(dims)));
    p.set("laoOpacityExponent", opacityExponent);
    VolumeLayoutPiece{volume_.layout()}.apply(p);
}

std::uint32_t AmbientOcclusion::uploadVisit(const BrickSet& bricks, const BrickSet& withinReach, const BrickSet& deep, bool laoEverywhere) {
    std::vector<std::uint32_t> tested, inside, beyond;
    for (std::uint32_t b : bricks.visitedIndices()) (deep.visited[b] ? inside : withinReach.visited[b] ? tested : beyond).push_back(b);
    std::vector<std::uint32_t> list;
    for (const std::vector<std::uint32_t>* part : {&tested, &inside, &beyond})
        for (std::uint32_t b : dealtToWorkerThreads(*part, llvmpipeWorkerThreads())) list.push_back(b);
    testedSlots_ = static_cast<std::uint32_t>(tested.size());
    deepSlotsEnd_ = testedSlots_ + static_cast<std::uint32_t>(inside.size());
    clipUnits_ = kTestedBrickCost * testedSlots_ + (static_cast<std::uint32_t>(list.size()) - testedSlots_);
    if (laoEverywhere)
        for (std::uint32_t& entry : list) entry |= kVisitLaoCanChange;
    laoFlagsPending_ = !laoEverywhere;
    if (!list.empty())
        glNamedBufferSubData(visitBricks_.name(), 0, static_cast<GLsizeiptr>(4 * list.size()), list.data());
    visitCount_ = static_cast<std::uint32_t>(list.size());
    return visitCount_;
}

void AmbientOcclusion::markLaoBricks() {
    // Step IV set kVisitOpacityChanged on the bricks where it clipped a voxel with opacity; read the list back,
    // flag the bricks a changed brick lies within LAO reach of, and upload it for step V.
    std::vector<std::uint32_t> list(visitCount_);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);   // the flags were written by shader atomics
    glGetNamedBufferSubData(visitBricks_.name(), 0, static_cast<GLsizeiptr>(4 * list.size()), list.data());
    const glm::ivec3 grid = visitBrickGrid(volume_.geometry().dims);
    std::vector<std::uint8_t> changed(std::size_t(grid.x) * std::size_t(grid.y) * std::size_t(grid.z), 0);
    if (clippedBricks_.size() != changed.size()) {
        clippedBricks_.assign(changed.size(), 0);
        clippedBricksKnown_ = false;
    }
    // Where the meshes left alone reach and this update does not visit, V_o is what step IV made it when it last
    // visited the brick, clipped or not (nothing that reaches it changed since).
    for (std::size_t b = 0; b < changed.size() && b < stillBricks_.visited.size(); ++b)
        if (stillBricks_.visited[b] && !(lastVisit_ && lastVisit_->visited[b]))
            changed[b] = clippedBricksKnown_ ? clippedBricks_[b] : std::uint8_t(1);
    // Drilled bricks this update does not visit: their V_o is the drilled one, not step I's.
    if (removal_)
        for (std::size_t b = 0; b < changed.size(); ++b)
            if (removalTexture_->drilledBricks()[b] && !(lastVisit_ && lastVisit_->visited[b])) changed[b] = 1;
    // The visited bricks: what step IV just found, kept for the updates that will leave them.
    for (std::uint32_t entry : list)
        changed[entry & kVisitBrickNumber] = clippedBricks_[entry & kVisitBrickNumber] = (entry & kVisitOpacityChanged) ? 1 : 0;
    if (list.size() == changed.size()) clippedBricksKnown_ = true;   // every brick visited
    laoReach_.setChanged(grid, changed);
    std::uint64_t lao = 0;
    for (std::uint32_t& entry : list) {
        std::uint32_t b = entry & kVisitBrickNumber;
        bool can = laoReach_.canChange(visitBrickAt(b, grid));
        entry = b | (can ? kVisitLaoCanChange : 0u);
        lao += can;
    }
    stats_.laoBricks = lao;
    glNamedBufferSubData(visitBricks_.name(), 0, static_cast<GLsizeiptr>(4 * list.size()), list.data());
    laoFlagsPending_ = false;
}

void AmbientOcclusion::setVisitUniforms(gl::Program& p) const {
    p.set("visitBrickCount", visitCount_);
    p.set("visitSlotOffset", 0u);
    p.set("brickGrid", visitBrickGrid(volume_.geometry().dims));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding::ssboVisitBricks, visitBricks_.name());
}

void AmbientOcclusion::setDecisionUniforms(gl::Program& p) const {
    // lao_common.glsl's: the voxels no visible sample reads (ambientSeen).
    if (!seenBricks_) return;
    p.set("seenBrickSize", GpuVolume::seenBrickSize);
    glBindTextureUnit(binding::seenBricks, seenBricks_->name());
}

void AmbientOcclusion::runVoxelClipping(const TransferFunctionTexture& tf, const clip::ClipMeshSet* clip, bool testDilation,
                                        bool applyDrill, std::uint32_t from, std::uint32_t to) {
    // Each slice takes its share of every part (uploadVisit): a tested brick costs several times another, so
    // slices of the list in order would cost unlike each other, and one sized by the last one's rate
    // (render/frame_run.h SliceSizer) would overrun its budget.
    const std::uint32_t partBegin[3] = {0, testedSlots_, deepSlotsEnd_}, partEnd[3] = {testedSlots_, deepSlotsEnd_, visitCount_};
    const SampleCount counts[3] = {SampleCount::Tested, SampleCount::AllInside, SampleCount::NoneInside};
    auto doneAt = [&](int part, std::uint32_t progress) {
        return partBegin[part] + static_cast<std::uint32_t>(std::uint64_t(partEnd[part] - partBegin[part]) * progress / std::max(clipUnits_, 1u));
    };
    for (int part = 0; part < 3; ++part) {
        std::uint32_t first = doneAt(part, from), last = doneAt(part, to);
        if (last > first) dispatchVoxelClipping(tf, clip, testDilation, applyDrill, counts[part], first, last - first);
    }
}

void AmbientOcclusion::dispatchVoxelClipping(const TransferFunctionTexture& tf, const clip::ClipMeshSet* clip, bool testDilation,
                                             bool applyDrill, SampleCount count, std::uint32_t firstSlot, std::uint32_t slots) {
    gl::Defines defines;
    if (count == SampleCount::AllInside) defines.emplace_back("DEEP_INSIDE_MESH", "1");
    if (count == SampleCount::NoneInside) defines.emplace_back("BEYOND_SAMPLE_REACH", "1");
    tf.addDefines(defines);
    NoDataPiece{volume_}.addDefines(defines);
    VolumeLayoutPiece{volume_.layout()}.addDefines(defines);
    gl::Program& p = clipPrograms_.get(defines);
    const VolumeGeometry& g = volume_.geometry();
    tf.apply(p);
    NoDataPiece{volume_}.apply(p);
    VolumeLayoutPiece{volume_.layout()}.apply(p);
    p.set("indexToWorld", glm::mat4(g.indexToWorld));
    p.set("volumeSize", g.dims);
    p.set("antiAliasingSamples", settings_.antiAliasingSamples);
    p.set("testDilation", testDilation ? 1 : 0);
    p.set("applyDrill", applyDrill ? 1 : 0);
    p.set("gradientToWorld", glm::mat3(g.gradientIndexToWorld() * volume_.valueScale()));
    if (clip) clip->apply(p);
    else p.set("clipMeshCount", 0);
    p.set("sampleReachMm", static_cast<float>(clipSampleReachMm(g)));
    glBindTextureUnit(binding::volume, volume_.texture());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding::ssboAntiAliasing, antiAliasing_.name());
    glBindImageTexture(binding::imageOpacity, opacity_.name(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R16);
    glBindImageTexture(binding::imageMask, mask_.name(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R8UI);
    setVisitUniforms(p);
    p.set("visitSlotOffset", firstSlot);
    glm::uvec2 grid = workGroupGrid(slots);
    p.use();
    glDispatchCompute(grid.x, grid.y, 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

gl::Program& AmbientOcclusion::bindLao(GLuint target, float opacityExponent) {
    gl::Program& program = laoProgram(opacityExponent);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding::ssboRecomputeList, list_.name());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding::ssboLaoDirections, directions_.name());
    glBindTextureUnit(binding::opacity, opacity_.name());
    glBindTextureUnit(binding::mask, mask_.name());
    glBindTextureUnit(binding::precomputedAo, precomputed_.name());
    glBindImageTexture(binding::imageAmbient, target, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R16);
    setLaoUniforms(program, opacityExponent);
    program.set("volumeSize", volume_.geometry().dims);
    program.set("listOffset", 0u);
    setVisitUniforms(program);
    setDecisionUniforms(program);
    return program;
}

void AmbientOcclusion::buildRecomputeList(std::uint32_t firstSlot, std::uint32_t bricks, std::uint32_t countChunks) {
    // Every visited voxel's decision: copies and unreachable voxels are written here, the rest appended (or counted).
    compactProgram_.set("volumeSize", volume_.geometry().dims);
    compactProgram_.set("maxGroupsX", kMaxWorkGroupsX);
    VolumeLayoutPiece{volume_.layout()}.apply(compactProgram_);
    setVisitUniforms(compactProgram_);
    compactProgram_.set("visitSlotOffset", firstSlot);
    setDecisionUniforms(compactProgram_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding::ssboDispatch, dispatch_.name());
    compactProgram_.set("prepareDispatch", 0);
    compactProgram_.set("countChunks", countChunks);
    compactProgram_.set("chunkCountsAt", static_cast<std::uint32_t>(chunkCountsAt_));
    compactProgram_.use();
    glm::uvec2 grid = workGroupGrid(bricks);
    glDispatchCompute(grid.x, grid.y, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void AmbientOcclusion::resetListLength() {
    // The last chunk's LAO dispatch read the list and its length: finish with them before they are rewritten.
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
    const std::uint32_t zero = 0;
    glNamedBufferSubData(list_.name(), 0, 4, &zero);
}

void AmbientOcclusion::readRecomputeCounts() {
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    std::uint32_t counts[2] = {0, 0};
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);   // the counters were written by shader atomics
    glGetNamedBufferSubData(list_.name(), 0, 8, counts);
    listCount_ = counts[0];
    stats_.recomputed = counts[1];
}

void AmbientOcclusion::runLao(GLuint target, bool compacted, float opacityExponent) {
    const std::uint32_t zero[2] = {0, 0};
    glNamedBufferSubData(list_.name(), 0, 8, zero);
    gl::Program& lao = bindLao(target, opacityExponent);
    // One work group per visited brick (shaders/visit_bricks.glsl).
    if (!compacted) {
        glm::uvec2 grid = workGroupGrid(visitCount_);
        lao.set("laoMode", 0);
        lao.use();
        glDispatchCompute(grid.x, grid.y, 1);
    } else {
        // Chunk after chunk of the visited bricks, each its own list (the list holds one chunk).
        for (std::uint32_t first = 0; first < visitCount_; first += listChunkBricks_) {
            if (first > 0) resetListLength();
            buildRecomputeList(first, std::min(listChunkBricks_, visitCount_ - first));
            compactProgram_.set("prepareDispatch", 1);
            glDispatchCompute(1, 1, 1);
            glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
            lao.set("laoMode", 1);
            lao.use();
            glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, dispatch_.name());
            glDispatchComputeIndirect(0);
            glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
        }
    }
    readRecomputeCounts();
}

std::uint32_t AmbientOcclusion::beginRecompute(const TransferFunctionTexture& tf) {
    recomputeGroups_ = recomputeGroupsDone_ = 0;
    if (visitCount_ == 0) return 0;
    if (laoFlagsPending_) markLaoBricks();
    float exponent = static_cast<float>(settings_.stepMm / tf.unitLengthMm());
    if (settings_.dispatch != LaoSettings::Dispatch::Compacted) {
        runLao(ambient_.name(), false, exponent);   // the full-grid baseline is not sliced
        return 0;
    }
    const std::uint32_t zero[2] = {0, 0};
    glNamedBufferSubData(list_.name(), 0, 8, zero);
    bindLao(ambient_.name(), exponent);
    const std::uint32_t chunks = (visitCount_ + listChunkBricks_ - 1) / listChunkBricks_;
    chunkEntries_.assign(chunks, 0);
    // Every chunk's length first (the decisions write the copies here), and the first chunk's list with it (with one
    // chunk, the whole list); the others are built when step V reaches them. The slices are sized on the CPU.
    const GLintptr counts = static_cast<GLintptr>(8 + 4 * chunkCountsAt_);
    glNamedBufferSubData(list_.name(), counts, static_cast<GLsizeiptr>(4 * chunkEntries_.size()), chunkEntries_.data());
    buildRecomputeList(0, visitCount_, listChunkBricks_);
    readRecomputeCounts();   // the first chunk's length
    glGetNamedBufferSubData(list_.name(), counts, static_cast<GLsizeiptr>(4 * chunkEntries_.size()), chunkEntries_.data());
    chunkEntries_[0] = listCount_;
    chunkBuilt_ = true;
    chunk_ = chunkGroupsDone_ = 0;
    recomputeExponent_ = exponent;
    recomputeGroups_ = 0;
    for (std::uint32_t entries : chunkEntries_) recomputeGroups_ += (entries + kLaoGroupSize - 1) / kLaoGroupSize;
    return recomputeGroups_;
}

std::uint32_t AmbientOcclusion::advanceRecompute(std::uint32_t groups) {
    std::uint32_t ran = 0;
    while (ran < groups && recomputeGroupsDone_ < recomputeGroups_) {
        const std::uint32_t chunkGroups = (chunkEntries_[chunk_] + kLaoGroupSize - 1) / kLaoGroupSize;
        if (chunkGroupsDone_ == chunkGroups) {   // on to the next chunk
            ++chunk_;
            chunkGroupsDone_ = 0;
            chunkBuilt_ = false;
            continue;
        }
        // Other passes may have bound their own resources since the last slice.
        gl::Program& lao = bindLao(ambient_.name(), recomputeExponent_);
        if (!chunkBuilt_) {
            resetListLength();
            const std::uint32_t first = chunk_ * listChunkBricks_;
            buildRecomputeList(first, std::min(listChunkBricks_, visitCount_ - first));
            chunkBuilt_ = true;
        }
        std::uint32_t n = std::min(groups - ran, chunkGroups - chunkGroupsDone_);
        lao.set("laoMode", 1);
        lao.set("listOffset", chunkGroupsDone_ * kLaoGroupSize);
        lao.use();
        glm::uvec2 grid = workGroupGrid(n);
        glDispatchCompute(grid.x, grid.y, 1);
        chunkGroupsDone_ += n;
        recomputeGroupsDone_ += n;
        ran += n;
    }
    if (ran == 0) return 0;
    if (recomputeGroupsDone_ == recomputeGroups_) readRecomputeCounts();
    else glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    return ran;
}

void AmbientOcclusion::precompute(const TransferFunctionTexture& tf) {
    // Step I is step IV without meshes (every voxel keeps its TF opacity, all category b) followed by the
    // LAO of every voxel, written to V_PAO: one slice of each phase over the whole grid.
    Progress progress("LAO precompute (step I)", 2);
    beginPrecompute();
    advancePrecompute(tf, totalBricks());
    progress.update(1);
    advancePrecompute(tf, totalBricks());
    progress.finish();
}

std::uint32_t AmbientOcclusion::totalBricks() const { return static_cast<std::uint32_t>(allBricks_.size()); }

void AmbientOcclusion::beginPrecompute() {
    if (allBricks_.empty()) {
        allBricks_ = BrickSet::all(volume_.geometry().dims).visitedIndices();
        for (std::uint32_t& entry : allBricks_) entry |= kVisitLaoCanChange;   // every voxel is category b
    }
    precomputeStarted_ = true;
    slicedBricks_ = 0;
    lastUpdate_.reset();   // V_AO is not written from this V_PAO yet: the next update visits every brick
    carried_.reset();
    clippedBricksKnown_ = false;
}

int AmbientOcclusion::precomputePhase() const {
    if (!precomputeStarted_) return 0;
    return static_cast<int>(slicedBricks_ / std::max<std::uint32_t>(totalBricks(), 1));
}

double AmbientOcclusion::precomputeProgress() const {
    if (!precomputeStarted_ || totalBricks() == 0) return 0.0;
    double total = totalBricks();
    double clipped = std::min<double>(slicedBricks_, total), lao = std::max<double>(0.0, double(slicedBricks_) - total);
    return (1.0 - kLaoShareOfPrecompute) * clipped / total + kLaoShareOfPrecompute * lao / total;
}

void AmbientOcclusion::uploadVisitRange(std::uint32_t first, std::uint32_t count) {
    std::vector<std::uint32_t> slice =
        dealtToWorkerThreads(std::vector<std::uint32_t>(allBricks_.begin() + first, allBricks_.begin() + first + count), llvmpipeWorkerThreads());
    glNamedBufferSubData(visitBricks_.name(), 0, static_cast<GLsizeiptr>(4 * std::size_t(count)), slice.data());
    visitCount_ = count;
    testedSlots_ = deepSlotsEnd_ = 0;   // step I clips without meshes
    clipUnits_ = clipUnitsDone_ = count;   // no step IV under way over this list
    laoFlagsPending_ = false;
}

std::uint32_t AmbientOcclusion::advancePrecompute(const TransferFunctionTexture& tf, std::uint32_t bricks) {
    if (!precomputeStarted_) beginPrecompute();
    std::uint32_t total = totalBricks(), ran = 0;
    // A slice never straddles the phases: the LAO of any voxel may read the V_o of any brick within reach.
    int phase = precomputePhase();
    if (phase >= 2 || bricks == 0) return 0;
    std::uint32_t first = slicedBricks_ - std::uint32_t(phase) * total;
    ran = std::min(bricks, total - first);
    uploadVisitRange(first, ran);
    if (phase == 0) runVoxelClipping(tf, nullptr, false, false, 0, clipUnits_);   // one part: no meshes
    else runLao(precomputed_.name(), false, static_cast<float>(settings_.stepMm / tf.unitLengthMm()));
    slicedBricks_ += ran;
    return ran;
}

void AmbientOcclusion::clipVoxels(const TransferFunctionTexture& tf, const clip::ClipMeshSet& clip, ShadingMode mode) {
    std::uint32_t units = beginClipVoxels(clip, mode);
    advanceClipVoxels(tf, clip, units);
}

std::uint32_t AmbientOcclusion::advanceClipVoxels(const TransferFunctionTexture& tf, const clip::ClipMeshSet& clip, std::uint32_t units) {
    std::uint32_t n = std::min(units, clipUnits_ - clipUnitsDone_);
    if (n == 0) return 0;
    runVoxelClipping(tf, &clip, clipDilation_, applyDrill_, clipUnitsDone_, clipUnitsDone_ + n);
    clipUnitsDone_ += n;
    return n;
}

std::uint32_t AmbientOcclusion::beginClipVoxels(const clip::ClipMeshSet& clip, ShadingMode mode) {
    bool cao = traits(mode).dilatedMaps;   // the mode table's: cao tests the dilated maps and updates in part
    // Full LAO (the baseline) and the first update after step I visit every voxel. A CAO update visits the
    // bricks (render/mesh_voxel_box.h) of the meshes that changed since the last update (pose, scale, geometry,
    // or every mesh when the maps were drawn again or one was added or removed), those they reach now and those
    // they reached then: outside a mesh's bricks nothing depends on it, so elsewhere V_o, V_m and V_AO already
    // hold what a whole-grid pass would write. A mesh that did not change is left where it is: its bricks hold
    // what its state, the same now, made them. A 42 mm sphere moving through the carved head then no longer
    // clips again, and recomputes the LAO around, the still cylinder.
    glm::ivec3 dims = volume_.geometry().dims;
    const bool partial = cao && lastUpdate_;
    const bool sameSet = partial && lastUpdate_->mapRenders == clip.mapRenderCount() && lastUpdate_->meshes.size() == std::size_t(clip.count());
    UpdateMeshes now{clip.mapRenderCount(), {}};
    BrickSet visit = partial ? BrickSet::none(dims) : BrickSet::all(dims);
    stillBricks_ = BrickSet::none(dims);
    for (int i = 0; i < clip.count(); ++i) {
        MeshBricks m{clip.pose(i), clip.scale(i), clip.geometry(i), {}};
        const MeshBricks* last = sameSet ? &lastUpdate_->meshes[std::size_t(i)] : nullptr;
        if (last && m.sameMesh(*last)) {
            m.bricks = last->bricks;   // the same box and ball: the same bricks
            stillBricks_.unite(m.bricks);
        } else {
            m.bricks = bricksAroundMesh(volume_.geometry(), clip, i);
            if (partial) visit.unite(m.bricks);
            if (last) visit.unite(last->bricks);
        }
        now.meshes.push_back(std::move(m));
    }
    if (partial && !sameSet)
        for (const MeshBricks& m : lastUpdate_->meshes) visit.unite(m.bricks);
    if (partial && carried_) visit.unite(*carried_);
    // The drill's changes since the last update: V_o changes in their bricks and LAO within the dilation radius.
    if (removal_) {
        if (partial && removal_->version() != removalApplied_) {
            std::vector<std::uint8_t> changed(removalTexture_->drilledBricks().size(), 0);
            for (std::uint32_t b : removal_->bricksChangedSince(removalApplied_)) changed[b] = 1;
            BrickSet drilled = BrickSet::none(dims);
            drilled.visited = removalTexture_->dilateBricks(changed, dilationRadiusMm());
            visit.unite(drilled);
        }
        removalApplied_ = removal_->version();
    }
    applyDrill_ = removal_ != nullptr;
    carried_.reset();
    lastUpdate_ = std::move(now);
    lastVisit_ = visit;
    if (!cao) clippedBricksKnown_ = false;   // full LAO rewrites V_o everywhere and reads no flags back
    stats_.voxels = std::uint64_t(dims.x) * std::uint64_t(dims.y) * std::uint64_t(dims.z);
    stats_.dispatched = visit.visitedVoxels();
    stats_.recomputed = 0;
    // Full LAO recomputes every visible voxel; CAO only where a changed V_o is within reach (markLaoBricks).
    stats_.bricks = uploadVisit(visit, bricksWithinSampleReach(volume_.geometry(), clip), bricksDeepInsideMeshes(volume_.geometry(), clip), !cao);
    stats_.sampledBricks = testedSlots_;
    stats_.deepBricks = deepSlotsEnd_ - testedSlots_;
    stats_.laoBricks = cao ? 0 : stats_.bricks;
    clipDilation_ = cao;
    clipUnitsDone_ = 0;
    return clipUnits_;
}

void AmbientOcclusion::abandonUpdate() {
    // Step IV rewrote V_o and V_m over any part of lastVisit_ (all of it unless it was abandoned in slices), step V
    // any part of V_AO there. Visiting all of it next time (with the meshes' bricks then) rewrites every voxel this
    // update touched or left stale; outside it nothing was touched since the update before, whose invariant holds.
    if (lastVisit_) carried_ = std::move(*lastVisit_);
    lastVisit_.reset();
    recomputeGroups_ = recomputeGroupsDone_ = 0;
    clipUnitsDone_ = clipUnits_;
}

void AmbientOcclusion::recomputeLao(const TransferFunctionTexture& tf) {
    if (visitCount_ == 0) return;
    if (laoFlagsPending_) markLaoBricks();
    runLao(ambient_.name(), settings_.dispatch == LaoSettings::Dispatch::Compacted,
           static_cast<float>(settings_.stepMm / tf.unitLengthMm()));
}

std::vector<GpuAllocation> AmbientOcclusion::allocations() const {
    glm::ivec3 d = volume_.geometry().dims;
    std::size_t texels = volume_.layout().texelCount();
    std::vector<GpuAllocation> list{{Resource::ClippedOpacity, 2 * texels, {}},
                                    {Resource::CategoryMask, texels, {}},
                                    {Resource::PrecomputedAo, 2 * texels, {}},
                                    {Resource::Ambient, 2 * texels, {}},
                                    // with the visited-brick list (4 bytes per brick)
                                    {Resource::RecomputeList, (settings_.dispatch == LaoSettings::Dispatch::Compacted ? 4 * listCapacity_ + 8 : 8) +
                                                                  4 * BrickSet::none(d).brickCount(), {}},
                                    {Resource::LaoDirections, 16u * std::size_t(directionCount_), {}}};
    return list;
}

std::vector<std::uint16_t> AmbientOcclusion::readAmbient() const {
    return readVolume<std::uint16_t>(ambient_.name(), volume_.layout(), kAmbientFormat);
}
std::vector<std::uint16_t> AmbientOcclusion::readPrecomputed() const {
    return readVolume<std::uint16_t>(precomputed_.name(), volume_.layout(), kAmbientFormat);
}
std::vector<std::uint16_t> AmbientOcclusion::readOpacity() const {
    return readVolume<std::uint16_t>(opacity_.name(), volume_.layout(), kOpacityFormat);
}
std::vector<std::uint8_t> AmbientOcclusion::readMask() const {
    return readVolume<std::uint8_t>(mask_.name(), volume_.layout(), kMaskFormat);
}

void AmbientOcclusion::setRemoval(const plan::RemovalVolume* removal, const RemovalTexture* texture) {
    if ((removal == nullptr) != (texture == nullptr)) throw std::logic_error("AmbientOcclusion::setRemoval: a removal and its texture");
    if (removal && visitBrickGrid(volume_.geometry().dims) != texture->brickGrid())
        throw std::logic_error("AmbientOcclusion::setRemoval: bricks differ from the visited bricks");
    if (removal == removal_ && texture == removalTexture_) return;
    // V_o holds no drilling where no update applied one: a removal attached for the first time is visited where it
    // drilled (every brick changed after version 0). Another removal, or none after one, differs from V_o anywhere
    // the old one drilled: the next update visits every brick.
    if (removal_) lastUpdate_.reset();
    removal_ = removal;
    removalTexture_ = texture;
    removalApplied_ = 0;
}

}  // namespace curette
