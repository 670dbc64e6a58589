#pragma once
// The bricks steps IV and V visit: kVisitBrickSize^3 blocks of the voxel grid, the flags of a visited-brick
// list entry, and a set of bricks. GL-free (shaders/visit_bricks.glsl reads the same layout).

#include "render/model/volume_geometry.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace curette {

// A bound on how far any of a voxel's 9 + N clip samples (clip_coverage.glsl: within the voxel's own cell,
// half a cell diagonal from its centre) lies from its centre: a whole cell diagonal and a thousandth, the
// bound the dilation radius (ambient_occlusion.cpp) was derived with. Step IV's near tests use it.
double clipSampleReachMm(const VolumeGeometry& geometry);

// Steps IV and V visit the grid in bricks of kVisitBrickSize^3 voxels, one 64-invocation work group each
// (shaders/visit_bricks.glsl). Bricks on the grid's upper faces are partial.
inline constexpr int kVisitBrickSize = 4;
// The flags of a visited-brick list entry beside the brick number (shaders/visit_bricks.glsl).
inline constexpr std::uint32_t kVisitBrickNumber = 0x3FFFFFFFu, kVisitOpacityChanged = 0x40000000u, kVisitLaoCanChange = 0x80000000u;
// Bricks per axis: ceil(dims / kVisitBrickSize).
inline glm::ivec3 visitBrickGrid(glm::ivec3 dims) { return (dims + kVisitBrickSize - 1) / kVisitBrickSize; }
// The brick numbered bx + grid.x * (by + grid.y * bz) (a visited-brick list entry's number) on a grid of `grid`.
inline glm::ivec3 visitBrickAt(std::uint32_t number, glm::ivec3 grid) {
    const std::uint32_t gx = std::uint32_t(grid.x), gy = std::uint32_t(grid.y);
    return {int(number % gx), int((number / gx) % gy), int(number / (gx * gy))};
}

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

}  // namespace curette
