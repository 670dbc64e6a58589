#include "render/recast_region.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace curette {

namespace {
// Far above the float rounding of the shaders' ray and box arithmetic (millimetres, pixels), so a ray the GPU
// finds meeting a box is never one the projection leaves out.
constexpr double kBoxMarginMm = 1.0;
constexpr int kPixelMargin = 1;

WorldCorners cornersOf(const clip::RigidPose& pose, glm::dvec3 lo, glm::dvec3 hi) {
    lo -= kBoxMarginMm;
    hi += kBoxMarginMm;
    glm::dmat4 toWorld = pose.matrix();
    WorldCorners corners;
    for (int c = 0; c < 8; ++c)
        corners[static_cast<std::size_t>(c)] = glm::dvec3(toWorld * glm::dvec4((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z, 1.0));
    return corners;
}
}  // namespace

PixelRect PixelRect::unitedWith(const PixelRect& other) const {
    if (empty()) return other;
    if (other.empty()) return *this;
    return {glm::min(min, other.min), glm::max(max, other.max)};
}

ClipSnapshot ClipSnapshot::of(const clip::ClipMeshSet& set, double cellDiagonalMm) {
    ClipSnapshot s;
    s.mapRenders = set.mapRenderCount();
    s.depthBoxTests = set.depthBoxTests();
    for (int i = 0; i < set.count(); ++i) {
        ClipMeshReach m;
        m.pose = set.pose(i);
        if (s.depthBoxTests) {
            set.depthBoxLocal(i, m.clipLo, m.clipHi);
        } else {
            set.mapBoxLocal(i, m.clipLo, m.clipHi);
        }
        set.dilatedBoxLocal(i, m.ambientLo, m.ambientHi);
        m.ambientLo -= cellDiagonalMm;
        m.ambientHi += cellDiagonalMm;
        s.meshes.push_back(m);
    }
    return s;
}

std::optional<std::vector<WorldCorners>> changedBoxes(const ClipSnapshot& before, const ClipSnapshot& now, bool ambient) {
    // The maps drawn again (a mesh's geometry or scale, the resolution or the dilation radius changed), a mesh
    // added or removed, or the depth-box tests switched: more than poses.
    if (before.mapRenders != now.mapRenders || before.depthBoxTests != now.depthBoxTests || before.meshes.size() != now.meshes.size())
        return std::nullopt;
    std::vector<WorldCorners> boxes;
    for (std::size_t i = 0; i < now.meshes.size(); ++i) {
        const ClipMeshReach &a = before.meshes[i], &b = now.meshes[i];
        if (a == b) continue;
        if (a.clipLo != b.clipLo || a.clipHi != b.clipHi || a.ambientLo != b.ambientLo || a.ambientHi != b.ambientHi) return std::nullopt;
        for (const ClipMeshReach* m : {&a, &b}) {
            boxes.push_back(cornersOf(m->pose, m->clipLo, m->clipHi));
            if (ambient) boxes.push_back(cornersOf(m->pose, m->ambientLo, m->ambientHi));
        }
    }
    return boxes;
}

std::optional<PixelRect> pixelsMeeting(const std::vector<WorldCorners>& boxes, const FrameDescription& frame) {
    // A ray starts at the eye (raycast.comp), and the projection of a box wholly in front of it is the convex hull
    // of its corners' projections; the pixel centres of pixel_ray.glsl: ndc = (pixel + 0.5) / size * 2 - 1, y up.
    glm::dvec2 size(frame.size);
    glm::dmat4 viewProjection = frame.camera.projection(size.x / size.y) * frame.camera.view();
    PixelRect all;
    for (const WorldCorners& box : boxes) {
        glm::dvec2 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
        for (const glm::dvec3& corner : box) {
            glm::dvec4 clip = viewProjection * glm::dvec4(corner, 1.0);
            if (!(clip.w > 1e-9)) return std::nullopt;   // at or behind the eye
            glm::dvec2 ndc(clip.x / clip.w, clip.y / clip.w);
            glm::dvec2 pixel((ndc.x + 1.0) * 0.5 * size.x, (1.0 - ndc.y) * 0.5 * size.y);   // where pixel centres are at +0.5
            lo = glm::min(lo, pixel);
            hi = glm::max(hi, pixel);
        }
        // Pixels whose centre lies in [lo, hi], widened by a margin and kept within the image (before the
        // conversion to int, so far-off corners do not overflow it).
        glm::dvec2 from = glm::clamp(glm::floor(lo - 0.5) - double(kPixelMargin), glm::dvec2(0.0), size);
        glm::dvec2 to = glm::clamp(glm::ceil(hi - 0.5) + double(kPixelMargin + 1), glm::dvec2(0.0), size);
        all = all.unitedWith(PixelRect{glm::ivec2(from), glm::ivec2(to)});
    }
    return all;
}

}  // namespace curette
