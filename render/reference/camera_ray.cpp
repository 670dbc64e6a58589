#include "render/reference/camera_ray.h"

namespace curette::reference {

CameraRay cameraRay(const FrameDescription& frame, glm::ivec2 pixel) {
    glm::dmat4 inverseViewProjection = glm::inverse(frame.camera.viewProjection(frame.size));
    glm::dvec2 ndc = (glm::dvec2(pixel) + 0.5) / glm::dvec2(frame.size) * 2.0 - 1.0;
    ndc.y = -ndc.y;
    glm::dvec4 farPoint = inverseViewProjection * glm::dvec4(ndc, 1.0, 1.0);
    glm::dvec3 eye = frame.camera.position();
    return {eye, glm::normalize(glm::dvec3(farPoint) / farPoint.w - eye)};
}

}  // namespace curette::reference
