#pragma once
// A head-mounted display's eye as curette renders it (`view --xr`, `render --xr-views`). GL-free.
//
// The runtime locates each eye in its room space (OpenXR's XrView: a pose in metres, +y up, the user looking
// along -z, and an asymmetric field of view as four angles). The volume stands in that room at real size
// (1 mm of RAS is 1 mm of room) on a table-height anchor, its anterior towards the user (room +z), the
// patient's right on the user's left (room -x), superior up (room +y).
//
// The renderer draws symmetric frusta only (render/model/stereo.h), so an eye's asymmetric frustum is taken,
// as the monitor's off-axis pair takes it, as a crop of a wider symmetric one rendered from the eye with the
// same pixel pitch: pitch p (tangent units per pixel) makes the recommended image hold the whole field of
// view, the four edges are moved inwards to whole pixels (less than a pixel; the fov actually rendered, which
// the application submits), and the symmetric frame reaches the farthest edge on each axis.

#include "render/model/frame.h"
#include "render/model/volume_geometry.h"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace curette {

// OpenXR's XrFovf: angles in radians from the view axis, left and down negative for a centred eye.
struct FieldOfView {
    double angleLeft = 0, angleRight = 0, angleUp = 0, angleDown = 0;
    bool operator==(const FieldOfView&) const = default;
};

// One located eye in the room (OpenXR's XrView in the reference space the application located it in).
struct TrackedView {
    glm::dvec3 positionM{0.0};
    glm::dquat orientation{1.0, 0.0, 0.0, 0.0};
    FieldOfView fov;
    bool operator==(const TrackedView&) const = default;
};

// The room spaces an anchor is defined for: a stage (origin on the floor) or a local space (origin at the
// user's head when the session started; taken as standing eye height above the floor).
enum class RoomSpace { Stage, Local };

// Where the volume stands in the room: a table top kTableHeightM above the floor carries the volume box's
// lowest corner, its centre kTableDistanceM in front of the space's origin (tableAnchor), the volume's axes as
// the header says. A hand moving the volume (session/xr_hands.h) carries it, turned by volumeTurnRoom, about
// the room: the scene moves rigidly in the room, nothing in world (RAS) space moves. Two hands holding it also
// scale it (volumeScale: its size in the room over its real size), again without moving anything in world space.
struct RoomAnchor {
    glm::dvec3 volumeCentreRoomM{0.0};
    glm::dvec3 volumeCentreWorldMm{0.0};
    glm::dquat volumeTurnRoom{1.0, 0.0, 0.0, 0.0};   // the volume's turn in the room since the table (identity there)
    double volumeScale = 1.0;                        // room metres per real metre (1: real size)
    glm::dvec3 roomToWorldMm(glm::dvec3 roomM) const;               // a point
    glm::dvec3 directionToWorld(glm::dvec3 roomDirection) const;    // a direction
    glm::dquat orientationToWorld(glm::dquat roomOrientation) const;   // a tracked object's (a grip's)
    // The anchor after the volume followed a grip rigidly from `before` to `after` (room poses): the grip keeps
    // its place on the anatomy.
    RoomAnchor carried(const TrackedView& before, const TrackedView& after) const;
    // The anchor after two hands holding the volume moved from (leftBefore, rightBefore) to (leftAfter,
    // rightAfter) (room positions): scaled by the ratio of the hands' distances about their midpoint, turned by
    // the shortest turn of the line between them, moved with the midpoint; each hand keeps its place on the
    // anatomy as far as a similarity can keep two points (exactly, for positions; the turn about the line
    // between the hands is left as it was).
    RoomAnchor heldByTwo(glm::dvec3 leftBefore, glm::dvec3 rightBefore, glm::dvec3 leftAfter, glm::dvec3 rightAfter) const;
    // The fixed axes: room (x right, y up, z towards the user) to RAS, the volume unturned.
    static glm::dvec3 roomDirectionToWorld(glm::dvec3 direction);
    static glm::dquat roomOrientationToWorld(glm::dquat orientation);
    bool operator==(const RoomAnchor&) const = default;
};

inline constexpr double kTableHeightM = 0.9;      // an operating or standing work table
inline constexpr double kTableDistanceM = 0.5;    // within arm's reach
inline constexpr double kStandingEyeHeightM = 1.6;
inline constexpr double kTwoHandMinimumM = 0.01;   // hands closer than this give no scale (RoomAnchor::heldByTwo)

RoomAnchor tableAnchor(const VolumeGeometry& geometry, RoomSpace space);

// An eye as rendered: `frame` (symmetric, from the eye's pose) and the rectangle of its image the eye keeps
// (origin from the top left, size), with the field of view those pixels span.
struct TrackedEye {
    FrameDescription frame;
    glm::ivec2 cropOrigin{0};
    glm::ivec2 size{0};
    FieldOfView renderedFov;
};

// The eye `view` of the scene frame `base` (its shading, settings and lights; camera and size replaced),
// its image at most `recommendedSize` pixels.
TrackedEye trackedEye(const FrameDescription& base, const TrackedView& view, const RoomAnchor& anchor, glm::ivec2 recommendedSize);

}  // namespace curette
