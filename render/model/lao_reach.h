#pragma once
// Which bricks' LAO a clipped opacity can change (CAO step V, render/passes/ambient_occlusion.h). The dilated maps
// (step III) mark every voxel within R of a mesh; a voxel's LAO changes only if a V_o its rays read differs
// from step I's, and V_o differs only where a clip sample fell inside a mesh AND the voxel has opacity: a mesh
// in empty space changes no LAO. Step IV flags the bricks holding such voxels (shaders/visit_bricks.glsl);
// this class says which bricks lie within the LAO's reach of a flagged one. Step V copies V_PAO in the
// others: every V_o their rays read is step I's, so their LAO is V_PAO bit for bit.
//
// Reach: voxel v's LAO (shaders/lao_ray.glsl) reads V_o trilinearly at q = v + m * step * d_k, m <= M - 1, so
// |q - v| <= (M - 1) * step (AmbientOcclusion::reachMm); the texels u a trilinear read blends lie within one
// index step of q along every axis, |u - q| <= cell diagonal. So V_o(u) can change LAO(v) only if
// |A (u - v)| <= reach + cell diagonal (A the index-to-world linear part). Between bricks B and C = B + d
// (4^3 voxels, render/mesh_voxel_box.h) the voxel offsets u - v are the integer x with
// x_i in [4 d_i - 3, 4 d_i + 3]; d is an offset when the least |A x| over those is within the limit.

#include "render/model/volume_geometry.h"

#include <cstdint>
#include <vector>

namespace curette {

class LaoReachBricks {
public:
    LaoReachBricks(const VolumeGeometry& geometry, double reachMm);

    double limitMm() const { return limitMm_; }   // reach + cell diagonal
    // The offsets d as rows: for each (dy, dz) that has any, the range [dxMin, dxMax] from its least to its
    // greatest offset (anything between counts too: conservative).
    struct Row {
        int dy, dz, dxMin, dxMax;
    };
    const std::vector<Row>& rows() const { return rows_; }
    bool isOffset(glm::ivec3 d) const;

    // Takes the bricks holding a changed V_o: `changed` per brick of a grid of `grid` bricks (x fastest).
    void setChanged(glm::ivec3 grid, const std::vector<std::uint8_t>& changed);
    // Whether a changed brick lies at an offset from `brick` (after setChanged).
    bool canChange(glm::ivec3 brick) const;

private:
    double limitMm_;
    std::vector<Row> rows_;
    glm::ivec3 grid_{0};
    std::vector<std::uint32_t> rowPrefix_;   // per brick row (y, z): changed bricks before x, grid.x + 1 entries
};

}  // namespace curette
