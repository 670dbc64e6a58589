#pragma once
// The accumulated removal of drilling (the drill issue): what the strokes took away, on the scan grid, at
// sub-voxel resolution. Each voxel's cell is split into 4 x 4 x 4 sub-cells, one bit each: a stroke removes
// (erase: restores) the sub-cells whose centres its sweep holds (plan/drill_sweep.h), so strokes add up as
// sets (union; erase is the difference) and undo restores bits exactly. Stored sparsely by bricks of 4^3
// voxels (the bricks CAO visits by), so memory follows the drilled region.
//
// What the rest of curette reads is the voxel's drilled fraction, quantised to a byte
// (drilledByte: round(bits * 255 / 64); fraction = byte / 255): the renderer's texture, step IV's V_o and the
// report use that one number, so they agree exactly. With the live clip meshes it combines as
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

inline constexpr int kRemovalCellsPerAxis = 4;   // sub-cells per voxel axis: 64 bits per voxel
inline constexpr int kRemovalBrickSize = 4;      // voxels per brick axis (render/mesh_voxel_box.h's bricks)
inline constexpr int kRemovalBrickVoxels = kRemovalBrickSize * kRemovalBrickSize * kRemovalBrickSize;

using BrickMasks = std::array<std::uint64_t, kRemovalBrickVoxels>;   // a brick's voxels, x fastest
// The masks of some bricks, by brick number: an undo step's "before" or "after".
using BrickMaskMap = std::map<std::uint32_t, BrickMasks>;

// A lower bound on the world length (mm) of any unit index step of a grid: 1 / |A^-1|_F for its linear part A
// (|A x| >= |x| / |A^-1|_F), so also for sheared grids. How far in index units a world distance can reach.
double smallestStretchMm(const glm::dmat4& indexToWorld);

// A voxel's drilled fraction as stored for the renderer: round(bits * 255 / 64).
std::uint8_t drilledByteFromBits(int bits);

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
    // when given. Returns the number of voxels whose masks changed.
    std::size_t apply(const InsideTest& inside, VoxelBox box, bool erase, BrickMaskMap* before = nullptr);
    // The voxel box that holds a world box (index bounds of its corners, grown by one voxel, clipped).
    VoxelBox voxelBoxAround(glm::dvec3 worldMin, glm::dvec3 worldMax) const;
    // Sets bricks' masks wholesale (undo, redo, loading); bumps the version of those that change.
    void setBricks(const BrickMaskMap& masks);
    BrickMasks brickMasks(std::uint32_t brick) const;   // all zero when never drilled
    void clear();

    std::uint64_t mask(glm::ivec3 voxel) const;
    // Whether the sub-cell holding a world point is drilled (the drilled region as a solid: margins, tract probes).
    bool drilledAt(glm::dvec3 world) const;
    std::uint8_t drilledByte(glm::ivec3 voxel) const { return drilledByteFromBits(std::popcount(mask(voxel))); }
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
