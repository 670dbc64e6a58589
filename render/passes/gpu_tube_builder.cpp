#include "render/passes/gpu_tube_builder.h"

#include "base/error.h"
#include "gl/bindings.h"
#include "gl/program.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>

namespace curette {

namespace {

// The records as tube_build.comp declares them (std430).
struct RingRecord {
    glm::vec4 point, tangent, normal, color;
};
struct StreamlineRecord {
    glm::uvec4 layout;
    glm::vec4 shape;
};
static_assert(sizeof(RingRecord) == 64 && sizeof(StreamlineRecord) == 32);

gl::Buffer storage(std::size_t bytes, const void* data) {
    gl::Buffer b = gl::createBuffer();
    glNamedBufferStorage(b.name(), static_cast<GLsizeiptr>(std::max<std::size_t>(bytes, 16)), data, 0);
    return b;
}

GLint64 limit(GLenum name) {
    GLint64 v = 0;
    glGetInteger64v(name, &v);
    return v;
}

}  // namespace

TubeBuffers buildTubeBuffersOnGpu(const TubeRings& rings, GpuTubeBuildStats* stats, std::size_t batchBytes) {
    GpuTubeBuildStats local;
    TubeBuffers out;
    out.vertexCount = rings.vertexCount;
    out.indexCount = rings.indexCount;
    out.lines = false;
    out.positions = storage(rings.vertexCount * sizeof(glm::vec3), nullptr);
    out.directions = storage(rings.vertexCount * sizeof(glm::vec3), nullptr);
    out.colors = storage(rings.vertexCount * sizeof(glm::vec4), nullptr);
    out.indices = storage(rings.indexCount * sizeof(std::uint32_t), nullptr);
    if (rings.streamlines.empty()) {
        if (stats) *stats = local;
        return out;
    }
    // The world box: every vertex lies within a radius of its ring's centre.
    out.boundsMin = glm::dvec3(1e300), out.boundsMax = glm::dvec3(-1e300);
    for (const TubeStreamline& line : rings.streamlines)
        for (std::uint32_t i = 0; i < line.ringCount; ++i) {
            glm::dvec3 p = rings.rings[line.firstRing + i].point;
            out.boundsMin = glm::min(out.boundsMin, p - line.radiusMm), out.boundsMax = glm::max(out.boundsMax, p + line.radiusMm);
        }

    // Every streamline's record, and the unit circle of every side count (computed in double, like the CPU's).
    std::vector<StreamlineRecord> lines;
    lines.reserve(rings.streamlines.size());
    for (const TubeStreamline& l : rings.streamlines)
        lines.push_back({glm::uvec4(l.firstRing, l.ringCount, l.firstVertex, l.firstIndex),
                         glm::vec4(static_cast<float>(l.radiusMm), static_cast<float>(l.sides), l.caps ? 1.0f : 0.0f, 0.0f)});
    std::vector<glm::vec2> circle(64 * 63 / 2 + 64);
    for (std::uint32_t sides = 1; sides <= 64; ++sides)
        for (std::uint32_t k = 0; k < sides; ++k) {
            double a = 2 * std::numbers::pi * k / sides;
            circle[sides * (sides - 1) / 2 + k] = glm::vec2(static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)));
        }
    gl::Buffer lineBuffer = storage(lines.size() * sizeof(StreamlineRecord), lines.data());
    gl::Buffer circleBuffer = storage(circle.size() * sizeof(glm::vec2), circle.data());
    local.ringBytes = lines.size() * sizeof(StreamlineRecord);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding::ssboTubeStreamlines, lineBuffer.name());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding::ssboTubeCircle, circleBuffer.name());

    gl::Program program = gl::Program::compute("tube_build.comp");
    const std::size_t alignment = static_cast<std::size_t>(std::max<GLint64>(limit(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT), 16));
    // Each bound range with its alignment slack stays within the block limit and `batchBytes`.
    const std::size_t blockLimit =
        std::min(static_cast<std::size_t>(limit(GL_MAX_SHADER_STORAGE_BLOCK_SIZE)) - alignment, batchBytes);
    std::vector<RingRecord> batch;
    std::size_t s = 0;
    while (s < rings.streamlines.size()) {
        // Streamlines [s, e): as many as fit.
        const TubeStreamline& first = rings.streamlines[s];
        std::size_t e = s, ringCount = 0, vertexCount = 0, indexCount = 0;
        while (e < rings.streamlines.size()) {
            const TubeStreamline& l = rings.streamlines[e];
            std::size_t r = ringCount + l.ringCount, v = vertexCount + l.vertexCount(), i = indexCount + l.indexCount();
            if (r * sizeof(RingRecord) > blockLimit || v * sizeof(glm::vec4) > blockLimit || i * sizeof(std::uint32_t) > blockLimit) break;
            ringCount = r, vertexCount = v, indexCount = i, ++e;
        }
        if (e == s) throw SystemError("a tube of " + std::to_string(first.vertexCount()) + " vertices exceeds a shader-storage block (" +
                                      std::to_string(blockLimit) + " bytes): build it on the CPU (tube_rendering.build \"cpu\")");
        batch.clear();
        batch.reserve(ringCount);
        for (std::size_t l = s; l < e; ++l) {
            const TubeStreamline& line = rings.streamlines[l];
            float index;
            std::uint32_t bits = static_cast<std::uint32_t>(l);
            std::memcpy(&index, &bits, sizeof index);
            for (std::uint32_t i = 0; i < line.ringCount; ++i) {
                const TubeRing& ring = rings.rings[line.firstRing + i];
                batch.push_back({glm::vec4(glm::vec3(ring.point), index), glm::vec4(glm::vec3(ring.tangent), 0.0f),
                                 glm::vec4(glm::vec3(ring.normal), 0.0f), ring.color});
            }
        }
        gl::Buffer ringBuffer = storage(batch.size() * sizeof(RingRecord), batch.data());
        local.ringBytes = std::max(local.ringBytes, lines.size() * sizeof(StreamlineRecord) + batch.size() * sizeof(RingRecord));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding::ssboTubeRings, ringBuffer.name());
        // Output ranges from the aligned offset at or below the batch's first element.
        auto bindRange = [&](unsigned unit, const gl::Buffer& b, std::size_t firstByte, std::size_t bytes, std::size_t elementBytes) {
            std::size_t start = firstByte / alignment * alignment;
            glBindBufferRange(GL_SHADER_STORAGE_BUFFER, unit, b.name(), static_cast<GLintptr>(start), static_cast<GLsizeiptr>(firstByte - start + bytes));
            return static_cast<unsigned>((firstByte - start) / elementBytes);
        };
        unsigned positionSlack = bindRange(binding::ssboTubePositions, out.positions, first.firstVertex * sizeof(glm::vec3), vertexCount * sizeof(glm::vec3), sizeof(float));
        bindRange(binding::ssboTubeDirections, out.directions, first.firstVertex * sizeof(glm::vec3), vertexCount * sizeof(glm::vec3), sizeof(float));
        unsigned colorSlack = bindRange(binding::ssboTubeColors, out.colors, first.firstVertex * sizeof(glm::vec4), vertexCount * sizeof(glm::vec4), sizeof(glm::vec4));
        unsigned indexSlack = bindRange(binding::ssboTubeIndices, out.indices, first.firstIndex * sizeof(std::uint32_t), indexCount * sizeof(std::uint32_t), sizeof(std::uint32_t));
        program.set("ringCount", static_cast<unsigned>(ringCount));
        program.set("firstRing", first.firstRing);
        program.set("firstVertex", first.firstVertex);
        program.set("firstIndex", first.firstIndex);
        program.set("positionSlack", positionSlack);
        program.set("colorSlack", colorSlack);
        program.set("indexSlack", indexSlack);
        program.use();
        program.dispatchCovering(glm::uvec3(static_cast<unsigned>(ringCount), 1, 1));
        ++local.batches;
        s = e;
    }
    glMemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_ELEMENT_ARRAY_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    for (unsigned unit : {binding::ssboTubeRings, binding::ssboTubeStreamlines, binding::ssboTubeCircle, binding::ssboTubePositions,
                          binding::ssboTubeDirections, binding::ssboTubeColors, binding::ssboTubeIndices})
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, unit, 0);
    if (stats) *stats = local;
    return out;
}

}  // namespace curette
