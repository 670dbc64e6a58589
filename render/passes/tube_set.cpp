#include "render/passes/tube_set.h"

#include "base/error.h"
#include "gl/bindings.h"
#include "render/shader_pieces.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace curette {

namespace {
constexpr std::size_t kPointsPerDispatch = std::size_t(1) << 20;
}

void GBuffer::ensure(glm::ivec2 size) {
    if (size == size_ && framebuffer_) return;
    auto make = [&](GLenum format, const char* label) {
        gl::Texture t = gl::createTexture(GL_TEXTURE_2D);
        glTextureStorage2D(t.name(), 1, format, size.x, size.y);
        glTextureParameteri(t.name(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(t.name(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTextureParameteri(t.name(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(t.name(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glObjectLabel(GL_TEXTURE, t.name(), -1, label);
        return t;
    };
    color_ = make(GL_RGBA16F, "G-buffer colour");
    normal_ = make(GL_RGBA16F, "G-buffer normal/tangent + kind");
    depth_ = make(GL_R32F, "G-buffer view depth");
    partial_ = make(GL_R32F, "partial occlusion buffer");
    nearestDepth_ = make(GL_R32UI, "impostor nearest depth (float bits)");
    nearestSegment_ = make(GL_R32UI, "impostor nearest segment");
    depthStencil_ = gl::createRenderbuffer();
    glNamedRenderbufferStorage(depthStencil_.name(), GL_DEPTH_COMPONENT32F, size.x, size.y);
    framebuffer_ = gl::createFramebuffer();
    glNamedFramebufferTexture(framebuffer_.name(), GL_COLOR_ATTACHMENT0, color_.name(), 0);
    glNamedFramebufferTexture(framebuffer_.name(), GL_COLOR_ATTACHMENT1, normal_.name(), 0);
    glNamedFramebufferTexture(framebuffer_.name(), GL_COLOR_ATTACHMENT2, depth_.name(), 0);
    glNamedFramebufferRenderbuffer(framebuffer_.name(), GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depthStencil_.name());
    const GLenum buffers[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    glNamedFramebufferDrawBuffers(framebuffer_.name(), 3, buffers);
    if (glCheckNamedFramebufferStatus(framebuffer_.name(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw SystemError("the tube G-buffer framebuffer is incomplete");
    size_ = size;
}

std::size_t GBuffer::gpuBytes() const {
    return static_cast<std::size_t>(size_.x) * static_cast<std::size_t>(size_.y) * (8u + 8u + 4u + 4u + 4u + 4u + 4u) + candidateWords_ * 4u;
}

GLuint GBuffer::candidates(std::size_t points) {
    std::size_t words = (points + 31) / 32;
    if (words > candidateWords_ || !candidates_) {
        candidates_ = gl::createBuffer();
        glNamedBufferStorage(candidates_.name(), static_cast<GLsizeiptr>(std::max<std::size_t>(words, 1) * 4), nullptr, GL_DYNAMIC_STORAGE_BIT);
        glObjectLabel(GL_BUFFER, candidates_.name(), -1, "impostor candidates (a bit per point)");
        candidateWords_ = std::max<std::size_t>(words, 1);
    }
    return candidates_.name();
}

std::vector<float> GBuffer::readDepth() const {
    std::vector<float> values(static_cast<std::size_t>(size_.x) * static_cast<std::size_t>(size_.y));
    glGetTextureImage(depth_.name(), 0, GL_RED, GL_FLOAT, static_cast<GLsizei>(values.size() * 4), values.data());
    return values;
}

namespace {
std::vector<glm::vec4> readRgba(GLuint texture, glm::ivec2 size) {
    std::vector<glm::vec4> values(static_cast<std::size_t>(size.x) * static_cast<std::size_t>(size.y));
    glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(values.size() * sizeof(glm::vec4)), values.data());
    return values;
}
}  // namespace

std::vector<glm::vec4> GBuffer::readColor() const { return readRgba(color_.name(), size_); }
std::vector<glm::vec4> GBuffer::readNormal() const { return readRgba(normal_.name(), size_); }

namespace {

TubeBuffers upload(const TubeVertices& v) {
    if (v.positions.size() != v.directions.size() || v.positions.size() != v.colors.size())
        throw InputError("<tubes>", "vertices", "as many directions and colours as positions");
    for (std::uint32_t i : v.indices)
        if (i >= v.positions.size()) throw InputError("<tubes>", "indices", "indices below the vertex count", std::to_string(i));
    auto make = [&](gl::Buffer& b, const void* data, std::size_t bytes) {
        b = gl::createBuffer();
        glNamedBufferStorage(b.name(), static_cast<GLsizeiptr>(std::max<std::size_t>(bytes, 4)), bytes ? data : nullptr, 0);
    };
    TubeBuffers b;
    make(b.positions, v.positions.data(), v.positions.size() * sizeof(glm::vec3));
    make(b.directions, v.directions.data(), v.directions.size() * sizeof(glm::vec3));
    make(b.colors, v.colors.data(), v.colors.size() * sizeof(glm::vec4));
    make(b.indices, v.indices.data(), v.indices.size() * sizeof(std::uint32_t));
    b.vertexCount = v.positions.size();
    b.indexCount = v.indices.size();
    b.lines = v.lines;
    if (!v.positions.empty()) {
        b.boundsMin = b.boundsMax = glm::dvec3(v.positions.front());
        for (const glm::vec3& p : v.positions) b.boundsMin = glm::min(b.boundsMin, glm::dvec3(p)), b.boundsMax = glm::max(b.boundsMax, glm::dvec3(p));
    }
    return b;
}

}  // namespace

TubeSet::TubeSet(const TubeVertices& v) : TubeSet(upload(v)) {}

TubeSet::TubeSet(TubeBuffers buffers) : buffers_(std::move(buffers)), lines_(buffers_.lines) {
    if (buffers_.indexCount > static_cast<std::size_t>(std::numeric_limits<GLsizei>::max()))
        throw InputError("<tubes>", "indices", "at most 2^31 - 1 indices in one draw", std::to_string(buffers_.indexCount));
    vertexArray_ = gl::createVertexArray();
    GLuint va = vertexArray_.name();
    glVertexArrayVertexBuffer(va, 0, buffers_.positions.name(), 0, sizeof(glm::vec3));
    glVertexArrayVertexBuffer(va, 1, buffers_.directions.name(), 0, sizeof(glm::vec3));
    glVertexArrayVertexBuffer(va, 2, buffers_.colors.name(), 0, sizeof(glm::vec4));
    for (GLuint a = 0; a < 3; ++a) {
        glEnableVertexArrayAttrib(va, a);
        glVertexArrayAttribFormat(va, a, a == 2 ? 4 : 3, GL_FLOAT, GL_FALSE, 0);
        glVertexArrayAttribBinding(va, a, a);
    }
    glVertexArrayElementBuffer(va, buffers_.indices.name());
    program_ = gl::Program::graphics("tube_gbuffer.vert", "tube_gbuffer.frag");
    unclippedProgram_ = gl::Program::graphics("tube_gbuffer.vert", "tube_gbuffer.frag", {{"NO_CLIP_MESHES", "1"}});
}

TubeSet::TubeSet(const TubeImpostors& impostors, std::size_t windowPoints)
    : impostor_(true), impostorBundles_(impostors.bundles), pointCount_(impostors.points.size()), windowPoints_(windowPoints) {
    for (const TubeImpostorBundle& b : impostors.bundles)
        if (b.firstPoint + b.pointCount > impostors.points.size() || !(b.radiusMm > 0))
            throw InputError("<tubes>", "impostor bundles", "point ranges within the points and positive radii");
    impostorPoints_ = gl::createBuffer();
    impostorBytes_ = impostors.bytes();
    glNamedBufferStorage(impostorPoints_.name(), static_cast<GLsizeiptr>(std::max<std::size_t>(impostors.bytes(), 16)),
                         impostors.points.empty() ? nullptr : impostors.points.data(), 0);
    impostorTexture_ = gl::createTexture(GL_TEXTURE_BUFFER);
    buffers_.boundsMin = impostors.boundsMin, buffers_.boundsMax = impostors.boundsMax;
    program_ = gl::Program::compute("tube_impostor.comp");
    unclippedProgram_ = gl::Program::compute("tube_impostor.comp", {{"NO_CLIP_MESHES", "1"}});
}

TubeVertices TubeSet::readBack(std::size_t firstVertex, std::size_t vertexCount, std::size_t firstIndex, std::size_t indexCount) const {
    if (impostor_) throw std::logic_error("TubeSet::readBack: impostor tubes have no vertex streams");
    if (firstVertex + vertexCount > buffers_.vertexCount || firstIndex + indexCount > buffers_.indexCount)
        throw InputError("<tubes>", "read back", "a range within the tube set's vertices and indices");
    TubeVertices v;
    v.lines = lines_;
    v.positions.resize(vertexCount);
    v.directions.resize(vertexCount);
    v.colors.resize(vertexCount);
    v.indices.resize(indexCount);
    auto read = [](const gl::Buffer& b, std::size_t offset, void* data, std::size_t bytes) {
        if (bytes) glGetNamedBufferSubData(b.name(), static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes), data);
    };
    read(buffers_.positions, firstVertex * sizeof(glm::vec3), v.positions.data(), vertexCount * sizeof(glm::vec3));
    read(buffers_.directions, firstVertex * sizeof(glm::vec3), v.directions.data(), vertexCount * sizeof(glm::vec3));
    read(buffers_.colors, firstVertex * sizeof(glm::vec4), v.colors.data(), vertexCount * sizeof(glm::vec4));
    read(buffers_.indices, firstIndex * sizeof(std::uint32_t), v.indices.data(), indexCount * sizeof(std::uint32_t));
    return v;
}

void TubeSet::drawGBuffer(const FrameDescription& frame, const clip::ClipMeshSet& clip, GBuffer& target) {
    clearGBuffer(frame.size, target);
    drawGBuffer(frame, clip, target, 0, primitiveCount());
}

void TubeSet::clearGBuffer(glm::ivec2 size, GBuffer& target) const {
    target.ensure(size);
    glDepthMask(GL_TRUE);   // a depth clear obeys the write mask
    const float zero[4] = {0, 0, 0, 0}, one = 1.0f;
    for (GLint i = 0; i < 3; ++i) glClearNamedFramebufferfv(target.framebuffer(), GL_COLOR, i, zero);
    glClearNamedFramebufferfv(target.framebuffer(), GL_DEPTH, 0, &one);
    if (!impostor_) return;
    const GLuint none = 0xFFFFFFFFu, noBits = 0;
    glClearTexImage(target.nearestDepth(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &none);
    glClearTexImage(target.nearestSegment(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &none);
    glClearNamedBufferData(target.candidates(pointCount_), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &noBits);
}

void TubeSet::drawGBuffer(const FrameDescription& frame, const clip::ClipMeshSet& clip, GBuffer& target, std::size_t first, std::size_t count) {
    first = std::min(first, primitiveCount());
    count = std::min(count, primitiveCount() - first);
    if (count == 0) return;
    if (impostor_) {
        drawImpostors(frame, clip, target, first, count);
        return;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer());
    glViewport(0, 0, frame.size.x, frame.size.y);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    drawElements(frame, clip, first, count);
    glDisable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
}

// llvmpipe runs a branch under a lane mask, so a clip test behind a false uniform still costs its texture reads
// at every fragment (each of an impostor's five crossings): without a mesh that clips tubes, the variant without it.
gl::Program& TubeSet::programFor(const clip::ClipMeshSet& clip) {
    for (int i = 0; i < clip.count(); ++i)
        if (clip.clipsTubes(i)) {
            clip.apply(program_);
            return program_;
        }
    return unclippedProgram_;
}

void TubeSet::drawElements(const FrameDescription& frame, const clip::ClipMeshSet& clip, std::size_t first, std::size_t count) {
    gl::Program& program = programFor(clip);
    program.set("viewProjection", glm::mat4(frame.camera.viewProjection(frame.size)));
    program.set("eyeWorld", glm::vec3(frame.camera.position()));
    program.set("viewForward", glm::vec3(frame.camera.forward()));
    program.set("surfaceKind", lines_ ? binding::surfaceLine : binding::surfaceTube);
    program.use();
    glBindVertexArray(vertexArray_.name());
    const std::size_t indicesPer = lines_ ? 2 : 3;
    glDrawElements(lines_ ? GL_LINES : GL_TRIANGLES, static_cast<GLsizei>(count * indicesPer), GL_UNSIGNED_INT,
                   reinterpret_cast<const void*>(first * indicesPer * sizeof(std::uint32_t)));
}

// The impostor primitives are the points twice: [0, P) runs phase 0 of shaders/tube_impostor.comp on the points,
// [P, 2P) phase 1, and the range that reaches 2P ends with phase 2 over the pixels.
void TubeSet::drawImpostors(const FrameDescription& frame, const clip::ClipMeshSet& clip, GBuffer& target, std::size_t first, std::size_t count) {
    gl::Program& program = programFor(clip);
    program.set("viewProjection", glm::mat4(frame.camera.viewProjection(frame.size)));
    program.set("viewForward", glm::vec3(frame.camera.forward()));
    CameraRayPiece{frame}.apply(program);
    glBindImageTexture(binding::imageTubeNearestDepth, target.nearestDepth(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    glBindImageTexture(binding::imageTubeNearestSegment, target.nearestSegment(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    glBindImageTexture(binding::imageTubeColor, target.color(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindImageTexture(binding::imageTubeNormal, target.normal(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindImageTexture(binding::imageTubeDepth, target.depth(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding::ssboTubeCandidates, target.candidates(pointCount_));
    const std::size_t P = pointCount_, end = first + count;
    if (first < P) impostorPhase(program, frame, 0, first, std::min(end, P) - first);
    if (end > P) {
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
        std::size_t from = std::max(first, P) - P;
        impostorPhase(program, frame, 1, from, end - P - from);
    }
    if (end == 2 * P) {
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        impostorPhase(program, frame, 2, 0, P);
    }
    glBindTextureUnit(binding::tubeImpostorPoints, 0);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

// One phase over the points [first, first + count), bundle by bundle (each its radius and caps) and window by
// window: a buffer texture is limited to GL_MAX_TEXTURE_BUFFER_SIZE texels and its range must start at a
// multiple of GL_TEXTURE_BUFFER_OFFSET_ALIGNMENT bytes, so larger sets are bound in windows, each from the
// aligned offset at or below its first point (the shader is told that offset's global index).
void TubeSet::impostorPhase(gl::Program& program, const FrameDescription& frame, int phase, std::size_t first, std::size_t count) {
    GLint64 maxTexels = 0, alignment = 0;
    glGetInteger64v(GL_MAX_TEXTURE_BUFFER_SIZE, &maxTexels);
    glGetInteger64v(GL_TEXTURE_BUFFER_OFFSET_ALIGNMENT, &alignment);
    const std::size_t pointBytes = sizeof(TubeImpostorPoint), align = static_cast<std::size_t>(std::max<GLint64>(alignment, 1));
    const std::size_t slackPoints = (align + pointBytes - 1) / pointBytes;
    std::size_t texels = std::min<std::size_t>(static_cast<std::size_t>(maxTexels), std::size_t(1) << 28);
    if (windowPoints_) texels = std::min(texels, windowPoints_);
    if (texels < slackPoints + 2) throw std::logic_error("TubeSet: an impostor window smaller than the texture buffer alignment");
    const std::size_t window = texels - slackPoints - 1;
    const std::size_t end = first + count;
    program.set("phase", phase);
    for (const TubeImpostorBundle& bundle : impostorBundles_) {
        std::size_t s = std::max(first, bundle.firstPoint), e = std::min(end, bundle.firstPoint + bundle.pointCount);
        if (s >= e) continue;
        program.set("radiusMm", static_cast<float>(bundle.radiusMm));
        program.set("caps", bundle.caps ? 1 : 0);
        while (s < e) {
            std::size_t n = std::min(e - s, window);
            std::size_t base = s * pointBytes / align * align / pointBytes;   // the window's texel 0
            std::size_t lastPoint = std::min(s + n, pointCount_ - 1);      // a segment's second point
            glTextureBufferRange(impostorTexture_.name(), GL_RGBA32UI, impostorPoints_.name(), static_cast<GLintptr>(base * pointBytes),
                                 static_cast<GLsizeiptr>((lastPoint + 1 - base) * pointBytes));
            glBindTextureUnit(binding::tubeImpostorPoints, impostorTexture_.name());
            program.set("globalBase", static_cast<unsigned>(base));
            if (phase == 2) {
                program.set("firstPoint", static_cast<unsigned>(s - base));
                program.set("pointCount", static_cast<unsigned>(n));
                program.dispatchCovering(glm::uvec3(frame.size.x, frame.size.y, 1));
            } else {
                // At most kPointsPerDispatch points a dispatch (a dimension holds 65535 groups); phase 1 takes a
                // word of candidate bits an invocation and keeps the bits of the dispatch's points.
                for (std::size_t q = 0; q < n; q += kPointsPerDispatch) {
                    std::size_t m = std::min<std::size_t>(kPointsPerDispatch, n - q), from = s + q;
                    program.set("firstPoint", static_cast<unsigned>(from - base));
                    program.set("pointCount", static_cast<unsigned>(m));
                    program.dispatchCovering(glm::uvec3(phase == 1 ? (from + m - 1) / 32 - from / 32 + 1 : m, 1, 1));
                }
            }
            s += n;
        }
    }
}

std::vector<glm::vec2> poissonDisk(int count, std::uint32_t seed) {
    // Dart throwing with a shrinking minimum distance, so `count` points always fit.
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<glm::vec2> points;
    double minDistance = 1.6 / std::sqrt(std::max(count, 1));
    while (static_cast<int>(points.size()) < count) {
        bool placed = false;
        for (int attempt = 0; attempt < 2000 && !placed; ++attempt) {
            glm::dvec2 p(u(random), u(random));
            if (glm::dot(p, p) > 1.0) continue;
            bool farEnough = true;
            for (const glm::vec2& q : points) farEnough = farEnough && glm::distance(glm::vec2(p), q) >= minDistance;
            if (farEnough) points.emplace_back(p), placed = true;
        }
        if (!placed) minDistance *= 0.9;
    }
    return points;
}

}  // namespace curette
