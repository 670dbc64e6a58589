#pragma once
// The accumulated removal of drilling (the drill issue): what the strokes took away, on the scan grid, at
// sub-voxel resolution. Each voxel's cell is split into 8 x 8 x 8 sub-cells, one bit each (512 bits: eight
// 64-bit words, word k the sub-cells of z-slice k, bit i + 8 j): a stroke removes (erase: restores) the
// sub-cells whose centres its sweep holds (plan/drill_sweep.h), so strokes add up as sets (union; erase is the
// difference) and undo restores bits exactly. 8 per axis, not 4: a 2 mm burr's capsule on a 1 mm grid came out
// up to +1.2 % at 4 (the sub-cell lattice beating with the stroke), +0.4 % at 8. Stored sparsely by bricks of
// 4^3 voxels (the bricks CAO visits by), so memory follows the drilled region.
//
// What the rest of curette reads is the voxel's drilled fraction, quantised to a byte
// (drilledByte: ceil(bits * 255 / 512); fraction = byte / 255), rounded up so a voxel is never shown or
// counted less drilled than its bits say (one drilled sub-cell is byte 1, not 0): the renderer's texture,
// step IV's V_o and the report use that one number, so they agree exactly. With the live clip meshes it combines as
// removed = 1 - (1 - meshes) * (1 - drilled) (plan/removal_field.h): where a mesh and the drilled region both
// cover part of one voxel the removal is counted as if they overlapped independently, which can overstate
// (never understate) that voxel's removal.

#include "plan/removal_field.h"

#include <glm/glm.hpp>

#include <array>
#include <bit>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

namespace curette::plan {

inline constexpr int kRemovalCellsPerAxis = 8;   // sub-cells per voxel axis
inline constexpr int kRemovalCellsPerVoxel = kRemovalCellsPerAxis * kRemovalCellsPerAxis * kRemovalCellsPerAxis;
inline constexpr int kRemovalWordsPerVoxel = kRemovalCellsPerVoxel / 64;   // a word per z-slice of sub-cells
static_assert(kRemovalCellsPerAxis * kRemovalCellsPerAxis == 64, "a z-slice of sub-cells is one 64-bit word");
inline constexpr int kRemovalBrickSize = 4;      // voxels per brick axis (render/mesh_voxel_box.h's bricks)
inline constexpr int kRemovalBrickVoxels = kRemovalBrickSize * kRemovalBrickSize * kRemovalBrickSize;

// A voxel's sub-cells: bit i + 8 j of word k is the sub-cell (i, j, k), centred at the voxel's index +
// ((i, j, k) + 0.5) / 8 - 0.5.
using VoxelMask = std::array<std::uint64_t, kRemovalWordsPerVoxel>;
inline constexpr VoxelMask kFullVoxelMask = [] {
    VoxelMask m{};
    for (std::uint64_t& w : m) w = ~std::uint64_t(0);
    return m;
}();
inline int drilledCells(const VoxelMask& m) {
    int n = 0;
    for (std::uint64_t w : m) n += std::popcount(w);
    return n;
}
inline bool isEmpty(const VoxelMask& m) { return m == VoxelMask{}; }

using BrickMasks = std::array<VoxelMask, kRemovalBrickVoxels>;   // a brick's voxels, x fastest
// The masks of some bricks, by brick number: an undo step's "before" or "after".
using BrickMaskMap = std::map<std::uint32_t, BrickMasks>;

// A lower bound on the world length (mm) of any unit index step of a grid: 1 / |A^-1|_F for its linear part A
// (|A x| >= |x| / |A^-1|_F), so also for sheared grids. How far in index units a world distance can reach.
double smallestStretchMm(const glm::dmat4& indexToWorld);

// A voxel's drilled fraction as stored for the renderer: ceil(bits * 255 / 512).
std::uint8_t drilledByteFromBits(int bits);

// A conservative signed distance (mm, world) to the region an InsideTest holds: d > 0 means no point within d
// of p is inside, d < 0 that every point within -d is; 0 says nothing. Lets apply() settle a voxel, or a block
// of its sub-cells, from one value at its centre.
using DistanceBound = std::function<double(glm::dvec3 world)>;

class RemovalVolume {
public:
    RemovalVolume(glm::ivec3 dims, const glm::dmat4& indexToWorld);

    glm::ivec3 dims() const { return dims_; }
    const glm::dmat4& indexToWorld() const { return indexToWorld_; }
    glm::ivec3 brickGrid() const { return bricks_; }
    std::uint32_t brickNumber(glm::ivec3 brick) const;
    glm::ivec3 brickOrigin(std::uint32_t brick) const;   // its first voxel

    // Removes (erase: restores) every sub-cell whose centre `inside` holds, over the voxels of `box` (clipped to
    // the grid). A brick's masks are added to `before` the first time this touches it (an undo step's record),
    // when given. With `bound`, a voxel (then each octant, down to 2^3 sub-cells) whose centre's bound shows it
    // wholly inside or outside is settled at once, the same bits as testing every sub-cell, and only blocks at
    // the region's surface are sampled. Returns the number of voxels whose masks changed.
    std::size_t apply(const InsideTest& inside, VoxelBox box, bool erase, BrickMaskMap* before = nullptr, const DistanceBound& bound = {});
    // The voxel box that holds a world box (index bounds of its corners, grown by one voxel, clipped).
    VoxelBox voxelBoxAround(glm::dvec3 worldMin, glm::dvec3 worldMax) const;
    // Sets bricks' masks wholesale (undo, redo, loading); bumps the version of those that change.
    void setBricks(const BrickMaskMap& masks);
    BrickMasks brickMasks(std::uint32_t brick) const;   // all zero when never drilled
    void clear();

    VoxelMask mask(glm::ivec3 voxel) const;
    // Whether the sub-cell holding a world point is drilled (the drilled region as a solid: margins, tract probes).
    bool drilledAt(glm::dvec3 world) const;
    std::uint8_t drilledByte(glm::ivec3 voxel) const { return drilledByteFromBits(drilledCells(mask(voxel))); }
    double drilledFraction(glm::ivec3 voxel) const { return drilledByte(voxel) / 255.0; }
    bool empty() const { return masks_.empty(); }
    double drilledVolumeMm3() const;       // sum of drilled fractions times the voxel volume
    VoxelBox drilledBox() const;           // the bricks holding a drilled voxel (size 0: none)
    // A brick's drilled bytes, x fastest, kRemovalBrickVoxels of them (voxels past the grid's edge: 0).
    std::array<std::uint8_t, kRemovalBrickVoxels> brickBytes(std::uint32_t brick) const;

    // Every change bumps the version; bricksChangedSince(v) lists the bricks changed after version v.
    std::uint64_t version() const { return version_; }
    std::vector<std::uint32_t> bricksChangedSince(std::uint64_t version) const;
    std::size_t storedBricks() const { return masks_.size(); }
    // SHA-256 of every drilled voxel's index and mask, in voxel order: equal digests, equal removals.
    std::string digest() const;
    std::size_t storedBytes() const;

private:
    void setBrick(std::uint32_t brick, const BrickMasks& masks);
    glm::ivec3 dims_;
    glm::dmat4 indexToWorld_, worldToIndex_;
    double halfDiagonalMm_ = 0;   // the longest world distance from a voxel's centre to its corners
    glm::ivec3 bricks_;
    std::unordered_map<std::uint32_t, BrickMasks> masks_;    // only bricks with a bit set
    std::vector<std::uint64_t> brickVersion_;                // per brick: the version of its last change
    std::uint64_t version_ = 0;
};

// The report's removal field with the drilled removal folded in: the box grown to hold the drilled bricks, and
// each voxel's count made ceil(S * (1 - (1 - count / S) * (1 - drilled))) for S = samplesPerVoxel, the
// combination step IV applies to V_o, rounded up so the report never counts less removed than that.
RemovalField withDrilledRemoval(const RemovalField& meshes, const RemovalVolume& drilled);

}  // namespace curette::plan
