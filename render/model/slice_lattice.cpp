#include "render/model/slice_lattice.h"

#include <algorithm>
#include <cmath>

namespace curette {

SliceLattice sliceLattice(const VolumeGeometry& g, const OrbitCamera& camera, double d) {
    glm::dvec3 eye = camera.position(), forward = camera.forward();
    double zMin = 1e300, zMax = -1e300;
    for (const glm::dvec3& c : g.worldCorners()) {
        double z = glm::dot(c - eye, forward);
        zMin = std::min(zMin, z), zMax = std::max(zMax, z);
    }
    zMin = std::max(zMin, camera.nearMm);
    SliceLattice lattice;
    lattice.distanceMm = d;
    lattice.first = static_cast<long>(std::ceil(zMin / d));
    lattice.last = static_cast<long>(std::floor(zMax / d));
    if (lattice.count() > kMaxSlabSlices) {
        lattice.distanceMm = (zMax - zMin) / static_cast<double>(kMaxSlabSlices - 1);
        lattice.first = static_cast<long>(std::ceil(zMin / lattice.distanceMm));
        lattice.last = static_cast<long>(std::floor(zMax / lattice.distanceMm));
        lattice.widened = true;
    }
    return lattice;
}

}  // namespace curette
