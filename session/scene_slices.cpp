#include "session/scene_slices.h"

#include "render/model/volume_geometry.h"

#include <limits>

namespace curette {

SliceOverlays sceneSliceOverlays(const LoadedScene& loaded, const InteractionState& state,
                                 const std::vector<std::uint8_t>* removedRegion, int heldMesh) {
    SliceOverlays overlays;
    overlays.removedRegion = removedRegion;
    for (const LoadedLabelSet& set : loaded.labels)
        overlays.labelSets.push_back(sliceLabelSet(set.onScanGrid, set.table, set.shown, set.protectedIds));
    std::vector<plan::PosedMesh> posed = state.posedMeshes();
    for (std::size_t i = 0; i < posed.size(); ++i) overlays.meshes.push_back({posed[i], static_cast<int>(i) == heldMesh});
    return overlays;
}

glm::dvec3 defaultCrosshair(const VolumeData& volume, const InteractionState& state) {
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    auto add = [&](glm::dvec3 p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    };
    for (const plan::PosedMesh& m : state.posedMeshes())
        for (const glm::dvec3& p : m.worldVertices()) add(p);
    if (hi.x >= lo.x) return 0.5 * (lo + hi);
    for (const glm::dvec3& corner : VolumeGeometry{volume.dims, volume.indexToWorld}.worldCorners()) add(corner);
    return 0.5 * (lo + hi);
}

}  // namespace curette
