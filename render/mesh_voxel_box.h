#pragma once
// The box of voxels the clip meshes can reach: step IV (render/ambient_occlusion.h) and the removal report's
// field (render/removal_probe.h) visit the same voxels.

#include "clip/clip_mesh_set.h"
#include "plan/removal_field.h"
#include "render/volume_geometry.h"

namespace curette {

// The voxels whose clip samples can fall inside a mesh: the box of the meshes' map boxes grown by a cell
// diagonal (the farthest clip sample), one millimetre and two voxels for rounding, clamped to the grid.
// Empty (size 0) without meshes. Step IV (render/ambient_occlusion.h) visits the same box.
plan::VoxelBox voxelBoxAroundMeshes(const VolumeGeometry& geometry, const clip::ClipMeshSet& clip);

}  // namespace curette
