#pragma once
// The removal field: for each voxel of a box of the scan grid, how many of step IV's 9 + N clip samples
// (CAO Algorithm 2: centre, the eight corners of the voxel's own cell, then N anti-aliasing offsets in that
// cell where those nine disagree)
// lie inside a clip mesh. count / (9 + N) is the fraction of the voxel the carve removes: the complement of
// the visible fraction Algorithm 2 line 10 scales the opacity by. The GPU pass writes exactly this (same
// samples, same clip test as the renderer); removalFieldCpu is its CPU oracle through clip::insideSampleCount.

#include "mesh/rigid_pose.h"
#include "mesh/triangle_mesh.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

namespace curette::plan {

// The N the report's field refines a partly covered voxel with, whatever the renderer's: the same clip test
// and sample cell as step IV, a finer quadrature of it. Step IV's N only weighs a voxel's opacity; with 32 a
// 5 mm box on 3 mm slices is reported 3 % small, with 256 within 0.5 %.
inline constexpr int kReportAntiAliasingSamples = 256;

// Whether a world point (RAS mm) lies inside the clip region (the union of the posed meshes).
using InsideTest = std::function<bool(glm::dvec3 world)>;

// A box of voxels of a grid: voxels origin .. origin + size - 1.
struct VoxelBox {
    glm::ivec3 origin{0};
    glm::ivec3 size{0};
    std::size_t voxelCount() const {
        return static_cast<std::size_t>(size.x) * static_cast<std::size_t>(size.y) * static_cast<std::size_t>(size.z);
    }
    bool contains(glm::ivec3 v) const {
        return glm::all(glm::greaterThanEqual(v, origin)) && glm::all(glm::lessThan(v, origin + size));
    }
};

struct RemovalField {
    glm::ivec3 gridDims{0};            // the scan grid
    glm::dmat4 indexToWorld{1.0};      // its voxel centre -> world RAS mm
    glm::ivec3 origin{0}, size{0};     // the box of the grid the field covers; outside it nothing is removed
    int samplesPerVoxel = 9;           // 9 + N
    double facePlacementMm = 0;        // how far the clip test can put a face from the mesh's (half a depth-map
                                       // pixel, the largest over the meshes; 0 for an exact inside test)
    std::vector<std::uint16_t> insideSamples;  // size.x * size.y * size.z, x fastest, each in [0, samplesPerVoxel]

    VoxelBox box() const { return {origin, size}; }
    // Index into insideSamples of a voxel of the box (global grid index).
    std::size_t boxIndex(glm::ivec3 globalIndex) const {
        glm::ivec3 l = globalIndex - origin;
        return (static_cast<std::size_t>(l.z) * static_cast<std::size_t>(size.y) + static_cast<std::size_t>(l.y)) *
                   static_cast<std::size_t>(size.x) + static_cast<std::size_t>(l.x);
    }
    // count / (9 + N) inside the box, 0 outside it.
    double removedFraction(glm::ivec3 globalIndex) const;
    // Throws InputError unless the sizes agree, the box lies in the grid and every count is in range.
    void validate() const;
};

// The CPU oracle of the GPU pass: Algorithm 2's sample count for every voxel of the box (clipped to the grid).
// `offsets` are the N anti-aliasing offsets (clip::antiAliasingOffsets(N)).
RemovalField removalFieldCpu(glm::ivec3 dims, const glm::dmat4& indexToWorld, glm::ivec3 origin, glm::ivec3 size,
                             const InsideTest& inside, const std::vector<glm::dvec3>& offsets);

// A clip mesh as the renderer places it: geometry in local mm, scaled per axis, then posed rigidly.
struct PosedMesh {
    std::shared_ptr<const clip::TriangleMesh> geometry;
    clip::RigidPose pose;
    glm::dvec3 scale{1.0};
    // The mesh's vertices in world RAS mm, in the order of geometry->positions (empty without geometry).
    std::vector<glm::dvec3> worldVertices() const;
};

// The union of the posed meshes: inside when clip::containsPoint(mesh, local) for any of them, with
// local = inverse(pose) * world / scale. A bounding-box rejection per mesh keeps far points cheap.
InsideTest insideAnyMesh(std::vector<PosedMesh> meshes);

// The box of grid voxels whose samples can reach a posed mesh: the index-space bounds of the meshes' world
// bounding boxes, grown by two voxels (a voxel's samples lie within half an index step of its centre; the
// rest is slack for rounding), clamped to the grid. Empty (size 0) when no mesh overlaps the grid.
VoxelBox boxAroundMeshes(const std::vector<PosedMesh>& meshes, glm::ivec3 dims, const glm::dmat4& indexToWorld);

}  // namespace curette::plan
