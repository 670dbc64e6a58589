#include "render/passes/ismos_pass.h"

#include "gl/bindings.h"

#include <algorithm>
#include <string>

namespace curette {

namespace {
bool usesExact(const IsmosSettings& s) { return s.partial && !s.fit; }
bool usesFit(const IsmosSettings& s) { return s.partial && s.fit; }
int layerCount(const IsmosSettings& s) { return std::clamp(s.layers, 1, 4); }

gl::Texture image2D(GLenum format, glm::ivec2 size, const char* label) { return gl::createPixelBuffer2D(format, size.x, size.y, label); }
}  // namespace

void IsmosPass::addLayerDefines(gl::Defines& defines, const IsmosSettings& s) {
    defines.emplace_back("ISMOS_LAYERS", std::to_string(layerCount(s)));
    defines.emplace_back("ISMOS_EXACT", usesExact(s) ? "1" : "0");
    defines.emplace_back("ISMOS_FIT", usesFit(s) ? "1" : "0");
}

void IsmosPass::ensureImages(glm::ivec2 size, const IsmosSettings& s) {
    if (size != size_) {
        front_ = gl::Texture(), alpha_ = gl::Texture(), back_ = gl::Texture(), beta_ = gl::Texture();
        size_ = size;
    }
    if (!front_) front_ = image2D(GL_RGBA32F, size, "ISMOS layer fronts");
    if (!alpha_) alpha_ = image2D(GL_RGBA32F, size, "ISMOS layer opacities");
    // The variant's own images: a mode allocates only what it uses (freed when the variant changes).
    exact_ = usesExact(s);
    fit_ = usesFit(s);
    if (exact_ && !back_) back_ = image2D(GL_RGBA32F, size, "ISMOS layer backs");
    if (!exact_) back_ = gl::Texture();
    if (fit_ && !beta_) beta_ = image2D(GL_R32F, size, "ISMOS transmittance fit beta");
    if (!fit_) beta_ = gl::Texture();
}

void IsmosPass::applyLayers(gl::Program& p, const FrameDescription& frame, const IsmosSpace& space, double stepMm) {
    ensureImages(frame.size, frame.ismos);
    double range = space.farMm - space.nearMm;
    stepDepth_ = stepMm / range;
    p.set("ismosForward", glm::vec3(space.forward));
    p.set("ismosDepthRangeMm", static_cast<float>(range));
    p.set("ismosNearDepth", static_cast<float>(space.nearMm / range));
    glBindImageTexture(binding::imageIsmosLayerFront, front_.name(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glBindImageTexture(binding::imageIsmosLayerAlpha, alpha_.name(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    if (back_) glBindImageTexture(binding::imageIsmosLayerBack, back_.name(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    if (beta_) glBindImageTexture(binding::imageIsmosFit, beta_.name(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
}

void IsmosPass::updateLights(const FrameDescription& frame, const IsmosSpace& space, glm::dvec3 centre) {
    LightKey key{frame.lights, frame.camera, frame.size, frame.ismos, centre};
    if (lightKey_ && *lightKey_ == key) return;
    lightKey_ = key;
    ++lightRebuilds_;
    int n = std::clamp(frame.ismos.lightSamples, 1, 1024);
    lights_ = ismosLights(frame, space, centre, n);
    std::vector<glm::vec4> packed;
    for (const IsmosLight& l : lights_)
        for (glm::dvec3 s : l.samples) packed.emplace_back(glm::vec3(s), 1.0f);
    if (packed.empty()) packed.emplace_back(0.0f);
    std::size_t bytes = packed.size() * sizeof(glm::vec4);
    if (!samples_ || bytes != sampleBytes_) {
        samples_ = gl::createBuffer();
        glNamedBufferStorage(samples_.name(), static_cast<GLsizeiptr>(bytes), nullptr, GL_DYNAMIC_STORAGE_BIT);
        sampleBytes_ = bytes;
    }
    glNamedBufferSubData(samples_.name(), 0, static_cast<GLsizeiptr>(bytes), packed.data());
}

void IsmosPass::runOcclusion(const FrameDescription& frame, const IsmosSpace& space, glm::dvec3 centre, GLuint output) {
    const IsmosSettings& s = frame.ismos;
    updateLights(frame, space, centre);
    gl::Defines defines;
    defines.emplace_back("ISMOS_LAYERS", std::to_string(layerCount(s)));
    defines.emplace_back("ISMOS_PARTIAL", s.partial ? "1" : "0");
    defines.emplace_back("ISMOS_EXACT", usesExact(s) ? "1" : "0");
    defines.emplace_back("ISMOS_FIT", usesFit(s) ? "1" : "0");
    defines.emplace_back("ISMOS_BLEND", s.blendLayers ? "1" : "0");
    gl::Program& p = programs_.get(defines);
    int count = static_cast<int>(lights_.size());
    glm::vec3 centres[kMaxLights]{}, tints[kMaxLights]{};
    glm::vec4 spots[kMaxLights]{};
    for (int j = 0; j < count; ++j) {
        const IsmosLight& l = lights_[static_cast<std::size_t>(j)];
        centres[j] = glm::vec3(l.centre);
        tints[j] = glm::vec3(l.tint);
        spots[j] = glm::vec4(glm::vec3(l.spotTarget), static_cast<float>(l.cosOmega));
    }
    p.set("outputSize", frame.size);
    p.set("lightCount", count);
    p.set("samplesPerLight", std::clamp(s.lightSamples, 1, 1024));
    p.set("testPoints", std::clamp(s.testPoints, 1, 4096));
    if (count > 0) {
        glProgramUniform3fv(p.name(), p.location("lightCentre"), count, &centres[0].x);
        glProgramUniform4fv(p.name(), p.location("lightSpot"), count, &spots[0].x);
        glProgramUniform3fv(p.name(), p.location("lightTint"), count, &tints[0].x);
    }
    p.set("falloff", s.falloff ? 1 : 0);
    p.set("ambientFloor", static_cast<float>(s.ambient));
    p.set("opacityThreshold", static_cast<float>(s.opacityThreshold));
    p.set("depthBias", static_cast<float>(s.depthBias));
    p.set("texToDepth", glm::vec3(space.boxMm / space.boxMm.z));
    p.set("layerStepDepth", static_cast<float>(stepDepth_));
    glBindImageTexture(binding::imageOutput, output, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    glBindTextureUnit(binding::ismosLayerFront, front_.name());
    glBindTextureUnit(binding::ismosLayerAlpha, alpha_.name());
    if (back_) glBindTextureUnit(binding::ismosLayerBack, back_.name());
    if (beta_) glBindTextureUnit(binding::ismosFit, beta_.name());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding::ssboIsmosLightSamples, samples_.name());
    if (capture_) {
        std::size_t n = static_cast<std::size_t>(frame.size.x) * static_cast<std::size_t>(frame.size.y);
        pass1Colour_.resize(n);
        glMemoryBarrier(GL_ALL_BARRIER_BITS);
        glGetTextureImage(output, 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(n * sizeof(glm::vec4)), pass1Colour_.data());
    }
    p.dispatchCovering(glm::uvec3(static_cast<unsigned>(frame.size.x), static_cast<unsigned>(frame.size.y), 1u));
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
}

IsmosLayerImages IsmosPass::readLayers() const {
    IsmosLayerImages out;
    out.size = size_;
    std::size_t n = static_cast<std::size_t>(size_.x) * static_cast<std::size_t>(size_.y);
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    auto read4 = [&](const gl::Texture& t, std::vector<glm::vec4>& v) {
        if (!t) return;
        v.resize(n);
        glGetTextureImage(t.name(), 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(n * sizeof(glm::vec4)), v.data());
    };
    read4(front_, out.front);
    read4(alpha_, out.alpha);
    read4(back_, out.back);
    if (beta_) {
        out.beta.resize(n);
        glGetTextureImage(beta_.name(), 0, GL_RED, GL_FLOAT, static_cast<GLsizei>(n * sizeof(float)), out.beta.data());
    }
    return out;
}

std::vector<GpuAllocation> IsmosPass::allocations() const {
    std::vector<GpuAllocation> list;
    std::size_t pixels = static_cast<std::size_t>(size_.x) * static_cast<std::size_t>(size_.y);
    if (front_) list.push_back({Resource::IsmosLayers, 2 * pixels * 16u, {}});
    if (back_) list.push_back({Resource::IsmosLayerBacks, pixels * 16u, {}});
    if (beta_) list.push_back({Resource::IsmosFit, pixels * 4u, {}});
    if (samples_) list.push_back({Resource::IsmosLightSamples, sampleBytes_, {}});
    return list;
}

}  // namespace curette
