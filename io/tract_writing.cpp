#include "io/tract_writing.h"

#include "base/error.h"

#include <algorithm>
#include <cmath>

namespace curette::io {

void requireWritableTractogram(const std::string& source, const Tractogram& tracts) {
    if (tracts.offsets.empty() || tracts.offsets.front() != 0 || tracts.offsets.back() != tracts.points.size() ||
        !std::is_sorted(tracts.offsets.begin(), tracts.offsets.end()))
        throw InputError(source, "offsets", "increasing streamline offsets from 0 to the point count " + std::to_string(tracts.points.size()));
    for (std::size_t p = 0; p < tracts.points.size(); ++p) {
        const glm::vec3& v = tracts.points[p];
        if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
            throw InputError(source, "points[" + std::to_string(p) + "]", "finite coordinates", "NaN or Inf");
    }
}

glm::dmat4 TractReferenceGrid::voxelToRas() const {
    glm::dmat4 m(voxelSize);
    m[3] = glm::dvec4(origin, 1.0);
    return m;
}

TractReferenceGrid tractReferenceGrid(const Tractogram& tracts) {
    TractReferenceGrid grid;
    if (tracts.points.empty()) return grid;
    glm::dvec3 lo(tracts.points.front()), hi(tracts.points.front());
    for (const glm::vec3& p : tracts.points) lo = glm::min(lo, glm::dvec3(p)), hi = glm::max(hi, glm::dvec3(p));
    // .trk stores dims as int16: keep each below 32767 voxels, the span plus the spare voxels and rounding.
    constexpr double kMaxVoxels = 32000.0;
    double span = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
    grid.voxelSize = std::max(1.0, std::ceil(span / kMaxVoxels));
    double s = grid.voxelSize;
    glm::dvec3 first = glm::floor(lo / s) - 1.0, last = glm::ceil(hi / s) + 1.0;
    grid.origin = first * s;
    grid.dims = glm::ivec3(last - first) + 1;
    return grid;
}

}  // namespace curette::io
