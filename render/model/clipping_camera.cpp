#include "render/model/clipping_camera.h"

#include <algorithm>

namespace curette::clip {

glm::dmat4 ClippingCamera::localToMap() const {
    glm::dmat4 m(1.0);
    m[0][0] = 1.0 / mapSizeMm;
    m[1][1] = 1.0 / mapSizeMm;
    m[3] = glm::dvec4(-mapOrigin.x / mapSizeMm, -mapOrigin.y / mapSizeMm, 0.0, 1.0);
    return m;
}

glm::dmat4 ClippingCamera::localToClip() const {
    // x, y: depth square [0,1] -> clip [-1,1]; z: [zmin, zmax] (bounds plus margin) -> [-1, 1], nearer = smaller z.
    double zmin = localMin.z - marginMm - 1.0, zmax = localMax.z + marginMm + 1.0;
    glm::dmat4 toDepthSquare(1.0);
    toDepthSquare[0][0] = 1.0 / depthSizeMm;
    toDepthSquare[1][1] = 1.0 / depthSizeMm;
    toDepthSquare[3] = glm::dvec4(-depthOrigin.x / depthSizeMm, -depthOrigin.y / depthSizeMm, 0.0, 1.0);
    glm::dmat4 toClip(1.0);
    toClip[0][0] = 2.0, toClip[1][1] = 2.0, toClip[2][2] = 2.0 / (zmax - zmin);
    toClip[3] = glm::dvec4(-1.0, -1.0, -1.0 - 2.0 * zmin / (zmax - zmin), 1.0);
    return toClip * toDepthSquare;
}

ClippingCamera fitClippingCamera(glm::dvec3 localMin, glm::dvec3 localMax, double dilationRadiusMm, int resolution,
                                 int depthResolution) {
    ClippingCamera c;
    c.localMin = localMin;
    c.localMax = localMax;
    c.resolution = resolution;
    double extent = std::max(localMax.x - localMin.x, localMax.y - localMin.y);
    // The dilation kernel reaches R + sqrt(2) pixels (+ a rounding epsilon); leave one more pixel spare so no
    // dilated value ever needs a pixel outside the map. Solve for the pixel size with 8 pixels of slack:
    // px0 = (extent + 2R) / (res - 8), margin = R + 3 px0 gives px = (extent + 2 margin) / res < px0.
    double estimate = (extent + 2.0 * dilationRadiusMm) / std::max(resolution - 8, 1);
    c.marginMm = dilationRadiusMm + 3.0 * estimate;
    c.mapSizeMm = extent + 2.0 * c.marginMm;
    glm::dvec2 centre = 0.5 * (glm::dvec2(localMin) + glm::dvec2(localMax));
    c.mapOrigin = centre - 0.5 * c.mapSizeMm;
    // The depth square: the bounds and two depth pixels on each side, so every pixel a face covers lies in it;
    // it lies inside the map square (whose margin is at least three of its pixels).
    c.depthResolution = depthResolution;
    c.depthSizeMm = std::min(extent * depthResolution / std::max(depthResolution - 4, 1), c.mapSizeMm);
    c.depthOrigin = centre - 0.5 * c.depthSizeMm;
    return c;
}

}  // namespace curette::clip
