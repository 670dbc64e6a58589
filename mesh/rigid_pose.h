#pragma once
// A rigid pose of a clip mesh in world millimetres: rotation about the mesh origin, then translation.
// Moving a mesh changes only this (and so only its clipping camera's matrix, never its maps).

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace curette::clip {

struct RigidPose {
    glm::dvec3 position{0.0};
    glm::dquat orientation{1.0, 0.0, 0.0, 0.0};  // w, x, y, z; kept unit length

    glm::dmat4 matrix() const;          // local -> world
    glm::dmat4 inverseMatrix() const;   // world -> local
    bool operator==(const RigidPose&) const = default;
};

// Rotation angles in degrees about x, then y, then z (fixed axes: q = Rz * Ry * Rx), as scene files give a
// mesh's "rotation_deg" and the mesh panel shows it; degreesFromOrientation inverts it (y within +-90).
glm::dquat orientationFromDegrees(glm::dvec3 xyzDeg);
glm::dvec3 degreesFromOrientation(glm::dquat orientation);

}  // namespace curette::clip
