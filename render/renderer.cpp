#include "render/renderer.h"

#include "base/error.h"
#include "render/bindings.h"
#include "render/lighting.h"

#include <glm/gtc/matrix_inverse.hpp>

namespace curette {

Renderer::Renderer(gl::Context& context, const VolumeData& volume, const TransferFunction& tf)
    : context_(context), volume_(context.info(), volume),
      clip_(clip::ClipMapSettings{0.5 * volume_.geometry().minSpacing(), 64, 1024}) {
    timers_.setSynchronous(context.info().softwareRenderer);
    clip_.setDilationRadiusMm(AmbientOcclusion::dilationRadiusMm(laoSettings_, volume_.geometry()));
    setTransferFunction(tf);
}

void Renderer::setLaoSettings(const LaoSettings& settings) {
    // The ambient scale only shades: changing it alone keeps every AO volume.
    LaoSettings comparable = settings;
    comparable.ambientScale = laoSettings_.ambientScale;
    bool aoChanged = !(comparable == laoSettings_);
    laoSettings_ = settings;
    if (!aoChanged) return;
    // The clip maps leave room for the LAO reach in every mode, so every mode clips identically.
    clip_.setDilationRadiusMm(AmbientOcclusion::dilationRadiusMm(laoSettings_, volume_.geometry()));
    ao_.reset();  // buffers depend on the settings (directions, list); reallocated at the next AO frame
    aoValid_ = aoPrecomputedValid_ = false;
}

void Renderer::updateAmbientOcclusion(ShadingMode mode) {
    lastFrameUpdatedAmbient_ = false;
    if (!ao_) {
        ao_ = std::make_unique<AmbientOcclusion>(volume_, laoSettings_);
        aoValid_ = aoPrecomputedValid_ = false;
    }
    // Only cao needs the dilated maps; lao recomputes every visible voxel.
    clip_.setDilatedMapsNeeded(mode == ShadingMode::Cao);
    clip_.update();
    if (!aoPrecomputedValid_ || aoTfVersion_ != tfVersion_) {
        ao_->precompute(*tf_, &timers_);
        aoPrecomputedValid_ = true;
        aoValid_ = false;
    }
    if (aoValid_ && aoClipVersion_ == clip_.version() && aoTfVersion_ == tfVersion_ && aoMode_ == mode) return;
    ao_->update(*tf_, clip_, mode, &timers_);
    aoValid_ = true;
    aoClipVersion_ = clip_.version();
    aoTfVersion_ = tfVersion_;
    aoMode_ = mode;
    lastFrameUpdatedAmbient_ = true;
}

Renderer::~Renderer() = default;

void Renderer::setTransferFunction(const TransferFunction& tf) {
    tf_ = std::make_unique<TransferFunctionTexture>(tf, volume_.valueScale(), volume_.valueOffset());
    ++tfVersion_;  // V_PAO and V_AO depend on the TF (the reference implementation forgot this: its bug 4)
    updateOccupancy();
}

double Renderer::resolveStepMm(const RaycastSettings& settings) const {
    return settings.stepMm > 0 ? settings.stepMm : 0.5 * volume_.geometry().minSpacing();
}

void Renderer::updateOccupancy() {
    // A brick may be skipped only if no texel value its samples can see has any opacity.
    glm::ivec3 grid = volume_.brickGrid();
    const std::vector<glm::vec2>& ranges = volume_.brickRanges();
    std::vector<std::uint8_t> flags(ranges.size());
    for (std::size_t i = 0; i < ranges.size(); ++i) flags[i] = tf_->maxOpacity(ranges[i].x, ranges[i].y) > 0.0f ? 255 : 0;
    if (!occupancy_) {
        occupancy_ = gl::createTexture(GL_TEXTURE_3D);
        glTextureStorage3D(occupancy_.name(), 1, GL_R8, grid.x, grid.y, grid.z);
        glObjectLabel(GL_TEXTURE, occupancy_.name(), -1, "occupancy (empty-space skipping)");
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage3D(occupancy_.name(), 0, 0, 0, 0, grid.x, grid.y, grid.z, GL_RED, GL_UNSIGNED_BYTE, flags.data());
}

void Renderer::ensureOutput(glm::ivec2 size) {
    if (size == outputSize_ && output_) return;
    output_ = gl::createTexture(GL_TEXTURE_2D);
    glTextureStorage2D(output_.name(), 1, GL_RGBA32F, size.x, size.y);
    glObjectLabel(GL_TEXTURE, output_.name(), -1, "output image");
    outputSize_ = size;
}

gl::Program& Renderer::raycastProgram(ShadingMode mode) {
    gl::Defines defines{{"SHADING", std::to_string(static_cast<int>(mode))}};
    if (countSamples_) defines.emplace_back("COUNT_SAMPLES", "1");
    tf_->addDefines(defines);
    return raycastPrograms_.get(defines);
}

void Renderer::render(const FrameDescription& frame) {
    if (frame.size.x < 1 || frame.size.y < 1 || frame.size.x > context_.info().maxTextureSize ||
        frame.size.y > context_.info().maxTextureSize)
        throw InputError("<frame>", "size", "between 1x1 and the GL maximum texture size",
                         std::to_string(frame.size.x) + "x" + std::to_string(frame.size.y));
    ensureOutput(frame.size);
    if (usesAmbientOcclusion(frame.shading)) {
        updateAmbientOcclusion(frame.shading);
    } else {
        clip_.update();
        lastFrameUpdatedAmbient_ = false;
    }
    if (tubes_) {
        renderWithTubes(frame);
        return;
    }
    if (frame.shading == ShadingMode::Dos) {
        // Directional occlusion needs the slab pass (all rays advance slice by slice together).
        timers_.begin("slab pass (DOS)");
        slab_.run(frame, frame.dos, volume_, *tf_, clip_, output_.name(), 0);
        timers_.end();
        slabUsed_ = true;
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
        return;
    }
    const VolumeGeometry& g = volume_.geometry();
    gl::Program& p = raycastProgram(frame.shading);

    double aspect = double(frame.size.x) / frame.size.y;
    glm::dmat4 viewProjection = frame.camera.projection(aspect) * frame.camera.view();
    p.set("inverseViewProjection", glm::mat4(glm::inverse(viewProjection)));
    p.set("eyeWorld", glm::vec3(frame.camera.position()));
    p.set("outputSize", frame.size);
    p.set("stepMm", static_cast<float>(resolveStepMm(frame.raycast)));
    p.set("earlyTerminationAlpha", static_cast<float>(frame.raycast.earlyTerminationAlpha));
    p.set("jitterSeed", static_cast<unsigned>(frame.raycast.jitterSeed));
    p.set("skipEmptySpace", frame.raycast.skipEmptySpace ? 1 : 0);
    p.set("volumeSize", g.dims);
    p.set("brickSize", GpuVolume::brickSize);
    p.set("worldToTexture", glm::mat4(g.worldToTexture()));
    p.set("texelSize", glm::vec3(1.0 / glm::dvec3(g.dims)));
    p.set("gradientToWorld", glm::mat3(g.gradientIndexToWorld() * volume_.valueScale()));
    tf_->setUniforms(p);
    p.set("clipMeshCount", clip_.count());
    p.set("ambientScale", static_cast<float>(laoSettings_.ambientScale));
    setLightingUniforms(p, frame, tf_->material());

    glBindTextureUnit(binding::volume, volume_.texture());
    tf_->bind();
    clip_.bind();
    glBindTextureUnit(binding::occupancy, occupancy_.name());
    if (ao_ && usesAmbientOcclusion(frame.shading)) glBindTextureUnit(binding::ambient, ao_->ambientTexture());
    glBindImageTexture(binding::imageOutput, output_.name(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    if (countSamples_) {
        if (!sampleCounter_) {
            sampleCounter_ = gl::createBuffer();
            glNamedBufferStorage(sampleCounter_.name(), 8, nullptr, GL_DYNAMIC_STORAGE_BIT | GL_MAP_READ_BIT);
        }
        const std::uint32_t zero[2] = {0, 0};
        glNamedBufferSubData(sampleCounter_.name(), 0, 8, zero);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding::ssboSampleCounter, sampleCounter_.name());
    }

    timers_.begin("VI ray casting");
    p.dispatchCovering(glm::uvec3(frame.size.x, frame.size.y, 1));
    timers_.end();
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
}

void Renderer::setTubes(const TubeVertices& vertices, const TubeShading& shading) {
    tubes_ = std::make_unique<TubeSet>(vertices);
    tubeShading_ = shading;
}

void Renderer::clearTubes() { tubes_.reset(); }

void Renderer::renderWithTubes(const FrameDescription& frame) {
    // Seed 000 Algorithm 1: G-buffer, slab pass (eye, partial and volumetric occlusion buffers), composite.
    timers_.begin("tubes G-buffer");
    tubes_->drawGBuffer(frame, clip_, gbuffer_);
    timers_.end();
    GLuint ambient = usesAmbientOcclusion(frame.shading) && ao_ ? ao_->ambientTexture() : 0;
    timers_.begin("slab pass");
    slab_.run(frame, frame.dos, volume_, *tf_, clip_, output_.name(), ambient, &gbuffer_, tubeShading_.geometryOpacity,
              laoSettings_.ambientScale);
    timers_.end();
    slabUsed_ = true;

    if (!compositeProgram_) compositeProgram_ = gl::Program::compute("tube_composite.comp");
    if (poissonCount_ != tubeShading_.vicinitySamples) {
        std::vector<glm::vec2> disk = poissonDisk(tubeShading_.vicinitySamples);
        poissonDisk_ = gl::createBuffer();
        glNamedBufferStorage(poissonDisk_.name(), static_cast<GLsizeiptr>(std::max<std::size_t>(disk.size(), 1) * sizeof(glm::vec2)),
                             disk.data(), 0);
        poissonCount_ = tubeShading_.vicinitySamples;
    }
    gl::Program& c = compositeProgram_;
    double aspect = double(frame.size.x) / frame.size.y;
    c.set("inverseViewProjection", glm::mat4(glm::inverse(frame.camera.projection(aspect) * frame.camera.view())));
    c.set("eyeWorld", glm::vec3(frame.camera.position()));
    c.set("outputSize", frame.size);
    c.set("poissonCount", poissonCount_);
    // Section 3.1.5: the vicinity radius l_vicinity tan(theta), projected at the surface's depth.
    double pixelsPerMmAtUnitDepth = frame.size.y / (2.0 * std::tan(glm::radians(frame.camera.fovYDeg) / 2.0));
    c.set("vicinityRadiusPixelsAtUnitDepth",
          static_cast<float>(tubeShading_.vicinityDistanceMm * std::tan(glm::radians(frame.dos.coneAngleDeg)) * pixelsPerMmAtUnitDepth));
    c.set("depthBiasMm", static_cast<float>(tubeShading_.depthBiasMm));
    c.set("useOcclusion", frame.shading == ShadingMode::Solid || frame.shading == ShadingMode::Phong ? 0 : 1);
    c.set("lineDiffuseExponent", static_cast<float>(tubeShading_.lineDiffuseExponent));
    setLightingUniforms(c, frame, tubeShading_.material);
    glBindImageTexture(binding::imageOutput, output_.name(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    glBindTextureUnit(binding::tubeDepth, gbuffer_.depth());
    glBindTextureUnit(binding::tubeColor, gbuffer_.color());
    glBindTextureUnit(binding::tubeNormal, gbuffer_.normal());
    glBindTextureUnit(binding::partialOcclusion, gbuffer_.partialOcclusion());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding::ssboPoissonDisk, poissonDisk_.name());
    timers_.begin("composite + vicinity");
    c.dispatchCovering(glm::uvec3(static_cast<unsigned>(frame.size.x), static_cast<unsigned>(frame.size.y), 1u));
    timers_.end();
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
}

std::uint64_t Renderer::samplesLastFrame() const {
    if (!sampleCounter_) return 0;
    std::uint32_t count = 0;  // one 32-bit counter: ample for a frame (4e9 samples)
    glGetNamedBufferSubData(sampleCounter_.name(), 0, 4, &count);
    return count;
}

Image Renderer::readImage() const {
    Image image;
    image.width = outputSize_.x;
    image.height = outputSize_.y;
    image.pixels.resize(static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height));
    // The shader writes row 0 as the top of the picture, which is also Image's convention.
    glGetTextureImage(output_.name(), 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(image.pixels.size() * sizeof(glm::vec4)),
                      image.pixels.data());
    return image;
}

std::vector<GpuAllocation> Renderer::gpuAllocations() const {
    const char* volumeFormat = volume_.format() == StorageFormat::UNorm8    ? "R8"
                               : volume_.format() == StorageFormat::UNorm16 ? "R16"
                                                                            : "R32F";
    glm::ivec3 grid = volume_.brickGrid();
    std::vector<GpuAllocation> list{
        {"V (data volume)", volumeFormat, volume_.gpuBytes()},
        {"transfer function", "RGBA32F 1D", TransferFunctionTexture::tableSize * 16u},
        {"gradient opacity", "R32F 1D", TransferFunctionTexture::gradientTableSize * 4u},
        {"occupancy bricks", "R8", static_cast<std::size_t>(grid.x) * static_cast<std::size_t>(grid.y) * static_cast<std::size_t>(grid.z)},
        {"output image", "RGBA32F", static_cast<std::size_t>(outputSize_.x) * static_cast<std::size_t>(outputSize_.y) * 16u},
    };
    if (clip_.count() > 0) list.push_back({"clip maps (depth + dilated arrays)", "R32F 2D arrays", clip_.gpuBytes()});
    if (ao_)
        for (const GpuAllocation& a : ao_->allocations()) list.push_back(a);
    if (slabUsed_) list.push_back({"DOS occlusion buffers (2, ping-pong)", "RG32F", slab_.gpuBytes()});
    if (tubes_) {
        list.push_back({"tube geometry", tubes_->lines() ? "line vertex buffers" : "triangle vertex buffers", tubes_->gpuBytes()});
        list.push_back({"G-buffer + partial occlusion", "RGBA16F x2, R32F x2, D32F", gbuffer_.gpuBytes()});
    }
    return list;
}

double Renderer::ambientOcclusionMs(const std::vector<std::pair<std::string, double>>& timings) {
    double ms = 0;
    for (const auto& [pass, passMs] : timings)
        if (pass.rfind("I ", 0) == 0 || pass.rfind("IV ", 0) == 0 || pass.rfind("V ", 0) == 0) ms += passMs;
    return ms;
}

}  // namespace curette
