#pragma once
// Which pixels an exact frame casts again when, since the last exact image, only clip meshes have moved
// (docs/subsystems.md, "Pixels an exact frame casts again"). A pixel is its ray's alone (shaders/raycast.comp:
// the same camera, volume, TF, settings and jitter give the same samples), so where the ray meets nothing that
// changed it is the last image's pixel bit for bit. A rigid motion of mesh i changes, along a ray:
//  - its clip tests: a sample's answer changes only where the mesh's depth maps call it inside at the old pose
//    or the new one, within the mesh's bounding ball grown by a map pixel and inside its depth box
//    (clip::ClipMeshSet::depthBoxLocal; without the depth-box tests, its map box), and the cut face and the
//    rules after a crossing follow a sample inside;
//  - V_AO (lao, cao): V_AO = LAO(V_o) at every voxel (the exactness contract); a clip sample of voxel u lies
//    within a cell diagonal of u, and LAO(v) reads V_o, and the seam rule the categories, within the reach plus
//    a cell diagonal of v, so V_AO changes only within R (AmbientOcclusion::dilationRadiusMm) of a point the
//    maps call inside: inside the dilated box (clip::ClipMeshSet::dilatedBoxLocal, which grows the bounds by
//    more than R) and the ball grown as much; a sample reads V_AO within a cell diagonal of itself, so both
//    grown by one more.
// Each region is the intersection of a box and a ball, taken at the old pose and the new one; a pixel is cast
// when its centre ray can meet one. Anything else that changed (camera, size, mode, settings, volume, TF, LAO
// settings, the meshes' geometry, scale, number or maps, tubes in the frame) casts every pixel.

#include "plan/removal_volume.h"
#include "render/passes/clip_mesh_set.h"
#include "render/model/frame.h"

#include <cstdint>
#include <optional>
#include <vector>

namespace curette {

// Pixels of an image row by row: row y holds the pixels [rows[y].x, rows[y].y) (none when x >= y). Row 0 is the
// top of the picture.
struct PixelRegion {
    glm::ivec2 size{0};
    std::vector<glm::ivec2> rows;
    static PixelRegion none(glm::ivec2 size);
    bool contains(glm::ivec2 pixel) const;
    std::int64_t area() const;
    // Row by row, the smallest run holding both runs.
    void unite(const PixelRegion& other);
    bool operator==(const PixelRegion&) const = default;
};

// A convex region of world millimetres: the convex hull of its corners.
using ConvexCorners = std::vector<glm::dvec3>;

// What of the clip meshes an exact image depends on: per mesh, its pose and, in its pose's local frame (they do
// not move with the pose), the two regions above as a box and a ball each; and how many times the maps were drawn.
struct ClipMeshReach {
    clip::RigidPose pose;
    glm::dvec3 clipLo, clipHi, ambientLo, ambientHi;   // the boxes
    glm::dvec3 centre;                                 // the balls' centre
    double clipRadius = 0, ambientRadius = 0;
    double ambientReachMm = 0;                         // V_AO changes within this of a point the maps call inside
    bool operator==(const ClipMeshReach&) const = default;
};

struct ClipSnapshot {
    std::uint64_t mapRenders = 0;
    bool depthBoxTests = true;
    std::vector<ClipMeshReach> meshes;
    static ClipSnapshot of(const clip::ClipMeshSet& set, double cellDiagonalMm);
};

// A ball in world millimetres.
struct WorldBall {
    glm::dvec3 centre;
    double radius = 0;
};

// Where an image of the meshes `now` can differ from one of the meshes `before` (with V_AO: `ambient`): per
// region, a box (its corners) and a ball that both hold it. An elongated mesh's regions come in pieces along its
// longest axis (a slab of its depth box, grown for V_AO, with a ball of its own), so a rod's region is not one
// ball around its whole length. None when more than poses changed (then every pixel may change); empty when
// nothing did.
struct ChangedRegion {
    ConvexCorners box;
    WorldBall ball;
    std::optional<WorldBall> wholeBall;   // a piece's: the ball holding the whole region it is a piece of
};
std::optional<std::vector<ChangedRegion>> changedRegions(const ClipSnapshot& before, const ClipSnapshot& now, bool ambient);
// Where drilling since version `since` can change an image: the world box of the bricks it changed, grown by
// `growMm` (index steps of at least the grid's smallest stretch), and a ball holding it. None when no brick changed.
std::optional<ChangedRegion> drilledRegion(const plan::RemovalVolume& removal, std::uint64_t since, double growMm);

// The pixels of `frame` whose centre ray can meet `corners`' hull, row by row; none when the hull reaches the
// eye's plane, so that its projection is not the hull of its corners' (then every pixel).
std::optional<PixelRegion> pixelsMeeting(const ConvexCorners& corners, const FrameDescription& frame);
// ... whose centre ray can meet the ball (through a pyramid around the cone of rays that meet it); none when the
// eye is in it.
std::optional<PixelRegion> pixelsMeeting(const WorldBall& ball, const FrameDescription& frame);
// ... that can meet one of the regions: per region, the pixels of its box and of its balls. None: every pixel.
std::optional<PixelRegion> pixelsMeeting(const std::vector<ChangedRegion>& regions, const FrameDescription& frame);

}  // namespace curette
