#include "viewer/slice_panel.h"

#include "scene/volume_statistics.h"
#include "session/scene_slices.h"

#include <imgui.h>

#include <cstdint>

namespace curette {

SlicePanel::SlicePanel(const LoadedScene& loaded, const InteractionState& initial)
    : loaded_(loaded),
      crosshair_(defaultCrosshair(loaded.volume, initial)),
      window_(defaultGreyWindow(computeStatistics(loaded.volume))) {}

void SlicePanel::takeRemovedRegion(std::uint64_t reportCount, const CarveReporter& reporter) {
    if (reportCount_ == reportCount) return;
    reportCount_ = reportCount;
    removedRegion_ = reporter.removedRegion();
    ++removedVersion_;
}

bool SlicePanel::update(const InteractionState& state, int heldMesh) {
    Inputs inputs{crosshair_, window_, {}, heldMesh, removedVersion_};
    for (const MeshState& m : state.meshes) inputs.meshes.emplace_back(m.geometry.get(), m.pose, m.scale);
    if (shown_ == inputs) return false;
    SliceOverlays overlays = sceneSliceOverlays(loaded_, state, removedRegion_.empty() ? nullptr : &removedRegion_, heldMesh);
    for (SliceAxis axis : kSliceAxes)
        images_[static_cast<std::size_t>(axis)] = renderSlice(loaded_.volume, axis, crosshair_, window_, overlays);
    shown_ = std::move(inputs);
    ++made_;
    return true;
}

void SlicePanel::scroll(SliceAxis axis, double steps) {
    SlicePlane plane = slicePlane(loaded_.volume.dims, loaded_.volume.indexToWorld, axis, crosshair_);
    crosshair_ += steps * plane.pixelMm * plane.normal;
}

glm::dvec3 SlicePanel::click(SliceAxis axis, glm::dvec2 pixel) {
    SlicePlane plane = slicePlane(loaded_.volume.dims, loaded_.volume.indexToWorld, axis, crosshair_);
    crosshair_ = plane.worldAt(pixel);
    return crosshair_;
}

std::optional<glm::dvec3> SlicePanel::draw(const std::array<std::uint32_t, 3>& textureNames, float width) {
    std::optional<glm::dvec3> clicked;
    ImGui::Text("crosshair R %.1f  A %.1f  S %.1f mm", crosshair_.x, crosshair_.y, crosshair_.z);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("click a slice to move the crosshair there; the wheel over a slice scrolls through it");
    float lo = static_cast<float>(window_.lo), hi = static_cast<float>(window_.hi);
    float speed = static_cast<float>((loaded_.volume.maxValue - loaded_.volume.minValue) / 500.0);
    if (ImGui::DragFloatRange2("window", &lo, &hi, speed > 0 ? speed : 0.01f, 0.0f, 0.0f, "%.4g", "%.4g") && hi > lo) window_ = {lo, hi};
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("grey levels: values at the left end black, at the right end white");
    for (SliceAxis axis : kSliceAxes) {
        const SliceImage& slice = image(axis);
        if (slice.image.width <= 0) continue;
        float scale = width / static_cast<float>(slice.image.width);
        ImVec2 size(width, scale * static_cast<float>(slice.image.height));
        ImGui::TextDisabled("%s", sliceAxisName(axis));
        ImTextureID texture = reinterpret_cast<ImTextureID>(static_cast<std::uintptr_t>(textureNames[static_cast<std::size_t>(axis)]));
        ImGui::Image(texture, size);
        if (!ImGui::IsItemHovered()) continue;
        const ImGuiIO& io = ImGui::GetIO();
        ImVec2 origin = ImGui::GetItemRectMin();
        glm::dvec2 pixel((io.MousePos.x - origin.x) / scale, (io.MousePos.y - origin.y) / scale);
        if (io.MouseWheel != 0.0f) scroll(axis, io.MouseWheel);
        if (ImGui::IsMouseClicked(ImGuiMouseButton_Left)) clicked = click(axis, pixel);
        glm::dvec3 under = slice.plane.worldAt(pixel);
        ImGui::SetTooltip("R %.1f  A %.1f  S %.1f mm", under.x, under.y, under.z);
    }
    return clicked;
}

}  // namespace curette
