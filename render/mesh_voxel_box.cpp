#include "render/mesh_voxel_box.h"

#include <limits>

namespace curette {

plan::VoxelBox voxelBoxAroundMeshes(const VolumeGeometry& g, const clip::ClipMeshSet& clip) {
    glm::dmat4 worldToIndex = g.worldToIndex();
    double padMm = g.cellDiagonalMm() + 1.0;
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    for (int i = 0; i < clip.count(); ++i) {
        clip::ClipMeshSet::WorldBox box = clip.mapBoxWorldBounds(i);
        for (int corner = 0; corner < 8; ++corner) {
            glm::dvec3 world((corner & 1) ? box.max.x + padMm : box.min.x - padMm, (corner & 2) ? box.max.y + padMm : box.min.y - padMm,
                             (corner & 4) ? box.max.z + padMm : box.min.z - padMm);
            glm::dvec3 index(worldToIndex * glm::dvec4(world, 1.0));
            lo = glm::min(lo, index);
            hi = glm::max(hi, index);
        }
    }
    if (clip.count() == 0 || !glm::all(glm::lessThanEqual(lo, hi))) return {};
    glm::dvec3 dims(g.dims);
    glm::dvec3 first = glm::clamp(glm::floor(lo) - 2.0, glm::dvec3(0.0), dims);
    glm::dvec3 end = glm::clamp(glm::ceil(hi) + 3.0, glm::dvec3(0.0), dims);
    return {glm::ivec3(first), glm::max(glm::ivec3(end) - glm::ivec3(first), glm::ivec3(0))};
}

}  // namespace curette
