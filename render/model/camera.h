#pragma once
// The perspective orbit camera: it circles `target` at `distanceMm`, at an azimuth around world +z
// (superior) and an elevation above the axial plane. Azimuth 0 looks at the face (camera anterior, +y),
// 90 from the right (+x). World space is RAS millimetres. A roll turns the image about the view axis: a
// head-mounted display's eye (render/model/tracked_view.h) tilts with the head; the viewer's camera has none.

#include <glm/glm.hpp>

namespace curette {

struct OrbitCamera {
    glm::dvec3 target{0.0};
    double distanceMm = 400.0;
    double azimuthDeg = 0.0;
    double elevationDeg = 0.0;
    double rollDeg = 0.0;        // positive: the image's up turns from the unrolled up towards its right
    double fovYDeg = 30.0;
    double nearMm = 1.0;
    double farMm = 10000.0;
    bool operator==(const OrbitCamera&) const = default;

    glm::dvec3 position() const;
    glm::dvec3 forward() const;  // unit vector from the camera towards the target
    glm::dvec3 up() const;       // unit vector, orthogonal to forward
    glm::dvec3 right() const;    // unit vector: forward x up
    glm::dmat4 view() const;
    glm::dmat4 projection(double aspect) const;
    // projection * view for an image of `sizePx` pixels (aspect width / height): the one matrix the passes,
    // the shaders' pixel rays and the CPU references all use, so they agree bit for bit.
    glm::dmat4 viewProjection(glm::ivec2 sizePx) const;
    // How many pixels one millimetre across the view spans at unit depth in an image `heightPx` high:
    // H / (2 tan(fovy / 2)); divide by a depth for the scale there.
    double pixelsPerMmAtUnitDepth(int heightPx) const;

    // Places the camera so a sphere of `radiusMm` around `center` fills the view with a small margin.
    void fit(glm::dvec3 center, double radiusMm);
    // The same camera moved `mm` along its right axis (negative: to the left), target and all: its view axis
    // stays parallel to this one's (an eye of an off-axis stereo pair, render/model/stereo.h).
    OrbitCamera movedRight(double mm) const;
    // Mouse-style orbit/zoom (degrees, multiplicative factor).
    void orbit(double deltaAzimuthDeg, double deltaElevationDeg);
    void zoom(double factor);
};

// The views a planner names (3D Slicer's A, P, L, R, S, I buttons): the camera on that side of its target,
// looking at it, the head upright (superior up) or, from above and below, anterior up.
enum class StandardView { Anterior, Posterior, Left, Right, Superior, Inferior, Count };
const char* standardViewName(StandardView view);
// `camera` turned to look from `view`; its target, distance and field of view stay.
OrbitCamera viewedFrom(OrbitCamera camera, StandardView view);

}  // namespace curette
