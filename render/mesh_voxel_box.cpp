#include "render/mesh_voxel_box.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace curette {

plan::VoxelBox voxelBoxAroundMeshes(const VolumeGeometry& g, const clip::ClipMeshSet& clip) {
    glm::dmat4 worldToIndex = g.worldToIndex();
    double padMm = g.cellDiagonalMm() + 1.0;
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    for (int i = 0; i < clip.count(); ++i) {
        clip::ClipMeshSet::WorldBox box = clip.mapBoxWorldBounds(i);
        for (int corner = 0; corner < 8; ++corner) {
            glm::dvec3 world((corner & 1) ? box.max.x + padMm : box.min.x - padMm, (corner & 2) ? box.max.y + padMm : box.min.y - padMm,
                             (corner & 4) ? box.max.z + padMm : box.min.z - padMm);
            glm::dvec3 index(worldToIndex * glm::dvec4(world, 1.0));
            lo = glm::min(lo, index);
            hi = glm::max(hi, index);
        }
    }
    if (clip.count() == 0 || !glm::all(glm::lessThanEqual(lo, hi))) return {};
    glm::dvec3 dims(g.dims);
    glm::dvec3 first = glm::clamp(glm::floor(lo) - 2.0, glm::dvec3(0.0), dims);
    glm::dvec3 end = glm::clamp(glm::ceil(hi) + 3.0, glm::dvec3(0.0), dims);
    return {glm::ivec3(first), glm::max(glm::ivec3(end) - glm::ivec3(first), glm::ivec3(0))};
}

namespace {

// A parallelepiped in world millimetres: a centre, three edge directions and the half length along each
// (a half length may be 0: a brick one voxel thick on the grid's upper face).
struct Parallelepiped {
    glm::dvec3 centre;
    glm::dvec3 axis[3];   // edge directions (not necessarily unit, never zero)
    double half[3];       // half edge lengths in units of `axis`
    double radiusAlong(glm::dvec3 n) const {
        return std::abs(glm::dot(n, axis[0])) * half[0] + std::abs(glm::dot(n, axis[1])) * half[1] + std::abs(glm::dot(n, axis[2])) * half[2];
    }
};

// Separating axis theorem for two parallelepipeds (convex, three edge directions each): they are disjoint
// iff their projections are disjoint on one of the 3 + 3 face normals or the 9 cross products of edge
// directions. Conservative: an axis separates only by more than a rounding margin, so touching or nearly
// touching counts as intersecting.
bool mayIntersect(const Parallelepiped& a, const Parallelepiped& b) {
    glm::dvec3 axes[15];
    int n = 0;
    for (int i = 0; i < 3; ++i) axes[n++] = glm::cross(a.axis[(i + 1) % 3], a.axis[(i + 2) % 3]);
    for (int i = 0; i < 3; ++i) axes[n++] = glm::cross(b.axis[(i + 1) % 3], b.axis[(i + 2) % 3]);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) axes[n++] = glm::cross(a.axis[i], b.axis[j]);
    glm::dvec3 d = b.centre - a.centre;
    for (const glm::dvec3& axis : axes) {
        double length = glm::length(axis);
        if (!(length > 1e-12)) continue;   // parallel edges: covered by the face normals
        glm::dvec3 u = axis / length;
        double ra = a.radiusAlong(u), rb = b.radiusAlong(u);
        double gap = std::abs(glm::dot(u, d)) - ra - rb;
        if (gap > 1e-9 * (glm::length(d) + ra + rb) + 1e-9) return false;
    }
    return true;
}

// Whether a brick centred at `brickCentre` may meet the ball: within the radius plus `brickCircumradius` (no corner
// of a brick lies farther from its centre) of the ball's centre. Conservative by the rounding margin of
// mayIntersect.
bool mayMeetBall(glm::dvec3 brickCentre, double brickCircumradius, glm::dvec3 centre, double radius) {
    double reach = radius + brickCircumradius;
    return glm::length(brickCentre - centre) <= reach + 1e-9 * reach + 1e-9;
}

}  // namespace

BrickSet bricksAroundMeshes(const VolumeGeometry& g, const clip::ClipMeshSet& clip) {
    BrickSet set = BrickSet::none(g.dims);
    for (int i = 0; i < clip.count(); ++i) set.unite(bricksAroundMesh(g, clip, i));
    return set;
}

namespace {

// The bricks whose voxel centres' parallelepiped meets the oriented box [lo, hi] of a mesh's local frame (placed
// by `toWorld`, rigid) and whose circumscribed ball meets the ball (world centre, radius).
BrickSet bricksMeetingBoxAndBall(const VolumeGeometry& g, glm::dvec3 lo, glm::dvec3 hi, const glm::dmat4& toWorld, glm::dvec3 ballCentre,
                                 double ballRadius) {
    BrickSet set = BrickSet::none(g.dims);
    const glm::dmat3 linear(g.indexToWorld);
    const glm::dmat4 worldToIndex = g.worldToIndex();
    // A whole brick's voxel centres span kVisitBrickSize - 1 cells along each axis; a partial one's fewer.
    const double brickCircumradius = 0.5 * (kVisitBrickSize - 1) * g.cellDiagonalMm();
    Parallelepiped box;
    box.centre = glm::dvec3(toWorld * glm::dvec4(0.5 * (lo + hi), 1.0));
    for (int a = 0; a < 3; ++a) {
        box.axis[a] = glm::dvec3(toWorld[a]);   // the pose's rotation: unit axes
        box.half[a] = 0.5 * (hi[a] - lo[a]);
    }
    // Only the bricks within the box's index-space bounds can meet it.
    glm::dvec3 first(std::numeric_limits<double>::infinity()), last(-std::numeric_limits<double>::infinity());
    for (int corner = 0; corner < 8; ++corner) {
        glm::dvec3 world = box.centre;
        for (int a = 0; a < 3; ++a) world += ((corner >> a) & 1 ? 1.0 : -1.0) * box.half[a] * box.axis[a];
        glm::dvec3 index(worldToIndex * glm::dvec4(world, 1.0));
        first = glm::min(first, index);
        last = glm::max(last, index);
    }
    glm::ivec3 from = glm::ivec3(glm::clamp(glm::floor(first / double(kVisitBrickSize)) - 1.0, glm::dvec3(0.0), glm::dvec3(set.grid)));
    glm::ivec3 to = glm::ivec3(glm::clamp(glm::floor(last / double(kVisitBrickSize)) + 2.0, glm::dvec3(0.0), glm::dvec3(set.grid)));
    for (int bz = from.z; bz < to.z; ++bz)
        for (int by = from.y; by < to.y; ++by)
            for (int bx = from.x; bx < to.x; ++bx) {
                std::size_t b = std::size_t(bx) + std::size_t(set.grid.x) * (std::size_t(by) + std::size_t(set.grid.y) * std::size_t(bz));
                // The brick's voxel centres span [o, o + size - 1] in index space.
                glm::ivec3 o = kVisitBrickSize * glm::ivec3(bx, by, bz);
                glm::dvec3 size(glm::min(glm::ivec3(kVisitBrickSize), g.dims - o));
                Parallelepiped brick;
                brick.centre = glm::dvec3(g.indexToWorld * glm::dvec4(glm::dvec3(o) + 0.5 * (size - 1.0), 1.0));
                for (int a = 0; a < 3; ++a) {
                    brick.axis[a] = linear[a];
                    brick.half[a] = 0.5 * (size[a] - 1.0);
                }
                if (mayMeetBall(brick.centre, brickCircumradius, ballCentre, ballRadius) && mayIntersect(box, brick)) set.visited[b] = 1;
            }
    return set;
}

// The bricks that can hold a voxel centre within `growMm` of both mesh i's depth box and its depth ball
// (clip::ClipMeshSet::depthBoxLocal, depthBallLocal: outside either no depth map says inside).
BrickSet bricksNearDepthMaps(const VolumeGeometry& g, const clip::ClipMeshSet& clip, int i, double growMm) {
    glm::dvec3 lo, hi;
    clip.depthBoxLocal(i, lo, hi);
    const glm::dmat4 toWorld = clip.pose(i).matrix();
    clip::ClipMeshSet::Ball ball = clip.depthBallLocal(i);
    return bricksMeetingBoxAndBall(g, lo - growMm, hi + growMm, toWorld, glm::dvec3(toWorld * glm::dvec4(ball.centre, 1.0)), ball.radius + growMm);
}

}  // namespace

BrickSet bricksAroundMesh(const VolumeGeometry& g, const clip::ClipMeshSet& clip, int i) {
    // The mesh's dilated box (clip::ClipMeshSet::dilatedBoxLocal) and its reach ball (reachBallLocal).
    glm::dvec3 lo, hi;
    clip.dilatedBoxLocal(i, lo, hi);
    glm::dmat4 toWorld = clip.pose(i).matrix();
    clip::ClipMeshSet::Ball ball = clip.reachBallLocal(i);
    return bricksMeetingBoxAndBall(g, lo, hi, toWorld, glm::dvec3(toWorld * glm::dvec4(ball.centre, 1.0)), ball.radius);
}

BrickSet bricksWithinSampleReach(const VolumeGeometry& g, const clip::ClipMeshSet& clip) {
    if (!clip.depthBoxTests()) return BrickSet::all(g.dims);   // step IV then tests the samples of every voxel near a mesh
    // Step IV tests a voxel's samples against mesh i only where nearDepthBox holds: its centre within the sample
    // reach of the depth box (clip::ClipMeshSet::depthBoxLocal) and of the depth ball. Both grown by the reach and
    // a hundredth of a millimetre for the shader's float rounding of the centre; a brick that misses either
    // holds no such voxel.
    const double reach = clipSampleReachMm(g) + 0.01;
    BrickSet set = BrickSet::none(g.dims);
    for (int i = 0; i < clip.count(); ++i) set.unite(bricksNearDepthMaps(g, clip, i, reach));
    return set;
}

BrickSet bricksDeepInsideMeshes(const VolumeGeometry& g, const clip::ClipMeshSet& clip) {
    BrickSet deep = BrickSet::none(g.dims);
    if (!clip.depthBoxTests()) return deep;   // the reference: every sample tested
    // A voxel's clip samples lie in its own cell, within half a step of its centre along each index axis; a
    // brick's, in its voxel centres' box grown by half a step. The shader maps a sample in float: its pixel may
    // be a neighbour of the one computed here and its depth a little off, so the rectangle is grown by a pixel
    // and the depths by a hundredth of a millimetre.
    const double depthSlackMm = 0.01;
    for (int i = 0; i < clip.count(); ++i) {
        const clip::ClippingCamera& camera = clip.camera(i);
        const DepthIntervalPyramid& intervals = clip.depthIntervals(i);
        const glm::dmat4 indexToMap = camera.worldToMap(clip.pose(i)) * g.indexToWorld;
        const glm::dvec2 offset = camera.depthOffset();
        const double scale = camera.depthScale() * intervals.resolution();
        // Only bricks near the depth box and ball can be inside.
        for (std::uint32_t b : bricksNearDepthMaps(g, clip, i, 0.0).visitedIndices()) {
            if (deep.visited[b]) continue;
            // Part by part (a turned cell's box in the map is wider than the cell): the brick is deep when each of
            // its 2^3 blocks of voxels is.
            const glm::ivec3 brickFirst = kVisitBrickSize * visitBrickAt(b, deep.grid), brickEnd = glm::min(brickFirst + kVisitBrickSize, g.dims);
            const glm::ivec3 half(kVisitBrickSize / 2);
            bool inside = true;
            for (int part = 0; part < 8 && inside; ++part) {
                glm::ivec3 from = brickFirst + glm::ivec3(part & 1, (part >> 1) & 1, (part >> 2) & 1) * half;
                glm::ivec3 to = glm::min(from + half, brickEnd);
                if (glm::any(glm::greaterThanEqual(from, to))) continue;   // past the grid's upper faces
                glm::dvec3 first(from), last = glm::dvec3(to - 1);
                glm::dvec2 pixelLo(std::numeric_limits<double>::infinity()), pixelHi(-std::numeric_limits<double>::infinity());
                double zLo = std::numeric_limits<double>::infinity(), zHi = -zLo;
                for (int corner = 0; corner < 8; ++corner) {
                    glm::dvec3 index((corner & 1) ? last.x + 0.5 : first.x - 0.5, (corner & 2) ? last.y + 0.5 : first.y - 0.5,
                                     (corner & 4) ? last.z + 0.5 : first.z - 0.5);
                    glm::dvec3 m(indexToMap * glm::dvec4(index, 1.0));
                    glm::dvec2 pixel = (glm::dvec2(m) - offset) * scale;
                    pixelLo = glm::min(pixelLo, pixel);
                    pixelHi = glm::max(pixelHi, pixel);
                    zLo = std::min(zLo, m.z);
                    zHi = std::max(zHi, m.z);
                }
                inside = intervals.intervalHolds(glm::ivec2(glm::floor(pixelLo)) - 1, glm::ivec2(glm::floor(pixelHi)) + 1, zLo - depthSlackMm,
                                                 zHi + depthSlackMm);
            }
            if (inside) deep.visited[b] = 1;
        }
    }
    return deep;
}

}  // namespace curette
