#include "mesh/rigid_pose.h"

#include <algorithm>
#include <cmath>

namespace curette::clip {

glm::dmat4 RigidPose::matrix() const {
    glm::dmat4 m = glm::mat4_cast(glm::normalize(orientation));
    m[3] = glm::dvec4(position, 1.0);
    return m;
}

glm::dmat4 RigidPose::inverseMatrix() const {
    glm::dmat3 r = glm::transpose(glm::dmat3(glm::mat4_cast(glm::normalize(orientation))));
    glm::dmat4 m(r);
    m[3] = glm::dvec4(-(r * position), 1.0);
    return m;
}

glm::dquat orientationFromDegrees(glm::dvec3 xyzDeg) {
    glm::dvec3 a = glm::radians(xyzDeg);
    return glm::angleAxis(a.z, glm::dvec3(0, 0, 1)) * glm::angleAxis(a.y, glm::dvec3(0, 1, 0)) * glm::angleAxis(a.x, glm::dvec3(1, 0, 0));
}

glm::dvec3 degreesFromOrientation(glm::dquat orientation) {
    glm::dmat3 m = glm::mat3_cast(glm::normalize(orientation));   // m[column][row]
    double y = std::asin(std::clamp(-m[0][2], -1.0, 1.0));
    double x = std::atan2(m[1][2], m[2][2]), z = std::atan2(m[0][1], m[0][0]);
    return glm::degrees(glm::dvec3(x, y, z));
}

}  // namespace curette::clip
