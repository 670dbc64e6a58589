#pragma once
// The pictures of the report page (plan/report_page.h): standard 3-D views of the carve as the renderer
// shows the state (the scene's camera, then turned about the superior axis by 90, 180 and 270 degrees: the
// carve from four sides with the protected structures the scene shows), and the axial, coronal and sagittal
// slices (session/scene_slices.h, as `render --slices` makes them: removed region tinted, label outlines,
// the meshes' cross-sections) through the cavity's centre (the removed region's voxel centroid; the
// meshes' centre when nothing is removed).

#include "plan/report_page.h"
#include "render/renderer.h"
#include "session/interaction.h"
#include "session/loaded_scene.h"

#include <cstdint>
#include <vector>

namespace curette {

// Renders with `renderer`, which holds the state's meshes and settings; `sizePx` is each view's width and height.
std::vector<plan::ReportFigure> reportViews(Renderer& renderer, const LoadedScene& loaded, int sizePx);

std::vector<plan::ReportFigure> reportSlices(const LoadedScene& loaded, const InteractionState& state,
                                             const std::vector<std::uint8_t>& removedRegion);

}  // namespace curette
