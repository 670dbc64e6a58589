#pragma once
// The orientation marker in a corner of the 3-D view (3D Slicer's: the patient axes, labelled): the six
// half-axes R/L, A/P, S/I as the camera sees them, so a planner always knows which side is which.

#include "render/model/camera.h"

#include <array>

namespace curette {

struct MarkerAxis {
    char label;            // 'R', 'L', 'A', 'P', 'S', 'I'
    glm::dvec3 direction;  // RAS unit vector of the half-axis
    glm::dvec2 screen;     // its end on screen, a unit-length axis seen from the camera: x right, y down (pixels / radius)
    double depth;          // towards the camera positive: drawn last, on top
};

// The six half-axes for `camera`, back to front (draw in this order). An orthographic projection of the
// camera's rotation: a marker shows directions, not perspective.
std::array<MarkerAxis, 6> orientationMarker(const OrbitCamera& camera);

}  // namespace curette
