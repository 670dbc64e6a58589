#include "viewer/orientation_marker.h"

#include <algorithm>

namespace curette {

std::array<MarkerAxis, 6> orientationMarker(const OrbitCamera& camera) {
    const glm::dvec3 right = camera.right(), up = camera.up(), towards = -camera.forward();
    std::array<MarkerAxis, 6> axes{{{'R', {1, 0, 0}, {}, 0}, {'L', {-1, 0, 0}, {}, 0}, {'A', {0, 1, 0}, {}, 0},
                                    {'P', {0, -1, 0}, {}, 0}, {'S', {0, 0, 1}, {}, 0}, {'I', {0, 0, -1}, {}, 0}}};
    for (MarkerAxis& a : axes) {
        a.screen = {glm::dot(a.direction, right), -glm::dot(a.direction, up)};
        a.depth = glm::dot(a.direction, towards);
    }
    std::stable_sort(axes.begin(), axes.end(), [](const MarkerAxis& a, const MarkerAxis& b) { return a.depth < b.depth; });
    return axes;
}

}  // namespace curette
