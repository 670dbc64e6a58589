#pragma once
// The slices the slab pass marches (DOS, seed 001 section 4): view-aligned planes at depths z_k = k d from the
// eye (k = first..last) covering the volume's depth range. A lattice of multiples of d, so orbiting does not
// make the slices swim through the data. The GPU pass and its CPU reference both take their planes from here.

#include "render/model/camera.h"
#include "render/model/volume_geometry.h"

namespace curette {

inline constexpr long kMaxSlabSlices = 8192;

struct SliceLattice {
    double distanceMm = 1.0;   // d; larger than asked when more than kMaxSlabSlices would be needed
    long first = 0, last = -1;
    bool widened = false;
    long count() const { return last - first + 1; }
};

SliceLattice sliceLattice(const VolumeGeometry& geometry, const OrbitCamera& camera, double distanceMm);

}  // namespace curette
