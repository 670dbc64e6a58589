#pragma once
// Where the ray caster shades phong's visible samples (shaders/raycast.comp). llvmpipe runs every line of the
// sample loop on every step, taken or not, so phong's six gradient fetches inside the loop cost every step.
// Between rounds of the loop (a round stops at a visible sample, which is shaded after it) they cost only the
// visible samples, but each stop costs the lanes that wait for the round to end. Rounds pay when a ray's
// visible samples are few against its steps: tissue opaque enough that a ray ends a short way into it (the
// head's TF). With a glass TF a ray crosses the whole head and nearly every step is visible: the loop pays.
// Both places take the same samples and give the same image; this only picks the faster program.

#include "base/transfer_function.h"
#include "base/value_histogram.h"

#include <cstddef>

namespace curette {

enum class PhongShading { BetweenRounds, InLoop };
const char* phongShadingName(PhongShading placement);

// The histogram phong's placement reads: a million voxels are enough for a median.
constexpr int kPlacementHistogramBins = 1024;
constexpr std::size_t kPlacementHistogramVoxels = std::size_t{1} << 20;

// The median over the volume's visible voxels (the TF's opacity above 0) of the TF's extinction per mm,
// -ln(1 - opacity) / unitLengthMm; 0 when no voxel is visible.
double medianVisibleExtinctionPerMm(const ValueHistogram& histogram, const TransferFunction& tf);

// Between rounds when a ray through tissue of that median extinction reaches `earlyTerminationAlpha` within
// half the volume's mean extent (the mean of its sides in mm); otherwise in the loop. The head's TF ends a ray
// 0.1 of the head's mean extent into tissue, the glass TF 1.4 (docs/measurements.md): half lies between.
PhongShading phongShadingPlacement(double medianExtinctionPerMm, double earlyTerminationAlpha, double meanExtentMm);

}  // namespace curette
