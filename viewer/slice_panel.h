#pragma once
// The viewer's slice views (3D Slicer's four-up beside the 3-D view): axial, coronal and sagittal reslices
// through a crosshair, made by the function `curette render --slices` uses (render/model/slice_view.h with
// session/scene_slices.h's overlays), so the panel and the headless output agree pixel for pixel. GL-free:
// it holds the crosshair and the three images, makes them again only when what they show changed (the
// crosshair, the grey window, the meshes' shapes, scales and poses, the held mesh, the removed region), and
// turns the mouse on a slice into crosshair moves. The caller uploads the images (render/image_texture.h)
// and hands their texture names to draw().

#include "render/model/slice_view.h"
#include "session/carve_report.h"
#include "session/interaction.h"
#include "session/loaded_scene.h"

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <tuple>
#include <vector>

namespace curette {

class SlicePanel {
public:
    // The crosshair starts where `render --slices` puts it (session/scene_slices.h defaultCrosshair), the grey
    // window is the volume's default (scene/volume_statistics.h defaultGreyWindow). `loaded` must outlive it.
    SlicePanel(const LoadedScene& loaded, const InteractionState& initial);

    // Takes the reporter's removed region when a new report was computed (`reportCount`: ViewerReport::
    // computedCount(); the region is read only when it changed).
    void takeRemovedRegion(std::uint64_t reportCount, const CarveReporter& reporter);
    // Makes the images again when their inputs changed; true when it did (upload them then).
    bool update(const InteractionState& state, int heldMesh);
    const SliceImage& image(SliceAxis axis) const { return images_[static_cast<std::size_t>(axis)]; }
    std::uint64_t imageCount() const { return made_; }   // how many times update() made them

    glm::dvec3 crosshair() const { return crosshair_; }
    void setCrosshair(glm::dvec3 world) { crosshair_ = world; }   // e.g. the 3-D view's pick
    GreyWindow window() const { return window_; }
    void setWindow(GreyWindow window) { window_ = window; }

    // The mouse wheel over a slice: the crosshair moves along the slice's normal by one pixel spacing a step
    // (positive: towards +S, +A or +R).
    void scroll(SliceAxis axis, double steps);
    // A click at pixel coordinates of a slice (slice_view.h: (0, 0) the top-left corner): the crosshair moves
    // to that world point, which is returned (the ruler takes it).
    glm::dvec3 click(SliceAxis axis, glm::dvec2 pixel);

    // Dear ImGui: the three slices one under the other, each `width` points wide, from the textures the
    // caller uploaded the images into (GL texture names, in kSliceAxes order), the crosshair's coordinates and
    // the grey window. Handles the wheel and left clicks over a slice; returns the world point clicked.
    std::optional<glm::dvec3> draw(const std::array<std::uint32_t, 3>& textureNames, float width);

private:
    // What the images show, compared for update().
    struct Inputs {
        glm::dvec3 crosshair{0.0};
        GreyWindow window;
        std::vector<std::tuple<const clip::TriangleMesh*, clip::RigidPose, glm::dvec3>> meshes;
        int heldMesh = -1;
        std::uint64_t removedRegion = 0;
        bool operator==(const Inputs&) const = default;
    };

    const LoadedScene& loaded_;
    glm::dvec3 crosshair_{0.0};
    GreyWindow window_;
    std::vector<std::uint8_t> removedRegion_;
    std::uint64_t removedVersion_ = 0;
    std::optional<std::uint64_t> reportCount_;
    std::optional<Inputs> shown_;
    std::array<SliceImage, 3> images_;
    std::uint64_t made_ = 0;
};

}  // namespace curette
