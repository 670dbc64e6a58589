#include "plan/removal_volume.h"

#include "base/error.h"
#include "base/sha256.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace curette::plan {

double smallestStretchMm(const glm::dmat4& indexToWorld) {
    glm::dmat3 inverse = glm::inverse(glm::dmat3(indexToWorld));
    double frobenius = 0;
    for (int c = 0; c < 3; ++c) frobenius += glm::dot(inverse[c], inverse[c]);
    return 1.0 / std::sqrt(frobenius);
}

std::uint8_t drilledByteFromBits(int bits) {
    return static_cast<std::uint8_t>((bits * 255 + kRemovalCellsPerVoxel - 1) / kRemovalCellsPerVoxel);
}

RemovalVolume::RemovalVolume(glm::ivec3 dims, const glm::dmat4& indexToWorld)
    : dims_(dims), indexToWorld_(indexToWorld), worldToIndex_(glm::inverse(indexToWorld)) {
    if (glm::any(glm::lessThan(dims, glm::ivec3(1)))) throw InputError("<removal>", "dims", "a grid of at least one voxel", "");
    bricks_ = (dims + kRemovalBrickSize - 1) / kRemovalBrickSize;
    brickVersion_.assign(static_cast<std::size_t>(bricks_.x) * bricks_.y * bricks_.z, 0);
    glm::dmat3 a(indexToWorld);
    for (int c = 0; c < 4; ++c)
        halfDiagonalMm_ = std::max(halfDiagonalMm_, glm::length(a * glm::dvec3((c & 1) ? -0.5 : 0.5, (c & 2) ? -0.5 : 0.5, 0.5)));
}

std::uint32_t RemovalVolume::brickNumber(glm::ivec3 b) const {
    return static_cast<std::uint32_t>((b.z * bricks_.y + b.y) * bricks_.x + b.x);
}

glm::ivec3 RemovalVolume::brickOrigin(std::uint32_t brick) const {
    int n = static_cast<int>(brick);
    return glm::ivec3(n % bricks_.x, (n / bricks_.x) % bricks_.y, n / (bricks_.x * bricks_.y)) * kRemovalBrickSize;
}

namespace {
int voxelInBrick(glm::ivec3 local) { return (local.z * kRemovalBrickSize + local.y) * kRemovalBrickSize + local.x; }
}  // namespace

VoxelMask RemovalVolume::mask(glm::ivec3 v) const {
    if (glm::any(glm::lessThan(v, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(v, dims_))) return {};
    auto it = masks_.find(brickNumber(v / kRemovalBrickSize));
    return it == masks_.end() ? VoxelMask{} : it->second[static_cast<std::size_t>(voxelInBrick(v % kRemovalBrickSize))];
}

bool RemovalVolume::drilledAt(glm::dvec3 world) const {
    glm::dvec3 index = glm::dvec3(worldToIndex_ * glm::dvec4(world, 1.0));
    glm::ivec3 v(glm::floor(index + 0.5));
    VoxelMask m = mask(v);
    if (isEmpty(m)) return false;
    glm::ivec3 cell = glm::clamp(glm::ivec3(glm::floor((index - glm::dvec3(v) + 0.5) * double(kRemovalCellsPerAxis))), glm::ivec3(0),
                                 glm::ivec3(kRemovalCellsPerAxis - 1));
    return (m[static_cast<std::size_t>(cell.z)] >> (cell.y * kRemovalCellsPerAxis + cell.x)) & 1u;
}

BrickMasks RemovalVolume::brickMasks(std::uint32_t brick) const {
    auto it = masks_.find(brick);
    return it == masks_.end() ? BrickMasks{} : it->second;
}

void RemovalVolume::setBrick(std::uint32_t brick, const BrickMasks& masks) {
    if (brickMasks(brick) == masks) return;
    if (std::all_of(masks.begin(), masks.end(), [](const VoxelMask& m) { return isEmpty(m); })) masks_.erase(brick);
    else masks_[brick] = masks;
    brickVersion_[brick] = ++version_;
}

void RemovalVolume::setBricks(const BrickMaskMap& masks) {
    for (const auto& [brick, m] : masks) {
        if (brick >= brickVersion_.size()) throw InputError("<removal>", "brick", "a brick of the grid", std::to_string(brick));
        setBrick(brick, m);
    }
}

void RemovalVolume::clear() {
    std::vector<std::uint32_t> held;
    for (const auto& entry : masks_) held.push_back(entry.first);
    for (std::uint32_t b : held) setBrick(b, BrickMasks{});
}

VoxelBox RemovalVolume::voxelBoxAround(glm::dvec3 worldMin, glm::dvec3 worldMax) const {
    glm::dvec3 lo(1e300), hi(-1e300);
    for (int c = 0; c < 8; ++c) {
        glm::dvec3 w((c & 1) ? worldMax.x : worldMin.x, (c & 2) ? worldMax.y : worldMin.y, (c & 4) ? worldMax.z : worldMin.z);
        glm::dvec3 i = glm::dvec3(worldToIndex_ * glm::dvec4(w, 1.0));
        lo = glm::min(lo, i), hi = glm::max(hi, i);
    }
    glm::ivec3 first = glm::max(glm::ivec3(glm::floor(lo)) - 1, glm::ivec3(0));
    glm::ivec3 last = glm::min(glm::ivec3(glm::ceil(hi)) + 1, dims_ - 1);
    VoxelBox box;
    box.origin = first;
    box.size = glm::max(last - first + 1, glm::ivec3(0));
    return box;
}

namespace {

// The bits of a cube of s^3 sub-cells from `cell` (within one voxel), set in `m`.
void setCube(VoxelMask& m, glm::ivec3 cell, int s) {
    std::uint64_t row = ((std::uint64_t(1) << s) - 1) << cell.x, slice = 0;
    for (int j = cell.y; j < cell.y + s; ++j) slice |= row << (j * kRemovalCellsPerAxis);
    for (int k = cell.z; k < cell.z + s; ++k) m[static_cast<std::size_t>(k)] |= slice;
}

}  // namespace

std::size_t RemovalVolume::apply(const InsideTest& inside, VoxelBox box, bool erase, BrickMaskMap* before, const DistanceBound& bound) {
    glm::ivec3 first = glm::max(box.origin, glm::ivec3(0));
    glm::ivec3 last = glm::min(box.origin + box.size, dims_) - 1;
    if (glm::any(glm::lessThan(last, first))) return 0;
    std::size_t changed = 0;
    constexpr int n = kRemovalCellsPerAxis;
    auto world = [&](glm::ivec3 voxel, glm::dvec3 cellIndex) {
        return glm::dvec3(indexToWorld_ * glm::dvec4(glm::dvec3(voxel) + cellIndex / double(n) - 0.5, 1.0));
    };
    // The sub-cells of the cube of s^3 from `cell` the region holds, into `covered`: settled whole when the
    // bound at the cube's centre clears its farthest sub-cell centre ((s - 1) / n of the voxel's half
    // diagonal; a micrometre spare for rounding), else split in octants down to single sub-cells, which
    // `inside` decides, so the bits are those of testing every sub-cell.
    auto cover = [&](auto& self, VoxelMask& covered, glm::ivec3 voxel, glm::ivec3 cell, int s) -> void {
        if (s == 1) {
            if (inside(world(voxel, glm::dvec3(cell) + 0.5))) setCube(covered, cell, 1);
            return;
        }
        if (bound) {
            double d = bound(world(voxel, glm::dvec3(cell) + 0.5 * s));
            double reach = (s - 1) * halfDiagonalMm_ / n + 1e-6;
            if (d > reach) return;
            if (d < -reach) return setCube(covered, cell, s);
        }
        int h = s / 2;
        for (int c = 0; c < 8; ++c) self(self, covered, voxel, cell + h * glm::ivec3(c & 1, (c >> 1) & 1, (c >> 2) & 1), h);
    };
    glm::ivec3 firstBrick = first / kRemovalBrickSize, lastBrick = last / kRemovalBrickSize;
    for (int bz = firstBrick.z; bz <= lastBrick.z; ++bz)
        for (int by = firstBrick.y; by <= lastBrick.y; ++by)
            for (int bx = firstBrick.x; bx <= lastBrick.x; ++bx) {
                std::uint32_t brick = brickNumber({bx, by, bz});
                auto held = masks_.find(brick);
                BrickMasks masks = held == masks_.end() ? BrickMasks{} : held->second;
                bool brickChanged = false;
                glm::ivec3 origin = glm::ivec3(bx, by, bz) * kRemovalBrickSize;
                glm::ivec3 lo = glm::max(first, origin), hi = glm::min(last, origin + kRemovalBrickSize - 1);
                for (int z = lo.z; z <= hi.z; ++z)
                    for (int y = lo.y; y <= hi.y; ++y)
                        for (int x = lo.x; x <= hi.x; ++x) {
                            VoxelMask& m = masks[static_cast<std::size_t>(voxelInBrick(glm::ivec3(x, y, z) - origin))];
                            // Nothing to do where every sub-cell already is what this stroke would make it.
                            if (erase ? isEmpty(m) : m == kFullVoxelMask) continue;
                            VoxelMask covered{};
                            cover(cover, covered, glm::ivec3(x, y, z), glm::ivec3(0), n);
                            bool voxelChanged = false;
                            for (std::size_t w = 0; w < m.size(); ++w) {
                                std::uint64_t next = erase ? (m[w] & ~covered[w]) : (m[w] | covered[w]);
                                voxelChanged = voxelChanged || next != m[w];
                                m[w] = next;
                            }
                            changed += voxelChanged;
                            brickChanged = brickChanged || voxelChanged;
                        }
                if (brickChanged) {
                    if (before && !before->count(brick)) (*before)[brick] = brickMasks(brick);
                    setBrick(brick, masks);
                }
            }
    return changed;
}

double RemovalVolume::drilledVolumeMm3() const {
    double voxelMm3 = std::abs(glm::determinant(glm::dmat3(indexToWorld_)));
    double sum = 0;
    for (const auto& [brick, masks] : masks_)
        for (const VoxelMask& m : masks) sum += drilledByteFromBits(drilledCells(m)) / 255.0;
    return sum * voxelMm3;
}

VoxelBox RemovalVolume::drilledBox() const {
    if (masks_.empty()) return {};
    glm::ivec3 lo(INT32_MAX), hi(INT32_MIN);
    for (const auto& entry : masks_) {
        glm::ivec3 o = brickOrigin(entry.first);
        lo = glm::min(lo, o), hi = glm::max(hi, o + kRemovalBrickSize);
    }
    hi = glm::min(hi, dims_);
    return {lo, hi - lo};
}

std::array<std::uint8_t, kRemovalBrickVoxels> RemovalVolume::brickBytes(std::uint32_t brick) const {
    std::array<std::uint8_t, kRemovalBrickVoxels> bytes{};
    auto it = masks_.find(brick);
    if (it == masks_.end()) return bytes;
    for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = drilledByteFromBits(drilledCells(it->second[i]));
    return bytes;
}

std::vector<std::uint32_t> RemovalVolume::bricksChangedSince(std::uint64_t version) const {
    std::vector<std::uint32_t> out;
    if (version >= version_) return out;
    for (std::uint32_t b = 0; b < brickVersion_.size(); ++b)
        if (brickVersion_[b] > version) out.push_back(b);
    return out;
}

std::string RemovalVolume::digest() const {
    std::vector<std::uint32_t> bricks;
    for (const auto& entry : masks_) bricks.push_back(entry.first);
    std::sort(bricks.begin(), bricks.end());
    Sha256 hash;
    for (std::uint32_t b : bricks) {
        const BrickMasks& m = masks_.at(b);
        for (std::size_t i = 0; i < m.size(); ++i) {
            if (isEmpty(m[i])) continue;
            std::uint64_t record[1 + kRemovalWordsPerVoxel] = {std::uint64_t(b) * kRemovalBrickVoxels + i};
            std::copy(m[i].begin(), m[i].end(), record + 1);
            hash.update(std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(record), sizeof record));
        }
    }
    return hash.hexDigest();
}

std::size_t RemovalVolume::storedBytes() const {
    return masks_.size() * (sizeof(BrickMasks) + sizeof(std::uint32_t)) + brickVersion_.size() * sizeof(std::uint64_t);
}

RemovalField withDrilledRemoval(const RemovalField& meshes, const RemovalVolume& drilled) {
    if (drilled.empty()) return meshes;
    if (drilled.dims() != meshes.gridDims) throw std::logic_error("withDrilledRemoval: the removal is not on the field's grid");
    VoxelBox a = meshes.box(), b = drilled.drilledBox();
    glm::ivec3 lo = b.origin, hi = b.origin + b.size;
    if (a.voxelCount() > 0) lo = glm::min(lo, a.origin), hi = glm::max(hi, a.origin + a.size);
    RemovalField out = meshes;
    out.origin = lo;
    out.size = hi - lo;
    out.insideSamples.assign(out.box().voxelCount(), 0);
    const int s = meshes.samplesPerVoxel;
    for (int z = lo.z; z < hi.z; ++z)
        for (int y = lo.y; y < hi.y; ++y)
            for (int x = lo.x; x < hi.x; ++x) {
                glm::ivec3 v(x, y, z);
                int count = a.contains(v) ? meshes.insideSamples[meshes.boxIndex(v)] : 0;
                int byte = drilled.drilledByte(v);
                if (byte > 0) {
                    // Integer form of ceil(S - (S - count) * (255 - byte) / 255).
                    int kept = ((s - count) * (255 - byte)) / 255;   // floor of what stays
                    count = s - kept;
                }
                out.insideSamples[out.boxIndex(v)] = static_cast<std::uint16_t>(count);
            }
    return out;
}

}  // namespace curette::plan
