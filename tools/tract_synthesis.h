#pragma once
// Whole-brain-scale tractograms from a few bundles (issue 12): `count` jittered copies of the source
// streamlines, copy i made from source streamline i mod S (S the sources' streamline count, in the order the
// files are given), so every source bundle is represented in proportion in any prefix of the result. Each copy
// is its source moved by a smooth random displacement along the streamline (arc-length fraction u in [0, 1]):
//     d(u) = J * (0.5 a + 0.3 b cos(pi u + phi) + 0.2 c cos(2 pi u + psi)),
// a, b, c random vectors in the unit ball, phi, psi random phases, J the jitter bound, so |d(u)| <= J at
// every point (the weights sum to 1) and the copy bends gently (one half-wave and one full wave over its
// length) instead of shifting rigidly; copies of one source do not coincide (almost surely). Copy i draws its
// numbers from its own stream (SplitMix64 of the seed and i), so the first N copies of a larger synthesis are
// the N-copy synthesis, and the result is the same on every platform (no std:: distribution, whose output the
// standard leaves to the library).

#include "base/tractogram.h"

#include <cstdint>
#include <filesystem>
#include <vector>

namespace curette {

struct TractSynthesisSettings {
    std::size_t count = 100000;
    std::uint64_t seed = 1;
    double jitterMm = 3.0;   // J: no point moves further than this from its source point
};

// The streamlines of `sources`, concatenated (scalars and properties are dropped: copies keep only points).
// InputError when there is no streamline with at least one point, or the settings are out of range.
Tractogram synthesiseTracts(const std::vector<Tractogram>& sources, const TractSynthesisSettings& settings);

// The displacement of copy `copy` at arc-length fraction u (the formula above); exposed for tests.
glm::dvec3 synthesisDisplacement(std::uint64_t seed, std::size_t copy, double jitterMm, double u);

// The tract files (.trk, .tck, .trx, gzip-compressed .trk.gz/.tck.gz) under `folder`, recursively, sorted by
// path so a synthesis does not depend on directory order; a file is returned as itself.
std::vector<std::filesystem::path> tractFilesUnder(const std::filesystem::path& folderOrFile);

}  // namespace curette
