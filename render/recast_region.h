#pragma once
// Which pixels an exact frame casts again when, since the last exact image, only clip meshes have moved
// (docs/architecture.md, "Pixels an exact frame casts again"). A pixel is its ray's alone (shaders/raycast.comp:
// the same camera, volume, TF, settings and jitter give the same samples), so where the ray meets nothing that
// changed it is the last image's pixel bit for bit. A rigid motion of mesh i changes, along a ray:
//  - its clip tests, only inside the box where its depth maps can call a point inside: the depth box
//    (clip::ClipMeshSet::depthBoxLocal), where the ray caster tests it at all (clip_test.glsl rayClipSpan); the
//    map box without the depth-box tests (a lookup outside it answers "outside" at any pose);
//  - V_AO (lao, cao): V_AO = LAO(V_o) at every voxel (the exactness contract), a clip sample of voxel u lies
//    within a cell diagonal of u, and LAO(v) reads V_o within the reach plus a cell diagonal of v, so the
//    motion changes V_AO only within R (AmbientOcclusion::dilationRadiusMm) of a point the mesh's maps call
//    inside, at its old pose or its new one: inside its dilated box (clip::ClipMeshSet::dilatedBoxLocal); a
//    sample reads V_AO within a cell diagonal of itself, so the box grown by one.
// Both boxes are taken at the old pose and the new one; the pixels are those whose centre ray the projection of
// some box covers. Anything else that changed (camera, size, mode, settings, volume, TF, LAO settings, the
// meshes' geometry, scale, number or maps, tubes in the frame) casts every pixel.

#include "clip/clip_mesh_set.h"
#include "render/frame.h"

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

namespace curette {

// Pixels [min, max) of an image (x right, y down: row 0 is the top of the picture).
struct PixelRect {
    glm::ivec2 min{0}, max{0};
    bool empty() const { return max.x <= min.x || max.y <= min.y; }
    std::int64_t area() const { return empty() ? 0 : std::int64_t(max.x - min.x) * (max.y - min.y); }
    PixelRect clampedTo(glm::ivec2 size) const { return {glm::clamp(min, glm::ivec2(0), size), glm::clamp(max, glm::ivec2(0), size)}; }
    // The smallest rectangle holding both.
    PixelRect unitedWith(const PixelRect& other) const;
    bool operator==(const PixelRect&) const = default;
};

// What of the clip meshes an exact image depends on: per mesh, its pose and the two boxes above in its pose's
// local frame (they do not move with the pose), and how many times the maps were drawn.
struct ClipMeshReach {
    clip::RigidPose pose;
    glm::dvec3 clipLo, clipHi;         // its clip tests: the depth box, or the map box without depth-box tests
    glm::dvec3 ambientLo, ambientHi;   // its reach into V_AO: the dilated box grown by a cell diagonal
    bool operator==(const ClipMeshReach&) const = default;
};

struct ClipSnapshot {
    std::uint64_t mapRenders = 0;
    bool depthBoxTests = true;
    std::vector<ClipMeshReach> meshes;
    static ClipSnapshot of(const clip::ClipMeshSet& set, double cellDiagonalMm);
};

// A box in world millimetres: its eight corners.
using WorldCorners = std::array<glm::dvec3, 8>;

// The world boxes within which an image of the meshes `now` can differ from one of the meshes `before` (with
// V_AO: `ambient`); none when more than poses changed (then every pixel may change).
std::optional<std::vector<WorldCorners>> changedBoxes(const ClipSnapshot& before, const ClipSnapshot& now, bool ambient);

// The pixels of `frame` whose centre ray can meet one of `boxes` (empty when none); none when a box reaches the
// camera's near plane, so that its projection is not bounded by its corners' (then every pixel).
std::optional<PixelRect> pixelsMeeting(const std::vector<WorldCorners>& boxes, const FrameDescription& frame);

}  // namespace curette
