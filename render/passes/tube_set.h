#pragma once
// Tubes (or illuminated lines) on the GPU and the G-buffer they are drawn into (seed 000 section 3.1.1):
// colour, world normal (tubes) or tangent (lines) with the surface kind, and the view depth along the camera
// axis. The geometry is built in world millimetres on the CPU (render/model/tube_geometry.h) or, for tubes, expanded
// from its swept rings on the GPU (render/passes/gpu_tube_builder.h); or, as impostors, only the swept points are
// uploaded and each segment is ray-cast over its box on the screen (render/model/tube_impostors.h,
// shaders/tube_impostor.comp).

#include "render/passes/clip_mesh_set.h"
#include "gl/program.h"
#include "render/model/frame.h"
#include "render/model/tube_impostors.h"
#include "render/model/tube_vertices.h"

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
    // Impostor tubes (shaders/tube_impostor.comp): per pixel the nearest depth's float bits and the first segment there.
    GLuint nearestDepth() const { return nearestDepth_.name(); }
    GLuint nearestSegment() const { return nearestSegment_.name(); }
    // ... and a bit per point, whether phase 0 found its segment the nearest at a pixel (grown to `points`).
    GLuint candidates(std::size_t points);
    GLuint framebuffer() const { return framebuffer_.name(); }
    std::size_t gpuBytes() const;
    std::vector<float> readDepth() const;
    std::vector<glm::vec4> readColor() const;    // tests: the colour and the normal/tangent + kind, row 0 at the top
    std::vector<glm::vec4> readNormal() const;

private:
    glm::ivec2 size_{0};
    gl::Texture color_, normal_, depth_, partial_, nearestDepth_, nearestSegment_;
    gl::Renderbuffer depthStencil_;
    gl::Buffer candidates_;
    std::size_t candidateWords_ = 0;
    gl::Framebuffer framebuffer_;
};

// The vertex streams of a TubeSet on the GPU, however they were filled.
struct TubeBuffers {
    gl::Buffer positions, directions, colors, indices;   // vec3, vec3, vec4, uint32 (TubeVertices' layout)
    std::size_t vertexCount = 0, indexCount = 0;
    bool lines = false;
    glm::dvec3 boundsMin{0.0}, boundsMax{0.0};           // a world box holding every vertex
    std::size_t bytes() const { return vertexCount * (2 * sizeof(glm::vec3) + sizeof(glm::vec4)) + indexCount * sizeof(std::uint32_t); }
};

class TubeSet {
public:
    // Uploads CPU-built vertices (the box is the vertices' own).
    explicit TubeSet(const TubeVertices& vertices);
    explicit TubeSet(TubeBuffers buffers);
    // Uploads impostor points (16 bytes each). They are taken in windows of at most GL_MAX_TEXTURE_BUFFER_SIZE
    // points, or `windowPoints` (tests force small windows).
    explicit TubeSet(const TubeImpostors& impostors, std::size_t windowPoints = 0);
    bool impostors() const { return impostor_; }
    std::size_t vertexCount() const { return buffers_.vertexCount; }
    // The vertex streams read back from the GPU (tests and bench tracts compare the two builders): all, or
    // `vertexCount` vertices from `firstVertex` and `indexCount` indices from `firstIndex` (a whole-brain set
    // is compared piece by piece).
    TubeVertices readBack() const { return readBack(0, buffers_.vertexCount, 0, buffers_.indexCount); }
    TubeVertices readBack(std::size_t firstVertex, std::size_t vertexCount, std::size_t firstIndex, std::size_t indexCount) const;
    bool lines() const { return lines_; }
    std::size_t triangleCount() const { return lines_ ? 0 : buffers_.indexCount / 3; }
    std::size_t segmentCount() const { return lines_ ? buffers_.indexCount / 2 : 0; }
    std::size_t gpuBytes() const { return impostor_ ? impostorBytes_ : buffers_.bytes(); }
    // The world box around every vertex (the frame plan leaves tubes out of a frame they cannot be seen in).
    glm::dvec3 boundsMin() const { return buffers_.boundsMin; }
    glm::dvec3 boundsMax() const { return buffers_.boundsMax; }
    // Impostors: each point twice, once per phase of shaders/tube_impostor.comp that runs per segment.
    std::size_t primitiveCount() const { return impostor_ ? impostorBundles_.empty() ? 0 : 2 * pointCount_ : lines_ ? segmentCount() : triangleCount(); }
    // The whole set into a cleared G-buffer; or, for an exact frame in slices, the G-buffer cleared and then the
    // primitives [first, first + count) drawn over what earlier ranges drew. Ranges drawn in order give one
    // draw's G-buffer: each fragment is depth-tested against those before it, ties keep the first drawn.
    void drawGBuffer(const FrameDescription& frame, const clip::ClipMeshSet& clip, GBuffer& target);
    void clearGBuffer(glm::ivec2 size, GBuffer& target) const;   // impostors: their scratch too
    void drawGBuffer(const FrameDescription& frame, const clip::ClipMeshSet& clip, GBuffer& target, std::size_t first, std::size_t count);

private:
    gl::Program& programFor(const clip::ClipMeshSet& clip);   // the clip-testing program only when a mesh clips tubes
    void drawElements(const FrameDescription& frame, const clip::ClipMeshSet& clip, std::size_t first, std::size_t count);
    void drawImpostors(const FrameDescription& frame, const clip::ClipMeshSet& clip, GBuffer& target, std::size_t first, std::size_t count);
    void impostorPhase(gl::Program& program, const FrameDescription& frame, int phase, std::size_t first, std::size_t count);

    TubeBuffers buffers_;
    bool impostor_ = false;
    gl::Buffer impostorPoints_;
    gl::Texture impostorTexture_;
    std::vector<TubeImpostorBundle> impostorBundles_;
    std::size_t pointCount_ = 0, impostorBytes_ = 0, windowPoints_ = 0;
    gl::VertexArray vertexArray_;
    gl::Program program_;            // impostors: shaders/tube_impostor.comp
    gl::Program unclippedProgram_;   // when no mesh clips tubes (NO_CLIP_MESHES)
    bool lines_ = false;
};

// Deterministic Poisson-disk samples in the unit disk (dart throwing with a fixed seed).
std::vector<glm::vec2> poissonDisk(int count, std::uint32_t seed = 7);

}  // namespace curette
