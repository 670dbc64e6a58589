#pragma once
// CPU double-precision twin of shaders/raycast.comp for single pixels: the same rays, the same sample
// lattice, trilinear sampling, the exact (unbaked) transfer function, opacity correction, Blinn-Phong and
// early termination. Tests compare the GPU image against it pixel by pixel.

#include "render/model/frame.h"
#include "base/transfer_function.h"
#include "base/volume.h"

#include <glm/glm.hpp>

#include <functional>
#include <limits>

namespace curette::reference {

struct RaycastResult {
    glm::dvec4 rgba{0.0};   // premultiplied
    int samples = 0;        // samples with non-zero opacity composited
    // Distance from the eye (mm, along the ray) of the first sample after which the accumulated opacity is at
    // least 0.5: where the pixel's surface is (render/reference/stereo_match.h); negative when it never gets there.
    double halfOpacityDistanceMm = -1.0;
};

// What the plain ray cast leaves out, for callers that need the pixel as the GPU shows it in a scene.
struct RaycastOptions {
    std::function<bool(glm::dvec3 world)> clipped;                     // samples it accepts are cut away; empty: none
    double opaqueAtMm = std::numeric_limits<double>::infinity();        // an opaque surface (a tube) ends the ray here
    // With `clipped` and frame.raycast.cutFace on: the unit normal of the clip surface at a world point on it,
    // pointing out of the clipped region (the cut-face rules need it).
    std::function<glm::dvec3(glm::dvec3 world)> clipNormal;
};

// `stepMm` must be the resolved step (Renderer::resolveStepMm).
RaycastResult raycastPixel(const VolumeData& volume, const TransferFunction& tf, const FrameDescription& frame,
                           double stepMm, glm::ivec2 pixel, const RaycastOptions& options = {});

}  // namespace curette::reference
