#pragma once
// CPU reference of the directional occlusion shading model (seed 001, eq. 7-10 with the cone phase function
// of eq. 6 and Fig. 2 b): for each sample along a pixel's ray, the fraction of ambient light V(x) reaching it
// is the average transmittance from x to the volume's boundary over directions uniformly distributed in the
// cone of half-angle theta around the direction towards the eye, estimated with stratified (spherical
// Fibonacci) directions. The primary ray uses the slab pass's sample positions and segment lengths, so
// the difference to the GPU is the slab pass's approximation of V (blur of the previous slice's buffer).

#include "render/model/frame.h"
#include "render/reference/lao_reference.h"
#include "base/transfer_function.h"
#include "base/volume.h"

namespace curette::reference {

struct DosReferenceSettings {
    int directions = 128;          // cone directions per sample
    double marchStepMm = 0.0;      // step along each cone direction; 0: the slice distance
    bool occlusion = true;         // false: V = 1 (emission-absorption at the same samples), the baseline
                                   // that shows how large the occlusion effect is
};

// The pixel's premultiplied RGBA. `inside` clips (may be empty). sliceDistanceMm must be resolved.
glm::dvec4 dosPixel(const VolumeData& volume, const TransferFunction& tf, const FrameDescription& frame,
                    double sliceDistanceMm, glm::ivec2 pixel, const DosReferenceSettings& settings, const InsideTest& inside);

}  // namespace curette::reference
