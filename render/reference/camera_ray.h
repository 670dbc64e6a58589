#pragma once
// The CPU twin of shaders/pixel_ray.glsl: the camera ray through a pixel centre (row 0 at the top), one
// definition for every CPU reference (ray casting, DOS, ISMOS).

#include "render/model/frame.h"

#include <glm/glm.hpp>

namespace curette::reference {

struct CameraRay {
    glm::dvec3 origin;      // the eye, world mm
    glm::dvec3 direction;   // unit, world
};

CameraRay cameraRay(const FrameDescription& frame, glm::ivec2 pixel);

}  // namespace curette::reference
