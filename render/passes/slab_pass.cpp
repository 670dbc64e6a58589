#include "render/passes/slab_pass.h"

#include "base/error.h"
#include "base/log.h"
#include "gl/bindings.h"
#include "render/lighting.h"
#include "render/model/setting_limits.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace curette {

gl::Program& SlabPass::program(ShadingMode mode, bool tubes, const TransferFunctionTexture& tf, gl::Defines defines) {
    SampleShadingPiece::addDefines(defines, mode);
    if (tubes) defines.emplace_back("HAS_TUBES", "1");
    if (!clampOcclusion_) defines.emplace_back("OCCLUSION_UNCLAMPED", "1");
    tf.addDefines(defines);
    return programs_.get(defines);
}

void SlabPass::ensureBuffers(glm::ivec2 size) {
    if (size == size_ && occlusion_[0]) return;
    for (gl::Texture& t : occlusion_) {
        t = gl::createTexture(GL_TEXTURE_2D);
        glTextureStorage2D(t.name(), 1, GL_RG32F, size.x, size.y);
        glTextureParameteri(t.name(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(t.name(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(t.name(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(t.name(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glObjectLabel(GL_TEXTURE, t.name(), -1, "DOS occlusion buffer (all, geometry)");
    }
    size_ = size;
}

double SlabPass::resolveSliceDistanceMm(const DosSettings& s, const GpuVolume& volume) const {
    return s.sliceDistanceMm > 0 ? s.sliceDistanceMm : 0.5 * volume.geometry().minSpacing();
}

namespace {
// Rows of work groups (the program's group is 8 x 8 pixels).
int groupRowsOf(int height) { return std::max(1, (height + 7) / 8); }
}  // namespace

int SlabPass::bandsPerSlice(int height) {
    int rows = groupRowsOf(height), perBand = std::min(kGroupRowsPerBand, rows);
    return (rows + perBand - 1) / perBand;
}

void SlabPass::run(const SlabInputs& in) {
    SlabRun whole = begin(in);
    advance(in, whole, whole.units());
}

SlabRun SlabPass::begin(const SlabInputs& in) {
    const FrameDescription& frame = in.frame;
    const DosSettings& settings = frame.dos;
    requireWithin(limits::dosConeAngleDeg, settings.coneAngleDeg, "<dos settings>", "cone_angle_deg");
    requireWithin(limits::dosGrid, settings.gridSize, "<dos settings>", "grid");
    ensureBuffers(frame.size);

    SliceLattice lattice = sliceLattice(in.volume.geometry(), frame.camera, resolveSliceDistanceMm(settings, in.volume));
    if (lattice.widened)
        log::warn("slab pass: slice distance " + std::to_string(resolveSliceDistanceMm(settings, in.volume)) + " mm needs more than " +
                  std::to_string(maxSlices) + " slices; using " + std::to_string(lattice.distanceMm) + " mm");
    SlabRun run{.first = lattice.first, .last = lattice.last, .distanceMm = lattice.distanceMm,
                .bandsPerSlice = bandsPerSlice(frame.size.y), .rowsPerBand = 8 * std::min(kGroupRowsPerBand, groupRowsOf(frame.size.y)), .next = 0,
                .current = 0, .generation = ++generation_};

    // Start: an empty eye buffer, and full visibility in both occlusion channels.
    const float clearEye[4] = {0, 0, 0, 0}, clearOcclusion[2] = {1, 1};
    glClearTexImage(in.eyeBuffer, 0, GL_RGBA, GL_FLOAT, clearEye);
    glClearTexImage(occlusion_[0].name(), 0, GL_RG, GL_FLOAT, clearOcclusion);
    if (in.tubes) {
        // Surfaces in front of the first slice keep full visibility.
        const float one = 1.0f;
        glClearTexImage(in.tubes->partialOcclusion(), 0, GL_RED, GL_FLOAT, &one);
    }
    slices_ = static_cast<int>(run.slices());
    last_ = 0;
    return run;
}

gl::Program& SlabPass::prepare(const SlabInputs& in, double d) {
    const FrameDescription& frame = in.frame;
    const DosSettings& settings = frame.dos;
    const GpuVolume& volume = in.volume;
    GBuffer* tubes = in.tubes;
    gl::Defines frameDefines;
    SampleShadingPiece::addCutFaceDefines(frameDefines, frame.raycast.cutFace, in.clip.count());
    addLightingDefines(frameDefines, frame);
    in.clip.addDefines(frameDefines);
    NoDataPiece{volume}.addDefines(frameDefines);
    VolumeLayoutPiece{volume.layout()}.addDefines(frameDefines);
    gl::Program& p = program(frame.shading, tubes != nullptr, in.tf, std::move(frameDefines));
    if (tubes) {
        glBindTextureUnit(binding::tubeDepth, tubes->depth());
        glBindImageTexture(binding::imagePartialOcclusion, tubes->partialOcclusion(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
        p.set("geometryOpacity", static_cast<float>(in.geometryOpacity));
        p.set("tubeThicknessMm", static_cast<float>(std::max(in.tubeThicknessMm, 1e-3)));
    }
    setLightingUniforms(p, frame, in.tf.material());
    CameraRayPiece{frame}.apply(p);
    VolumePiece{volume}.apply(p);
    NoDataPiece{volume}.apply(p);
    VolumeLayoutPiece{volume.layout()}.apply(p);
    in.tf.apply(p);
    in.clip.apply(p);
    in.shading.apply(p);
    p.set("viewForward", glm::vec3(frame.camera.forward()));
    p.set("sliceDistance", static_cast<float>(d));
    p.set("gridSize", settings.gridSize);
    p.set("ambientRadiance", static_cast<float>(settings.ambientRadiance));
    p.set("earlyTerminationAlpha", static_cast<float>(frame.raycast.earlyTerminationAlpha));
    p.set("jitterSeed", static_cast<unsigned>(frame.raycast.jitterSeed));
    glBindImageTexture(binding::imageOutput, in.eyeBuffer, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    return p;
}

void SlabPass::advance(const SlabInputs& in, SlabRun& run, long count) {
    const FrameDescription& frame = in.frame;
    if (run.generation != generation_ || frame.size != size_)
        throw SystemError("slab pass: a run in slices continued after another run began (begin it again)");
    count = std::min(count, run.left());
    if (count <= 0) return;
    const double d = run.distanceMm;
    gl::Program& p = prepare(in, d);
    // Eq. 11 and 12: the cone base radius d tan(theta) in world units, projected at the previous slice's
    // depth into pixels (the projection scales a length at depth z by H / (2 z tan(fovy / 2))).
    double tanTheta = std::tan(glm::radians(frame.dos.coneAngleDeg));
    double pixelsPerMmAtUnitDepth = frame.camera.pixelsPerMmAtUnitDepth(frame.size.y);
    for (long end = run.next + count; run.next < end; ++run.next) {
        long k = run.first + run.next / run.bandsPerSlice;
        int band = static_cast<int>(run.next % run.bandsPerSlice);
        double z = double(k) * d;
        double previousDepth = std::max(z - d, 1e-3);
        p.set("sliceDepth", static_cast<float>(z));
        p.set("coneRadiusPixels", static_cast<float>(d * tanTheta * pixelsPerMmAtUnitDepth / previousDepth));
        p.set("firstRow", band * run.rowsPerBand);
        glBindTextureUnit(binding::occlusionPrevious, occlusion_[run.current].name());
        glBindImageTexture(binding::imageOcclusionNext, occlusion_[1 - run.current].name(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG32F);
        int rows = std::min(run.rowsPerBand, frame.size.y - band * run.rowsPerBand);
        p.dispatchCovering(glm::uvec3(static_cast<unsigned>(frame.size.x), static_cast<unsigned>(rows), 1u));
        // The next slice reads this one's occlusion around each pixel: it waits for every band.
        if (band == run.bandsPerSlice - 1) {
            glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
            run.current = 1 - run.current;
        }
    }
    last_ = run.current;
}

std::vector<glm::vec2> SlabPass::readOcclusion() const {
    std::vector<glm::vec2> values(static_cast<std::size_t>(size_.x) * static_cast<std::size_t>(size_.y));
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);  // written by image stores
    glGetTextureImage(occlusion_[last_].name(), 0, GL_RG, GL_FLOAT, static_cast<GLsizei>(values.size() * sizeof(glm::vec2)),
                      values.data());
    return values;
}

std::size_t SlabPass::gpuBytes() const {
    return 2u * static_cast<std::size_t>(size_.x) * static_cast<std::size_t>(size_.y) * 8u;
}

}  // namespace curette
