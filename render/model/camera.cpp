#include "render/model/camera.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace curette {

glm::dvec3 OrbitCamera::forward() const {
    double az = glm::radians(azimuthDeg), el = glm::radians(std::clamp(elevationDeg, -89.9, 89.9));
    glm::dvec3 towardsCamera(std::cos(el) * std::sin(az), std::cos(el) * std::cos(az), std::sin(el));
    return -towardsCamera;
}

glm::dvec3 OrbitCamera::position() const { return target - forward() * distanceMm; }

namespace {

// The axes of the unrolled camera: right horizontal, up in the vertical plane through forward.
glm::dvec3 unrolledRight(const OrbitCamera& c) { return glm::normalize(glm::cross(c.forward(), glm::dvec3(0, 0, 1))); }

}  // namespace

glm::dvec3 OrbitCamera::right() const {
    glm::dvec3 r = unrolledRight(*this);
    if (rollDeg == 0.0) return r;
    glm::dvec3 u = glm::cross(r, forward());
    double a = glm::radians(rollDeg);
    return std::cos(a) * r - std::sin(a) * u;
}

glm::dvec3 OrbitCamera::up() const {
    glm::dvec3 r = unrolledRight(*this);
    glm::dvec3 u = glm::cross(r, forward());
    if (rollDeg == 0.0) return u;
    double a = glm::radians(rollDeg);
    return std::sin(a) * r + std::cos(a) * u;
}

glm::dmat4 OrbitCamera::view() const { return glm::lookAt(position(), target, up()); }

glm::dmat4 OrbitCamera::projection(double aspect) const {
    return glm::perspective(glm::radians(fovYDeg), aspect, nearMm, farMm);
}

glm::dmat4 OrbitCamera::viewProjection(glm::ivec2 sizePx) const {
    return projection(double(sizePx.x) / sizePx.y) * view();
}

double OrbitCamera::pixelsPerMmAtUnitDepth(int heightPx) const { return heightPx / (2.0 * std::tan(glm::radians(fovYDeg) / 2.0)); }

void OrbitCamera::fit(glm::dvec3 center, double radiusMm) {
    target = center;
    distanceMm = 1.05 * radiusMm / std::sin(glm::radians(fovYDeg) / 2.0);
    nearMm = std::max(0.1, distanceMm - 4.0 * radiusMm);
    farMm = distanceMm + 4.0 * radiusMm;
}

OrbitCamera OrbitCamera::movedRight(double mm) const {
    OrbitCamera moved = *this;
    moved.target += mm * right();
    return moved;
}

void OrbitCamera::orbit(double dAz, double dEl) {
    azimuthDeg = std::fmod(azimuthDeg + dAz, 360.0);
    elevationDeg = std::clamp(elevationDeg + dEl, -89.0, 89.0);
}

void OrbitCamera::zoom(double factor) {
    double d = std::clamp(distanceMm * factor, 1.0, 1e5);
    nearMm *= d / distanceMm;
    farMm *= d / distanceMm;
    distanceMm = d;
}

const char* standardViewName(StandardView view) {
    static const char* const names[] = {"anterior", "posterior", "left", "right", "superior", "inferior"};
    return names[static_cast<int>(view)];
}

OrbitCamera viewedFrom(OrbitCamera camera, StandardView view) {
    // Azimuth 0 puts the camera at +A (forward()); from above the camera stands anterior of the pole (azimuth
    // 180) so anterior is up and the patient's right is on the right, from below the other way round.
    struct Angles {
        double azimuth, elevation;
    };
    static const Angles angles[] = {{0, 0}, {180, 0}, {-90, 0}, {90, 0}, {180, 89}, {0, -89}};
    camera.azimuthDeg = angles[static_cast<int>(view)].azimuth;
    camera.elevationDeg = angles[static_cast<int>(view)].elevation;
    return camera;
}

}  // namespace curette
