#pragma once
// How rough a cut face looks: the high-frequency energy of an image over the pixels that show the cut (issue
// "cut faces"): luma minus a small Gaussian blur of it, RMS over a mask. A smooth face scores near zero;
// speckle, dotting at the voxel pitch and wood grain at the step's pitch all raise it. CPU only.

#include "render/model/image.h"

#include <vector>

namespace curette {

// Rec. 709 luma of each pixel of `image` composited over `background` (straight RGBA), row-major.
std::vector<double> compositedLuma(const Image& image, glm::vec4 background);

// The pixels that show a carve: luma of `carved` and `uncarved` (the same view without clip meshes) differ by
// more than `threshold`, and so does every pixel within `erodePx` (a square), which keeps the rim of the cavity
// (a true edge) and the blur's reach across it out of the measure.
std::vector<bool> carvedPixels(const Image& carved, const Image& uncarved, glm::vec4 background, double threshold,
                               int erodePx);

// sqrt(mean over `mask` of (L - G_sigma * L)^2), L the composited luma, G_sigma a separable Gaussian of
// standard deviation `sigmaPx` (radius 3 sigma, clamped at the image edge). 0 for an empty mask.
double highFrequencyRms(const Image& image, glm::vec4 background, const std::vector<bool>& mask, double sigmaPx);

}  // namespace curette
