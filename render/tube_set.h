#pragma once
// Tubes (or illuminated lines) on the GPU and the G-buffer they are drawn into (seed 000 section 3.1.1):
// colour, world normal (tubes) or tangent (lines) with the surface kind, and the view depth along the camera
// axis. The geometry itself is built on the CPU (render/tube_geometry.h) in world millimetres.

#include "clip/clip_mesh_set.h"
#include "gl/program.h"
#include "render/frame.h"
#include "render/tube_vertices.h"

#include <vector>

namespace curette {

class GBuffer {
public:
    void ensure(glm::ivec2 size);
    glm::ivec2 size() const { return size_; }
    GLuint color() const { return color_.name(); }
    GLuint normal() const { return normal_.name(); }
    GLuint depth() const { return depth_.name(); }
    GLuint partialOcclusion() const { return partial_.name(); }
    GLuint framebuffer() const { return framebuffer_.name(); }
    std::size_t gpuBytes() const;
    std::vector<float> readDepth() const;

private:
    glm::ivec2 size_{0};
    gl::Texture color_, normal_, depth_, partial_;
    gl::Renderbuffer depthStencil_;
    gl::Framebuffer framebuffer_;
};

class TubeSet {
public:
    explicit TubeSet(const TubeVertices& vertices);
    bool lines() const { return lines_; }
    std::size_t triangleCount() const { return lines_ ? 0 : indexCount_ / 3; }
    std::size_t segmentCount() const { return lines_ ? indexCount_ / 2 : 0; }
    std::size_t gpuBytes() const { return bytes_; }
    // The world box around every vertex (the frame plan leaves tubes out of a frame they cannot be seen in).
    glm::dvec3 boundsMin() const { return boundsMin_; }
    glm::dvec3 boundsMax() const { return boundsMax_; }
    void drawGBuffer(const FrameDescription& frame, const clip::ClipMeshSet& clip, GBuffer& target);

private:
    gl::Buffer positions_, directions_, colors_, indices_;
    gl::VertexArray vertexArray_;
    gl::Program program_;
    GLsizei indexCount_ = 0;
    bool lines_ = false;
    std::size_t bytes_ = 0;
    glm::dvec3 boundsMin_{0.0}, boundsMax_{0.0};
};

// Deterministic Poisson-disk samples in the unit disk (dart throwing with a fixed seed).
std::vector<glm::vec2> poissonDisk(int count, std::uint32_t seed = 7);

}  // namespace curette
