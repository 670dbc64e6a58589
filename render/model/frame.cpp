#include "render/model/frame.h"

namespace curette {

glm::dvec3 worldLightDirection(const Light& l, const OrbitCamera& camera) {
    glm::dvec3 d = l.cameraSpace ? l.direction.x * camera.right() + l.direction.y * camera.up() - l.direction.z * camera.forward()
                                 : l.direction;
    return glm::normalize(d);
}

}  // namespace curette
