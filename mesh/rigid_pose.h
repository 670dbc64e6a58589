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

}  // namespace curette::clip
