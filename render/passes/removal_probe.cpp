#include "render/passes/removal_probe.h"

#include "mesh/coverage.h"
#include "gl/bindings.h"
#include "render/model/brick_set.h"

#include <algorithm>

namespace curette {

RemovalProbe::RemovalProbe(const VolumeGeometry& geometry, int antiAliasingSamples)
    : geometry_(geometry), antiAliasingSamples_(antiAliasingSamples) {
    std::vector<glm::vec4> aa;
    for (const glm::dvec3& o : clip::antiAliasingOffsets(std::max(antiAliasingSamples, 1))) aa.emplace_back(glm::vec3(o), 0.0f);
    antiAliasing_ = gl::createBuffer();
    glNamedBufferStorage(antiAliasing_.name(), static_cast<GLsizeiptr>(aa.size() * sizeof(glm::vec4)), aa.data(), 0);
    countProgram_ = gl::Program::compute("removal_count.comp");
    probeProgram_ = gl::Program::compute("clip_probe.comp");
}

plan::RemovalField RemovalProbe::removalField(clip::ClipMeshSet& clip) {
    plan::RemovalField field;
    field.gridDims = geometry_.dims;
    field.indexToWorld = geometry_.indexToWorld;
    field.samplesPerVoxel = 9 + antiAliasingSamples_;
    clip.update();
    for (int i = 0; i < clip.count(); ++i) field.facePlacementMm = std::max(field.facePlacementMm, 0.5 * clip.camera(i).depthPixelMm());
    plan::VoxelBox box = voxelBoxAroundMeshes(geometry_, clip);
    field.origin = box.origin;
    field.size = box.size;
    if (box.voxelCount() == 0) return field;
    gl::Buffer counts = gl::createBuffer();
    auto bytes = static_cast<GLsizeiptr>(box.voxelCount() * sizeof(std::uint32_t));
    glNamedBufferStorage(counts.name(), bytes, nullptr, GL_DYNAMIC_STORAGE_BIT);
    clip.apply(countProgram_);
    countProgram_.set("indexToWorld", glm::mat4(geometry_.indexToWorld));
    countProgram_.set("antiAliasingSamples", antiAliasingSamples_);
    countProgram_.set("regionOrigin", box.origin);
    countProgram_.set("regionSize", box.size);
    countProgram_.set("sampleReachMm", static_cast<float>(clipSampleReachMm(geometry_)));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding::ssboAntiAliasing, antiAliasing_.name());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding::ssboRemovalCounts, counts.name());
    countProgram_.dispatchCovering(glm::uvec3(box.size));
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<std::uint32_t> read(box.voxelCount());
    glGetNamedBufferSubData(counts.name(), 0, bytes, read.data());
    field.insideSamples.assign(read.begin(), read.end());
    return field;
}

std::vector<std::uint8_t> RemovalProbe::insideFlags(clip::ClipMeshSet& clip, const std::vector<glm::dvec3>& points) {
    std::vector<std::uint8_t> flags(points.size(), 0);
    if (points.empty() || clip.count() == 0) return flags;
    clip.update();
    // In batches, so a whole-brain tractogram needs no buffer of its size.
    const std::size_t batch = std::min<std::size_t>(points.size(), 1 << 20);
    gl::Buffer in = gl::createBuffer(), out = gl::createBuffer();
    glNamedBufferStorage(in.name(), static_cast<GLsizeiptr>(batch * sizeof(glm::vec4)), nullptr, GL_DYNAMIC_STORAGE_BIT);
    glNamedBufferStorage(out.name(), static_cast<GLsizeiptr>(batch * sizeof(std::uint32_t)), nullptr, GL_DYNAMIC_STORAGE_BIT);
    clip.apply(probeProgram_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding::ssboProbePoints, in.name());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding::ssboProbeResults, out.name());
    std::vector<glm::vec4> packed;
    std::vector<std::uint32_t> results;
    for (std::size_t first = 0; first < points.size(); first += batch) {
        std::size_t n = std::min(batch, points.size() - first);
        packed.resize(n);
        for (std::size_t i = 0; i < n; ++i) packed[i] = glm::vec4(glm::vec3(points[first + i]), 1.0f);
        glNamedBufferSubData(in.name(), 0, static_cast<GLsizeiptr>(n * sizeof(glm::vec4)), packed.data());
        probeProgram_.set("pointCount", static_cast<unsigned>(n));
        probeProgram_.dispatchCovering(glm::uvec3(static_cast<unsigned>(n), 1, 1));
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        results.resize(n);
        glGetNamedBufferSubData(out.name(), 0, static_cast<GLsizeiptr>(n * sizeof(std::uint32_t)), results.data());
        for (std::size_t i = 0; i < n; ++i) flags[first + i] = static_cast<std::uint8_t>(results[i] & 1u);
    }
    return flags;
}

}  // namespace curette
