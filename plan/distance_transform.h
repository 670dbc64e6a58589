#pragma once
// Exact Euclidean distance transform on an anisotropic voxel grid, in millimetres: for every voxel, the
// distance from its centre to the nearest centre of a feature voxel. Felzenszwalb & Huttenlocher, "Distance
// Transforms of Sampled Functions" (Theory of Computing 2012): the squared distance is separable, so one 1-D
// pass per axis computes the lower envelope of parabolas (x - x_q)^2 + f(q) with x_q = q * spacing of that
// axis; O(n) per line, exact (up to rounding) for any spacing.
//
// Grids with an oblique affine: the spacing per axis is the column norm of the 3x3 part (gridSpacingMm), so
// the distances are exact only when the axes are orthogonal; our grids' columns are orthogonal or nearly so
// (scanner shear of a fraction of a degree changes distances by a fraction of a percent).

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace curette::plan {

// The length in mm of one index step along each axis: the column norms of the affine's 3x3 part.
glm::dvec3 gridSpacingMm(const glm::dmat4& indexToWorld);

// `isFeature` has dims.x * dims.y * dims.z entries, x fastest; nonzero marks a feature voxel. The result has
// the same layout: 0 on features, +infinity everywhere when there is no feature.
std::vector<double> distanceTransformMm(glm::ivec3 dims, glm::dvec3 spacingMm, const std::vector<std::uint8_t>& isFeature);

// The same as squared distances (mm^2), which is what the passes compute; saves the square roots.
std::vector<double> squaredDistanceTransformMm(glm::ivec3 dims, glm::dvec3 spacingMm, const std::vector<std::uint8_t>& isFeature);

// The 1-D pass on its own (exposed for tests): in place, f[q] := min_p (q - p)^2 spacing^2 + f[p]; entries
// of +infinity are "no parabola". `scratchV`, `scratchZ` are resized as needed.
void lowerEnvelopeOfParabolas(double* f, int n, double spacing, std::vector<int>& scratchV, std::vector<double>& scratchZ,
                              std::vector<double>& scratchOut);

}  // namespace curette::plan
