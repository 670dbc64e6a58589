#include "render/recast_region.h"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace curette {

namespace {
// Far above the float rounding of the shaders' ray, box and map arithmetic (millimetres), so a ray the GPU finds
// meeting a region is never one the projection leaves out; and a pixel more on every side of what is cast.
constexpr double kMarginMm = 1.0;
constexpr double kMarginPixels = 1.0;

ConvexCorners boxCorners(const clip::RigidPose& pose, glm::dvec3 lo, glm::dvec3 hi) {
    lo -= kMarginMm;
    hi += kMarginMm;
    glm::dmat4 toWorld = pose.matrix();
    ConvexCorners corners;
    for (int c = 0; c < 8; ++c)
        corners.emplace_back(toWorld * glm::dvec4((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z, 1.0));
    return corners;
}

// The region of the points within `growMm` of the box [lo, hi] (local, placed by `pose`) as pieces: the box
// cut along its longest axis into slabs about as long as its shortest side (at most 8), each grown by `growMm`
// and cut to the box [fullLo, fullHi] (which holds the whole region), with a ball around the slab grown as much
// and the ball `whole` (the mesh's own, which holds the whole region too). A point within growMm of the box lies
// within growMm of a point of one slab, so in that piece's box and balls.
void pushPieces(std::vector<ChangedRegion>& regions, const clip::RigidPose& pose, glm::dvec3 lo, glm::dvec3 hi, double growMm, glm::dvec3 fullLo,
                glm::dvec3 fullHi, const WorldBall& whole) {
    glm::dvec3 extent = hi - lo;
    int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
    double shortest = std::max(std::min({extent.x, extent.y, extent.z}), 1e-6);
    int pieces = static_cast<int>(std::clamp(std::round(extent[axis] / shortest), 1.0, 8.0));
    if (pieces == 1) {
        regions.push_back({boxCorners(pose, fullLo, fullHi), whole});
        return;
    }
    for (int j = 0; j < pieces; ++j) {
        glm::dvec3 a = lo, b = hi;
        a[axis] = lo[axis] + extent[axis] * j / pieces;
        b[axis] = j + 1 == pieces ? hi[axis] : lo[axis] + extent[axis] * (j + 1) / pieces;
        glm::dvec3 centre(pose.matrix() * glm::dvec4(0.5 * (a + b), 1.0));
        regions.push_back({boxCorners(pose, glm::max(a - growMm, fullLo), glm::min(b + growMm, fullHi)),
                           {centre, 0.5 * glm::length(b - a) + growMm + kMarginMm}, whole});
    }
}

// Row by row, the pixels in both.
PixelRegion intersection(const PixelRegion& a, const PixelRegion& b) {
    PixelRegion r = a;
    for (std::size_t y = 0; y < r.rows.size(); ++y)
        r.rows[y] = glm::ivec2(std::max(a.rows[y].x, b.rows[y].x), std::min(a.rows[y].y, b.rows[y].y));
    return r;
}
}  // namespace

PixelRegion PixelRegion::none(glm::ivec2 size) {
    return {size, std::vector<glm::ivec2>(static_cast<std::size_t>(std::max(size.y, 0)), glm::ivec2(0))};
}

bool PixelRegion::contains(glm::ivec2 pixel) const {
    if (pixel.y < 0 || pixel.y >= static_cast<int>(rows.size())) return false;
    glm::ivec2 run = rows[static_cast<std::size_t>(pixel.y)];
    return pixel.x >= run.x && pixel.x < run.y;
}

std::int64_t PixelRegion::area() const {
    std::int64_t n = 0;
    for (glm::ivec2 run : rows) n += std::max(run.y - run.x, 0);
    return n;
}

void PixelRegion::unite(const PixelRegion& other) {
    for (std::size_t y = 0; y < rows.size() && y < other.rows.size(); ++y) {
        glm::ivec2 &a = rows[y], b = other.rows[y];
        if (b.x >= b.y) continue;
        a = a.x >= a.y ? b : glm::ivec2(std::min(a.x, b.x), std::max(a.y, b.y));
    }
}

ClipSnapshot ClipSnapshot::of(const clip::ClipMeshSet& set, double cellDiagonalMm) {
    ClipSnapshot s;
    s.mapRenders = set.mapRenderCount();
    s.depthBoxTests = set.depthBoxTests();
    for (int i = 0; i < set.count(); ++i) {
        ClipMeshReach m;
        m.pose = set.pose(i);
        glm::dvec3 depthLo, depthHi;
        set.depthBoxLocal(i, depthLo, depthHi);
        if (s.depthBoxTests) {
            m.clipLo = depthLo;
            m.clipHi = depthHi;
        } else {
            set.mapBoxLocal(i, m.clipLo, m.clipHi);
        }
        set.dilatedBoxLocal(i, m.ambientLo, m.ambientHi);
        m.ambientLo -= cellDiagonalMm;
        m.ambientHi += cellDiagonalMm;
        // The balls (clip::ClipMeshSet::depthBallLocal, reachBallLocal): the depth ball holds every point the
        // depth maps call inside; the reach ball every point within R of one, and so every voxel whose V_AO the
        // mesh can change; a cell diagonal more, like the box, for the samples that read it.
        clip::ClipMeshSet::Ball depthBall = set.depthBallLocal(i), reachBall = set.reachBallLocal(i);
        m.centre = depthBall.centre;
        m.clipRadius = depthBall.radius;
        m.ambientRadius = reachBall.radius + cellDiagonalMm;
        m.ambientReachMm = set.dilationRadiusMm() + cellDiagonalMm;
        s.meshes.push_back(m);
    }
    return s;
}

std::optional<std::vector<ChangedRegion>> changedRegions(const ClipSnapshot& before, const ClipSnapshot& now, bool ambient) {
    // The maps drawn again (a mesh's geometry or scale, the resolution or the dilation radius changed), a mesh
    // added or removed, or the depth-box tests switched: more than poses.
    if (before.mapRenders != now.mapRenders || before.depthBoxTests != now.depthBoxTests || before.meshes.size() != now.meshes.size())
        return std::nullopt;
    std::vector<ChangedRegion> regions;
    for (std::size_t i = 0; i < now.meshes.size(); ++i) {
        ClipMeshReach a = before.meshes[i], b = now.meshes[i];
        if (a == b) continue;
        b.pose = a.pose;
        if (!(a == b)) return std::nullopt;   // more than the pose
        for (const clip::RigidPose& pose : {before.meshes[i].pose, now.meshes[i].pose}) {
            // The points the maps call inside lie in the clip box (and ball); V_AO changes within the ambient reach
            // of them (and in the ambient box and ball).
            glm::dvec3 centre(pose.matrix() * glm::dvec4(a.centre, 1.0));
            pushPieces(regions, pose, a.clipLo, a.clipHi, 0.0, a.clipLo, a.clipHi, {centre, a.clipRadius + kMarginMm});
            if (ambient)
                pushPieces(regions, pose, a.clipLo, a.clipHi, a.ambientReachMm, a.ambientLo, a.ambientHi, {centre, a.ambientRadius + kMarginMm});
        }
    }
    return regions;
}

std::optional<PixelRegion> pixelsMeeting(const ConvexCorners& corners, const FrameDescription& frame) {
    // A ray starts at the eye (raycast.comp), and the projection of a hull wholly in front of the eye's plane is
    // the hull of its corners' projections. Pixel centres as pixel_ray.glsl: ndc = (pixel + 0.5) / size * 2 - 1,
    // y up; here in pixel units, y down, a centre at (x + 0.5, y + 0.5).
    glm::dvec2 size(frame.size);
    glm::dmat4 viewProjection = frame.camera.viewProjection(frame.size);
    std::vector<glm::dvec2> points;
    double top = std::numeric_limits<double>::infinity(), bottom = -top;
    for (const glm::dvec3& corner : corners) {
        glm::dvec4 clip = viewProjection * glm::dvec4(corner, 1.0);
        if (!(clip.w > 1e-9)) return std::nullopt;
        glm::dvec2 p((clip.x / clip.w + 1.0) * 0.5 * size.x, (1.0 - clip.y / clip.w) * 0.5 * size.y);
        points.push_back(p);
        top = std::min(top, p.y);
        bottom = std::max(bottom, p.y);
    }
    PixelRegion region = PixelRegion::none(frame.size);
    // Row y: the hull's extent across the strip of its centre line widened by the margin. Every point of a
    // segment between two corners lies in the hull, and the hull's extreme points within the strip are corners
    // in it or crossings of its edges (segments among those) with the strip's lines.
    int firstRow = static_cast<int>(std::clamp(std::floor(top - 0.5 - kMarginPixels), 0.0, size.y));
    int endRow = static_cast<int>(std::clamp(std::ceil(bottom - 0.5 + kMarginPixels) + 1.0, 0.0, size.y));
    for (int y = firstRow; y < endRow; ++y) {
        double lo = y + 0.5 - kMarginPixels, hi = y + 0.5 + kMarginPixels;
        double left = std::numeric_limits<double>::infinity(), right = -left;
        for (std::size_t i = 0; i < points.size(); ++i) {
            const glm::dvec2& p = points[i];
            if (p.y >= lo && p.y <= hi) left = std::min(left, p.x), right = std::max(right, p.x);
            for (std::size_t j = i + 1; j < points.size(); ++j) {
                const glm::dvec2& q = points[j];
                for (double line : {lo, hi}) {
                    if ((p.y - line) * (q.y - line) > 0.0 || p.y == q.y) continue;
                    double x = p.x + (q.x - p.x) * (line - p.y) / (q.y - p.y);
                    left = std::min(left, x);
                    right = std::max(right, x);
                }
            }
        }
        if (!(left <= right)) continue;
        // Pixels whose centre lies within the margin of [left, right] (clamped before the conversion to int).
        double from = std::clamp(std::ceil(left - 0.5 - kMarginPixels), 0.0, size.x);
        double to = std::clamp(std::floor(right - 0.5 + kMarginPixels) + 1.0, 0.0, size.x);
        region.rows[static_cast<std::size_t>(y)] = glm::ivec2(static_cast<int>(from), static_cast<int>(to));
    }
    return region;
}

std::optional<PixelRegion> pixelsMeeting(const WorldBall& ball, const FrameDescription& frame) {
    // The rays that meet the ball form a cone from the eye of half-angle asin(r / d). The frustum of the pyramid
    // around it whose cross-sections are octagons circumscribing the cone's circles, between the ball's nearest
    // and farthest distances along the axis, holds the ball; its projection is that of the pyramid.
    glm::dvec3 eye = frame.camera.position();
    glm::dvec3 axis = ball.centre - eye;
    double d = glm::length(axis);
    if (!(d > ball.radius * (1.0 + 1e-9))) return std::nullopt;
    axis /= d;
    glm::dvec3 side = glm::normalize(glm::cross(axis, std::abs(axis.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0)));
    glm::dvec3 up = glm::cross(side, axis);
    double tangent = ball.radius / std::sqrt(d * d - ball.radius * ball.radius);
    const int sides = 8;
    double circumscribe = 1.0 / std::cos(glm::pi<double>() / sides);
    ConvexCorners corners;
    for (double s : {d - ball.radius, d + ball.radius})
        for (int k = 0; k < sides; ++k) {
            double phi = 2.0 * glm::pi<double>() * k / sides;
            corners.push_back(eye + s * axis + s * tangent * circumscribe * (std::cos(phi) * side + std::sin(phi) * up));
        }
    return pixelsMeeting(corners, frame);
}

std::optional<PixelRegion> pixelsMeeting(const std::vector<ChangedRegion>& regions, const FrameDescription& frame) {
    PixelRegion all = PixelRegion::none(frame.size);
    for (const ChangedRegion& r : regions) {
        // A ray that meets the region meets its box and each of its balls.
        std::optional<PixelRegion> meeting;
        for (std::optional<PixelRegion> part : {pixelsMeeting(r.box, frame), pixelsMeeting(r.ball, frame),
                                                r.wholeBall ? pixelsMeeting(*r.wholeBall, frame) : std::nullopt})
            if (part) meeting = meeting ? intersection(*meeting, *part) : *part;
        if (!meeting) return std::nullopt;
        all.unite(*meeting);
    }
    return all;
}

std::optional<ChangedRegion> drilledRegion(const plan::RemovalVolume& removal, std::uint64_t since, double growMm) {
    std::vector<std::uint32_t> bricks = removal.bricksChangedSince(since);
    if (bricks.empty()) return std::nullopt;
    glm::ivec3 lo(INT32_MAX), hi(INT32_MIN);
    for (std::uint32_t b : bricks) {
        glm::ivec3 o = removal.brickOrigin(b);
        lo = glm::min(lo, o), hi = glm::max(hi, o + plan::kRemovalBrickSize - 1);
    }
    // In index units at most growMm / the grid's smallest stretch, and half a voxel: a voxel's cell around its centre.
    double growIndex = growMm / plan::smallestStretchMm(removal.indexToWorld()) + 0.5;
    glm::dvec3 a = glm::dvec3(lo) - growIndex, b = glm::dvec3(hi) + growIndex;
    ChangedRegion region;
    glm::dvec3 centre(0.0);
    for (int c = 0; c < 8; ++c) {
        glm::dvec3 index((c & 1) ? b.x : a.x, (c & 2) ? b.y : a.y, (c & 4) ? b.z : a.z);
        region.box.push_back(glm::dvec3(removal.indexToWorld() * glm::dvec4(index, 1.0)));
        centre += region.box.back() / 8.0;
    }
    double radius = 0;
    for (const glm::dvec3& corner : region.box) radius = std::max(radius, glm::length(corner - centre));
    region.ball = {centre, radius};
    return region;
}

}  // namespace curette
