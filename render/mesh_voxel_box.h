#pragma once
// The voxels the clip meshes can reach. Two forms:
//  - voxelBoxAroundMeshes: one axis-aligned box (the removal report's field, render/passes/removal_probe.h);
//  - bricksAroundMeshes: the bricks (kVisitBrickSize^3 blocks of the grid) a mesh's oriented dilated box
//    reaches, which steps IV and V visit (render/passes/ambient_occlusion.h). A turned mesh's axis-aligned box grows
//    by up to sqrt(3) per axis; its bricks stay with the oriented box.

#include "render/passes/clip_mesh_set.h"
#include "plan/removal_field.h"
#include "render/model/brick_set.h"
#include "render/model/volume_geometry.h"

#include <cstdint>
#include <vector>

namespace curette {

// The voxels whose clip samples can fall inside a mesh: the box of the meshes' map boxes grown by a cell
// diagonal (the farthest clip sample), one millimetre and two voxels for rounding, clamped to the grid.
// Empty (size 0) without meshes. The removal probe (render/passes/removal_probe.h) visits this box.
plan::VoxelBox voxelBoxAroundMeshes(const VolumeGeometry& geometry, const clip::ClipMeshSet& clip);

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

// The bricks holding a voxel one of whose clip samples step IV tests against the depth maps of some mesh
// (shaders/clip_coverage.glsl meshesWithinSampleReach): those whose voxel centres come within the sample reach
// (clipSampleReachMm) of a mesh's depth box and its depth ball (clip::ClipMeshSet::depthBoxLocal,
// depthBallLocal). Elsewhere every voxel's count of samples inside is 0 without a test. Every brick when the
// set's depth-box tests are off.
BrickSet bricksWithinSampleReach(const VolumeGeometry& geometry, const clip::ClipMeshSet& clip);

// The bricks whose every voxel has every clip sample inside one mesh, by that mesh's depth maps (read back,
// clip::ClipMeshSet::depthIntervals): one interval holds the depths of the voxels' cells, grown by the float
// rounding of the shader's sample points, at every map pixel they cover. There step IV's count is 9 + N without
// a test: such a mesh's dilated shape holds the centre and its depth box and ball the samples, so the shader
// would test it and find all nine samples inside. None when the set's depth-box tests are off (the reference
// that tests every sample).
BrickSet bricksDeepInsideMeshes(const VolumeGeometry& geometry, const clip::ClipMeshSet& clip);

}  // namespace curette
