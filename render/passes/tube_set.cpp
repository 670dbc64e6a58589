#include "render/passes/tube_set.h"

#include "base/error.h"
#include "gl/bindings.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace curette {

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
    return static_cast<std::size_t>(size_.x) * static_cast<std::size_t>(size_.y) * (8u + 8u + 4u + 4u + 4u);
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
}

TubeVertices TubeSet::readBack(std::size_t firstVertex, std::size_t vertexCount, std::size_t firstIndex, std::size_t indexCount) const {
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
}

void TubeSet::drawGBuffer(const FrameDescription& frame, const clip::ClipMeshSet& clip, GBuffer& target, std::size_t first, std::size_t count) {
    first = std::min(first, primitiveCount());
    count = std::min(count, primitiveCount() - first);
    if (count == 0) return;
    glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer());
    glViewport(0, 0, frame.size.x, frame.size.y);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    program_.set("viewProjection", glm::mat4(frame.camera.viewProjection(frame.size)));
    program_.set("eyeWorld", glm::vec3(frame.camera.position()));
    program_.set("viewForward", glm::vec3(frame.camera.forward()));
    program_.set("surfaceKind", lines_ ? binding::surfaceLine : binding::surfaceTube);
    clip.apply(program_);
    program_.use();
    glBindVertexArray(vertexArray_.name());
    const std::size_t indicesPer = lines_ ? 2 : 3;
    glDrawElements(lines_ ? GL_LINES : GL_TRIANGLES, static_cast<GLsizei>(count * indicesPer), GL_UNSIGNED_INT,
                   reinterpret_cast<const void*>(first * indicesPer * sizeof(std::uint32_t)));
    glDisable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
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
