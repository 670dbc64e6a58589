#include "session/scene_slices.h"

#include <limits>

namespace curette {

SliceOverlays sceneSliceOverlays(const LoadedScene& loaded, const InteractionState& state,
                                 const std::vector<std::uint8_t>* removedRegion, int heldMesh) {
    SliceOverlays overlays;
    overlays.removedRegion = removedRegion;
    for (const LoadedLabelSet& set : loaded.labels)
        overlays.labelSets.push_back(sliceLabelSet(set.onScanGrid, set.table, set.shown, set.protectedIds));
    for (std::size_t i = 0; i < state.meshes.size(); ++i) {
        const MeshState& m = state.meshes[i];
        overlays.meshes.push_back({plan::PosedMesh{m.geometry, m.pose, m.scale}, static_cast<int>(i) == heldMesh});
    }
    return overlays;
}

glm::dvec3 defaultCrosshair(const VolumeData& volume, const InteractionState& state) {
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    auto add = [&](glm::dvec3 p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    };
    for (const MeshState& m : state.meshes) {
        if (!m.geometry) continue;
        const glm::dmat4 toWorld = m.pose.matrix();
        for (const glm::vec3& p : m.geometry->positions) add(glm::dvec3(toWorld * glm::dvec4(m.scale * glm::dvec3(p), 1.0)));
    }
    if (hi.x >= lo.x) return 0.5 * (lo + hi);
    for (int c = 0; c < 8; ++c) {
        glm::dvec3 index(c & 1 ? volume.dims.x - 0.5 : -0.5, c & 2 ? volume.dims.y - 0.5 : -0.5, c & 4 ? volume.dims.z - 0.5 : -0.5);
        add(glm::dvec3(volume.indexToWorld * glm::dvec4(index, 1.0)));
    }
    return 0.5 * (lo + hi);
}

}  // namespace curette
