#pragma once
// The voxels the clip meshes can reach. Two forms:
//  - voxelBoxAroundMeshes: one axis-aligned box (the removal report's field, render/removal_probe.h);
//  - bricksAroundMeshes: the bricks (kVisitBrickSize^3 blocks of the grid) a mesh's oriented dilated box
//    reaches, which steps IV and V visit (render/ambient_occlusion.h). A turned mesh's axis-aligned box grows
//    by up to sqrt(3) per axis; its bricks stay with the oriented box.

#include "clip/clip_mesh_set.h"
#include "plan/removal_field.h"
#include "render/volume_geometry.h"

#include <cstdint>
#include <vector>

namespace curette {

// The voxels whose clip samples can fall inside a mesh: the box of the meshes' map boxes grown by a cell
// diagonal (the farthest clip sample), one millimetre and two voxels for rounding, clamped to the grid.
// Empty (size 0) without meshes. The removal probe (render/removal_probe.h) visits this box.
plan::VoxelBox voxelBoxAroundMeshes(const VolumeGeometry& geometry, const clip::ClipMeshSet& clip);

// The farthest any of a voxel's 9 + N clip samples (clip_coverage.glsl: the corners one index step away
// along every axis, the N offsets in [-1, 1]^3) lies from its centre: a cell diagonal, and a thousandth
// for float rounding. Step IV's near test (sampleReachMm) uses it.
double clipSampleReachMm(const VolumeGeometry& geometry);

// Steps IV and V visit the grid in bricks of kVisitBrickSize^3 voxels, one 64-invocation work group each
// (shaders/visit_bricks.glsl). Bricks on the grid's upper faces are partial.
inline constexpr int kVisitBrickSize = 4;
// The flags of a visited-brick list entry beside the brick number (shaders/visit_bricks.glsl).
inline constexpr std::uint32_t kVisitBrickNumber = 0x3FFFFFFFu, kVisitOpacityChanged = 0x40000000u, kVisitLaoCanChange = 0x80000000u;
// Bricks per axis: ceil(dims / kVisitBrickSize).
inline glm::ivec3 visitBrickGrid(glm::ivec3 dims) { return (dims + kVisitBrickSize - 1) / kVisitBrickSize; }

struct BrickSet {
    glm::ivec3 dims{0};                    // the voxel grid
    glm::ivec3 grid{0};                    // visitBrickGrid(dims)
    std::vector<std::uint8_t> visited;     // per brick (x fastest): 1 = steps IV and V visit it

    static BrickSet none(glm::ivec3 dims);
    static BrickSet all(glm::ivec3 dims);
    std::size_t brickCount() const { return visited.size(); }
    std::size_t visitedCount() const;
    std::uint64_t visitedVoxels() const;   // voxels in visited bricks (partial bricks count what they hold)
    bool visits(glm::ivec3 voxel) const;
    // Adds the bricks of `other` (same grid).
    void unite(const BrickSet& other);
    // The visited bricks' numbers (bx + grid.x * (by + grid.y * bz)), ascending: what the shaders read.
    std::vector<std::uint32_t> visitedIndices() const;
};

// The bricks of the voxels whose V_o, V_m or V_AO a mesh can change: every brick whose voxel centres'
// parallelepiped meets some mesh's dilated box (clip::ClipMeshSet::dilatedBoxLocal, an oriented box: outside it
// neither the depth nor the dilated maps call any point inside), by the separating-axis theorem, and its reach
// ball (clip::ClipMeshSet::reachBallLocal: every point within R of one the depth maps call inside), through the
// brick's circumscribed ball. A voxel outside every such brick has none of its clip samples (within a cell
// diagonal of the centre, less than R) in a mesh, so step IV would write exactly its unclipped opacity, and no
// V_o its LAO reads (within R less a cell diagonal) changed, so step V would write V_PAO; its centre may still
// lie in a dilated shape where the separable kernel reaches past the ball (dilation.comp), but its category
// is read only at visited voxels and next to visited clipped ones, which lie within a cell diagonal of the
// mesh. Several meshes: the union.
BrickSet bricksAroundMeshes(const VolumeGeometry& geometry, const clip::ClipMeshSet& clip);
// ... of mesh `index` alone.
BrickSet bricksAroundMesh(const VolumeGeometry& geometry, const clip::ClipMeshSet& clip, int index);

}  // namespace curette
