#pragma once
// A scene's slice views (render/model/slice_view.h) as `curette render --slices` and the viewer's slice
// panel both make them: the overlays of a loaded scene in an interaction state (its label sets, the
// state's clip meshes, the removed region) and where the crosshair starts.

#include "render/model/slice_view.h"
#include "session/interaction.h"
#include "session/loaded_scene.h"

#include <cstdint>
#include <vector>

namespace curette {

// Each label set outlined (its shown ids in their table colour, its protected ids red), each of the state's
// clip meshes as posed (`heldMesh`: the index of the one the user moves, -1 for none) and `removedRegion`
// (CarveReporter::removedRegion, or null). The overlays point into `loaded` and `removedRegion`.
SliceOverlays sceneSliceOverlays(const LoadedScene& loaded, const InteractionState& state,
                                 const std::vector<std::uint8_t>* removedRegion, int heldMesh);

// The centre of the clip meshes' world bounding box when the state has meshes, else of the scan's.
glm::dvec3 defaultCrosshair(const VolumeData& volume, const InteractionState& state);

}  // namespace curette
