#pragma once
// The cavity surface: the boundary of what the carve removes, as a closed clip::TriangleMesh in world RAS
// mm (for the viewer, for export, and as a clip mesh itself). Marching tetrahedra on the field
// f(v) = tissue(v) * removedFraction(v) at iso 0.5, over the field box padded by one voxel of zeros so the
// surface closes. Each cube of eight voxel centres is split into the six Kuhn (Freudenthal) tetrahedra
// along its main diagonal, the same way in every cube, so neighbouring cubes split their shared faces
// alike. One vertex per crossed lattice edge (shared by every tetrahedron around the edge, no welding by
// position), placed by linear interpolation; triangles face outward, from f >= iso to f < iso. Marching
// tetrahedra has no ambiguous cases, so the result is always a closed, consistently oriented 2-manifold
// (clip::validateClosed passes) unless it is empty.

#include "mesh/triangle_mesh.h"
#include "plan/removal_field.h"

#include <cstdint>
#include <vector>

namespace curette::plan {

// The iso-surface of `values` (one per voxel of `box`, x fastest) at `iso`; voxels outside the box count as
// 0 (so iso must be > 0 for a closed result). "Inside" is values >= iso. Positions: indexToWorld of the
// interpolated index point. Orientation follows the sign of det(indexToWorld) so it is outward in world.
clip::TriangleMesh isoSurfaceTetrahedra(const VoxelBox& box, const std::vector<double>& values, const glm::dmat4& indexToWorld,
                                        double iso);

// The cavity surface of a removal field. `tissueInFieldBox` (plan/tissue_mask.h, over field.box()) may be
// empty: every voxel counts as tissue. Empty mesh when nothing reaches f >= 0.5.
clip::TriangleMesh cavitySurface(const RemovalField& field, const std::vector<std::uint8_t>& tissueInFieldBox);

}  // namespace curette::plan
