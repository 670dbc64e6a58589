#include "render/reference/surface_pick.h"

#include "render/reference/camera_ray.h"
#include "render/reference/raycast_reference.h"

#include <algorithm>

namespace curette::reference {

std::optional<glm::dvec3> pickFirstVisible(const VolumeData& volume, const TransferFunction& tf, const FrameDescription& frame,
                                           double stepMm, glm::ivec2 pixel, const plan::InsideTest& carved) {
    RaycastOptions options;
    if (carved) options.clipped = carved;
    FrameDescription opaque = frame;
    // The ray must reach 0.5 before it may stop early; the shading only colours (the opacity reads the
    // gradient through the TF's gradient opacity whatever the mode), so solid skips the lighting.
    opaque.shading = ShadingMode::Solid;
    opaque.raycast.earlyTerminationAlpha = std::max(frame.raycast.earlyTerminationAlpha, 0.5);
    RaycastResult result = raycastPixel(volume, tf, opaque, stepMm, pixel, options);
    if (result.halfOpacityDistanceMm < 0) return std::nullopt;
    const CameraRay ray = cameraRay(frame, pixel);
    return ray.origin + (result.halfOpacityDistanceMm - 0.5 * stepMm) * ray.direction;
}

}  // namespace curette::reference
