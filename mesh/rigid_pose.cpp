#include "mesh/rigid_pose.h"

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

}  // namespace curette::clip
