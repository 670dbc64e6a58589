#pragma once
// The point a click in the 3-D view lands on: 3D Slicer's "first visible surface" rule, the first point along
// the pixel's ray where the accumulated opacity reaches 0.5. The ray is the image's own (cameraRay), sampled
// and classified by the CPU twin of the ray cast (raycastPixel: same lattice, trilinear samples, the TF's
// opacity and gradient opacity, opacity correction), with carved tissue transparent (the clip test given).
// It lives beside the twin so there is one definition of what a pixel shows; the label overlay and tubes are
// not part of it (a click on a shown label lands on the tissue under it).

#include "base/transfer_function.h"
#include "base/volume.h"
#include "plan/removal_field.h"
#include "render/model/frame.h"

#include <glm/glm.hpp>

#include <optional>

namespace curette::reference {

// The world point (RAS mm) of the first visible surface under `pixel` (row 0 at the top) of `frame`'s image,
// or nothing when the ray's opacity never reaches 0.5. `stepMm` is the renderer's resolved step; `carved`
// (may be empty) says which world points the clip meshes remove. The surface lies between the lattice
// sample where the opacity first reaches 0.5 and the sample before it; the point returned is their midpoint,
// within half a step of the crossing.
std::optional<glm::dvec3> pickFirstVisible(const VolumeData& volume, const TransferFunction& tf, const FrameDescription& frame,
                                           double stepMm, glm::ivec2 pixel, const plan::InsideTest& carved);

}  // namespace curette::reference
