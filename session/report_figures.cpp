#include "session/report_figures.h"

#include "session/scene_slices.h"
#include "scene/volume_statistics.h"
#include "render/model/image.h"
#include "render/model/slice_view.h"

#include <cmath>

namespace curette {

std::vector<plan::ReportFigure> reportViews(Renderer& renderer, const LoadedScene& loaded, int sizePx) {
    FrameDescription frame = initialFrame(loaded.scene, renderer.geometry());
    frame.size = glm::ivec2(sizePx);
    const glm::vec4 background(loaded.scene.background);
    std::vector<plan::ReportFigure> out;
    for (int quarter = 0; quarter < 4; ++quarter) {
        FrameDescription f = frame;
        f.camera.azimuthDeg = frame.camera.azimuthDeg + 90.0 * quarter;
        renderer.render(f);
        Image image = renderer.readImage();
        std::string caption = quarter == 0 ? "the scene's camera" : "turned " + std::to_string(90 * quarter) + " degrees about the superior axis";
        out.push_back({caption, encodePng(image.width, image.height, toRgba8(image, background))});
    }
    return out;
}

std::vector<plan::ReportFigure> reportSlices(const LoadedScene& loaded, const InteractionState& state, const std::vector<std::uint8_t>& removedRegion) {
    const VolumeData& volume = loaded.volume;
    glm::dvec3 sum(0.0);
    std::size_t count = 0;
    for (int k = 0; k < volume.dims.z; ++k)
        for (int j = 0; j < volume.dims.y; ++j)
            for (int i = 0; i < volume.dims.x; ++i)
                if (!removedRegion.empty() && removedRegion[volume.linearIndex(i, j, k)]) sum += glm::dvec3(i, j, k), ++count;
    glm::dvec3 at = count ? glm::dvec3(volume.indexToWorld * glm::dvec4(sum / double(count), 1.0)) : defaultCrosshair(volume, state);
    SliceOverlays overlays = sceneSliceOverlays(loaded, state, &removedRegion, -1);
    GreyWindow window = defaultGreyWindow(computeStatistics(volume));
    std::vector<plan::ReportFigure> out;
    char where[96];
    std::snprintf(where, sizeof where, " through %.1f, %.1f, %.1f mm (RAS)", at.x, at.y, at.z);
    for (SliceAxis axis : kSliceAxes) {
        SliceImage slice = renderSlice(volume, axis, at, window, overlays);
        out.push_back({std::string(sliceAxisName(axis)) + where, encodePng(slice.image.width, slice.image.height, toRgba8(slice.image, glm::vec4(0, 0, 0, 1)))});
    }
    return out;
}

}  // namespace curette
