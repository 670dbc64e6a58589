#pragma once
// Tubes (or illuminated lines) on the GPU and the G-buffer they are drawn into (seed 000 section 3.1.1):
// colour, world normal (tubes) or tangent (lines) with the surface kind, and the view depth along the camera
// axis. The geometry itself is built on the CPU (render/tube_geometry.h) in world millimetres.

#include "clip/clip_mesh_set.h"
#include "render/frame.h"
#include "render/gl/program.h"
#include "render/transfer_function.h"

#include <vector>

namespace curette {

// Vertex streams as drawn: triangles for tubes, GL_LINES pairs for illuminated lines.
struct TubeVertices {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> directions;   // normals (tubes) or tangents (lines), unit
    std::vector<glm::vec4> colors;
    std::vector<std::uint32_t> indices;
    bool lines = false;
};

// How tubes take part in the combined occlusion (seed 000) and how they are lit.
struct TubeShading {
    double geometryOpacity = 0.9;      // opacity a tube injects into the occlusion buffer (Algorithm 3)
    double vicinityDistanceMm = 3.0;   // l_vicinity: the vicinity radius is l_vicinity tan(theta) (section 3.1.5)
    int vicinitySamples = 64;          // Poisson-disk samples (the paper: up to 118)
    double depthBiasMm = 0.5;          // an occluding neighbour must be this much nearer (Algorithm 5)
    double lineDiffuseExponent = 2.0;  // p of seed 004 eq. 3.15 (Banks: 4.8; the chapter: 2)
    TransferFunction::Material material{0.25, 0.75, 0.35, 32.0};
    bool operator==(const TubeShading&) const = default;
};

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
    void drawGBuffer(const FrameDescription& frame, const clip::ClipMeshSet& clip, GBuffer& target);

private:
    gl::Buffer positions_, directions_, colors_, indices_;
    gl::VertexArray vertexArray_;
    gl::Program program_;
    GLsizei indexCount_ = 0;
    bool lines_ = false;
    std::size_t bytes_ = 0;
};

// Deterministic Poisson-disk samples in the unit disk (dart throwing with a fixed seed).
std::vector<glm::vec2> poissonDisk(int count, std::uint32_t seed = 7);

}  // namespace curette
