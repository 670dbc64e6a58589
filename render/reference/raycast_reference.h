#pragma once
// CPU double-precision twin of shaders/raycast.comp for single pixels: the same rays, the same sample
// lattice, trilinear sampling, the exact (unbaked) transfer function, opacity correction, Blinn-Phong and
// early termination. Tests compare the GPU image against it pixel by pixel.

#include "render/frame.h"
#include "base/transfer_function.h"
#include "base/volume.h"

#include <glm/glm.hpp>

namespace curette::reference {

struct RaycastResult {
    glm::dvec4 rgba{0.0};   // premultiplied
    int samples = 0;        // samples with non-zero opacity composited
};

// `stepMm` must be the resolved step (Renderer::resolveStepMm).
RaycastResult raycastPixel(const VolumeData& volume, const TransferFunction& tf, const FrameDescription& frame,
                           double stepMm, glm::ivec2 pixel);

}  // namespace curette::reference
