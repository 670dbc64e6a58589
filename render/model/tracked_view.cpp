#include "render/model/tracked_view.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace curette {

glm::dvec3 RoomAnchor::roomDirectionToWorld(glm::dvec3 d) {
    // Room (x right, y up, z towards the user) to RAS: R = -x, A = z, S = y (a proper rotation).
    return {-d.x, d.z, d.y};
}

glm::dquat RoomAnchor::roomOrientationToWorld(glm::dquat orientation) {
    // M R M^T with M the room-to-RAS rotation above (its columns: where room x, y, z go).
    const glm::dmat3 m(glm::dvec3(-1, 0, 0), glm::dvec3(0, 0, 1), glm::dvec3(0, 1, 0));
    return glm::normalize(glm::quat_cast(m * glm::mat3_cast(orientation) * glm::transpose(m)));
}

glm::dvec3 RoomAnchor::directionToWorld(glm::dvec3 d) const {
    // Undo the volume's turn in the room, then the fixed axes. Unturned: the axes alone, so an unmoved
    // volume's eyes and grips keep every bit (a rotation by the identity may flip a zero's sign).
    if (volumeTurnRoom == glm::dquat(1.0, 0.0, 0.0, 0.0)) return roomDirectionToWorld(d);
    return roomDirectionToWorld(glm::conjugate(volumeTurnRoom) * d);
}

glm::dquat RoomAnchor::orientationToWorld(glm::dquat orientation) const {
    if (volumeTurnRoom == glm::dquat(1.0, 0.0, 0.0, 0.0)) return roomOrientationToWorld(orientation);
    return roomOrientationToWorld(glm::conjugate(volumeTurnRoom) * orientation);
}

glm::dvec3 RoomAnchor::roomToWorldMm(glm::dvec3 roomM) const {
    return volumeCentreWorldMm + (1000.0 / volumeScale) * directionToWorld(roomM - volumeCentreRoomM);
}

RoomAnchor RoomAnchor::carried(const TrackedView& before, const TrackedView& after) const {
    // The grip's motion in the room, applied to the volume: turn about where the grip was, then move with it.
    glm::dquat turn = after.orientation * glm::conjugate(before.orientation);
    RoomAnchor a = *this;
    a.volumeCentreRoomM = turn * (volumeCentreRoomM - before.positionM) + after.positionM;
    a.volumeTurnRoom = glm::normalize(turn * volumeTurnRoom);
    return a;
}

RoomAnchor RoomAnchor::heldByTwo(glm::dvec3 leftBefore, glm::dvec3 rightBefore, glm::dvec3 leftAfter, glm::dvec3 rightAfter) const {
    const glm::dvec3 before = rightBefore - leftBefore, after = rightAfter - leftAfter;
    const double lengthBefore = glm::length(before), lengthAfter = glm::length(after);
    if (!(lengthBefore > kTwoHandMinimumM) || !(lengthAfter > kTwoHandMinimumM)) return *this;   // hands together: no scale to read
    // The shortest turn from one direction to the other: q = (1 + a.b, a x b), normalised; opposite directions
    // (a hand passed through the other) take a half turn about an axis across them.
    const glm::dvec3 a = before / lengthBefore, b = after / lengthAfter;
    glm::dquat turn(1.0 + glm::dot(a, b), glm::cross(a, b));
    if (turn.w < 1e-9) {
        const glm::dvec3 across = std::abs(a.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
        turn = glm::dquat(0.0, glm::normalize(glm::cross(a, across)));
    }
    turn = glm::normalize(turn);
    const double ratio = lengthAfter / lengthBefore;
    const glm::dvec3 midBefore = 0.5 * (leftBefore + rightBefore), midAfter = 0.5 * (leftAfter + rightAfter);
    RoomAnchor held = *this;
    held.volumeCentreRoomM = midAfter + ratio * (turn * (volumeCentreRoomM - midBefore));
    held.volumeTurnRoom = glm::normalize(turn * volumeTurnRoom);
    held.volumeScale = volumeScale * ratio;
    return held;
}

RoomAnchor tableAnchor(const VolumeGeometry& geometry, RoomSpace space) {
    RoomAnchor a;
    a.volumeCentreWorldMm = geometry.worldCenter();
    double lowestS = a.volumeCentreWorldMm.z;
    for (const glm::dvec3& corner : geometry.worldCorners()) lowestS = std::min(lowestS, corner.z);
    double centreHeightM = kTableHeightM + (a.volumeCentreWorldMm.z - lowestS) / 1000.0;
    if (space == RoomSpace::Local) centreHeightM -= kStandingEyeHeightM;
    a.volumeCentreRoomM = glm::dvec3(0.0, centreHeightM, -kTableDistanceM);
    return a;
}

TrackedEye trackedEye(const FrameDescription& base, const TrackedView& view, const RoomAnchor& anchor, glm::ivec2 recommendedSize) {
    const FieldOfView& f = view.fov;
    const double tanL = std::tan(f.angleLeft), tanR = std::tan(f.angleRight), tanU = std::tan(f.angleUp), tanD = std::tan(f.angleDown);
    if (!(tanR > tanL && tanU > tanD) || recommendedSize.x < 1 || recommendedSize.y < 1)
        throw std::invalid_argument("eyeView: an empty field of view or image");
    // The pitch that fits the whole field of view into the recommended image, then the edges inwards to whole
    // pixels; an edge within kSnap of a whole pixel is on it (the angles came through float).
    constexpr double kSnap = 1e-4;
    const double pitch = std::max((tanR - tanL) / recommendedSize.x, (tanU - tanD) / recommendedSize.y);
    const int left = static_cast<int>(std::ceil(tanL / pitch - kSnap)), right = static_cast<int>(std::floor(tanR / pitch + kSnap));
    const int up = static_cast<int>(std::floor(tanU / pitch + kSnap)), down = static_cast<int>(std::ceil(tanD / pitch - kSnap));
    const int halfWidth = std::max({std::abs(left), std::abs(right), 1}), halfHeight = std::max({std::abs(up), std::abs(down), 1});

    TrackedEye eye;
    eye.size = {std::max(1, right - left), std::max(1, up - down)};
    eye.cropOrigin = {halfWidth + left, halfHeight - up};
    eye.renderedFov = {std::atan(left * pitch), std::atan(right * pitch), std::atan(up * pitch), std::atan(down * pitch)};

    // The eye's axes in the room (OpenXR views look along -z, up +y), then in RAS.
    const glm::dvec3 forward = glm::normalize(anchor.directionToWorld(view.orientation * glm::dvec3(0, 0, -1)));
    const glm::dvec3 upAxis = glm::normalize(anchor.directionToWorld(view.orientation * glm::dvec3(0, 1, 0)));
    const glm::dvec3 position = anchor.roomToWorldMm(view.positionM);

    eye.frame = base;
    OrbitCamera& c = eye.frame.camera;
    c.elevationDeg = glm::degrees(std::asin(std::clamp(-forward.z, -1.0, 1.0)));
    c.azimuthDeg = glm::degrees(std::atan2(-forward.x, -forward.y));
    c.rollDeg = 0.0;
    c.distanceMm = std::max(1.0, glm::dot(anchor.volumeCentreWorldMm - position, forward));
    c.target = position + c.distanceMm * forward;
    // The roll that turns the unrolled up (camera.h) onto the eye's up.
    const glm::dvec3 r = c.right(), u = c.up();
    c.rollDeg = glm::degrees(std::atan2(glm::dot(upAxis, r), glm::dot(upAxis, u)));
    c.fovYDeg = glm::degrees(2.0 * std::atan(halfHeight * pitch));
    c.nearMm = 20.0 / anchor.volumeScale;   // a head-mounted display's near plane (2 cm of the room): the volume may come close to the eyes
    c.farMm = 10000.0;
    eye.frame.size = {2 * halfWidth, 2 * halfHeight};
    return eye;
}

}  // namespace curette
