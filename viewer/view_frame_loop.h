#pragma once
// The viewer's frame loop as decisions, without GL or a window (docs/architecture.md, "Preview and exact
// frames"): each frame it is told what moved, what the renderer is already showing and whether step I is still
// to run, and it says what to do: run slices of step I for a budget, and render a preview (reduced resolution,
// steps I, IV and V left out: Renderer::renderPreview) or the exact frame (Renderer::render), or nothing.
// `curette view` (GLFW) and `curette bench view` (EGL, a session played back in real time) both run it through
// one iteration (viewer/viewer_driver.h), so the bench measures the viewer's own policy.
//
// The policy:
//   - adaptive quality: while something moved within the last `settleSeconds`, previews; once nothing has
//     moved for that long the motion counts as stopped and the exact frame follows (the exact frame thus
//     comes settleSeconds plus one exact render after the last motion, plus at most the preview in flight).
//     The preview's resolution follows its measured time towards `previewTargetMs` (between the scale bounds,
//     starting at the lower),
//     so a slow scene (or a loaded machine) drops resolution rather than frames; its ray step is
//     `previewStepScale` times the exact frame's (VTK's interactive sample distance), halving its samples.
//     A preview of the very frame already on screen is not drawn again at the size the steering has moved to
//     since: after the last motion that would show the same picture a frame later, and the exact frame would
//     wait for it.
//   - exact quality: the exact frame whenever it is not on screen (a hardware GPU's default).
//   - adaptive quality computes the exact frame in slices of `exactBudgetMs` per frame (steps IV, V, the slab
//     pass and the ray cast are sliced: Renderer::advanceExact), showing the last preview meanwhile, so the window
//     never freezes for it; the decision stays "exact" until the renderer shows it. When no preview is on screen
//     (the first frame of a scene, or a change that was no motion after an exact frame) a preview comes first, so
//     the slices are never drawn over the image on screen.
//   - in both, a label field still to build (a labelled scene's first frame, a label style edit) is built first
//     in slices of `precomputeBudgetMs`, nothing drawn meanwhile (viewer/viewer_driver.h).
//   - in both, while step I is to run, each frame runs slices of it for `precomputeBudgetMs` and shows a
//     preview (phong: there is no AO yet) at the preview resolution (a full-size frame on llvmpipe would stall
//     the window for seconds), so the window keeps presenting and the overlay shows the progress.
//   - step I waits while its inputs are being edited: while they (volume, TF, LAO settings) changed within
//     `settleSeconds`, no slice of it runs, only previews. A TF drag changes them every frame, and each change
//     starts step I over, so a slice then would be thrown away by the next frame's edit and would only take
//     its time from the previews.

#include "render/model/frame.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <limits>
#include <optional>
#include <string>

namespace curette {

enum class ViewQuality { Exact, Adaptive };
const char* viewQualityName(ViewQuality quality);
std::optional<ViewQuality> parseViewQuality(const std::string& text);
// Exact every frame on a hardware GPU, adaptive on a software renderer (gl::ContextInfo::softwareRenderer).
ViewQuality defaultViewQuality(bool softwareRenderer);

struct FrameLoopSettings {
    ViewQuality quality = ViewQuality::Adaptive;
    // Nothing moved for this long: the motion has stopped. 0.1 s, not 0.2 s, since a motion abandons an exact frame
    // under way at the cost of its slice in flight: the exact frame came 0.10-0.17 s sooner on head-carved-move and
    // -pause, the motion frames as many and the TF drag's step I as held (docs/measurements.md).
    double settleSeconds = 0.1;
    double previewTargetMs = 70;       // the preview frame time its resolution is steered to
    double minPreviewScale = 0.125;    // preview resolution bounds, as a fraction of the exact frame's; the loop
                                       // starts at the lower one, so the first image (during step I) comes soon
    double maxPreviewScale = 0.5;
    double previewStepScale = 2.0;     // the preview's ray step over the exact frame's
    double precomputeBudgetMs = 60;    // step I per frame while it runs
    double exactBudgetMs = 60;         // adaptive quality: the exact frame in slices of this much per frame
                                       // (Renderer::advanceExact), so the window keeps presenting while it is
                                       // computed; exact quality renders it whole
    std::uint32_t exactSliceUnits = 0; // > 0: the exact frame's slices have this many units each (tests; see
                                       // Renderer::advanceExact), 0: as many as fit the budget
    int labelSlicePlanes = 0;          // > 0: the label field's slices have this many planes each (tests; see
                                       // Renderer::advanceLabelField), 0: as many as fit precomputeBudgetMs
};

enum class FrameKind { None, Preview, Exact };
const char* frameKindName(FrameKind kind);

struct FrameDecision {
    FrameKind render = FrameKind::None;
    glm::ivec2 size{0};                // of the image to render (unset for None)
    double rayStepScale = 1.0;         // times the exact frame's ray step (previews: previewStepScale)
    double precomputeBudgetMs = 0;     // > 0: first run slices of step I for this long
    double exactBudgetMs = 0;          // exact frames: > 0 run the next slices of it for this long
                                       // (Renderer::advanceExact), 0 render it whole
    std::uint32_t exactSliceUnits = 0;  // ... in slices of this many units (FrameLoopSettings::exactSliceUnits)
    bool inMotion = false;             // something moved within settleSeconds
};

struct FrameLoopInputs {
    double now = 0;                    // seconds, any origin (the loop compares differences)
    bool moved = false;                // the camera, a mesh, a light or the shading changed this frame
    // When that change happened, where its input says so (a played session's recorded time: the loop applies it
    // late, after the frame it was rendering), so the settle time counts from the motion itself; NaN: `now`.
    double movedAt = std::numeric_limits<double>::quiet_NaN();
    bool precomputePending = false;    // the frame's mode needs step I and it has not finished
    std::uint64_t precomputeInputs = 0; // changes whenever step I's inputs change (Renderer::precomputeInputsVersion)
    glm::ivec2 exactSize{1};           // the image size of the exact frame (the window times the user's scale)
    // What the renderer already shows of this frame (Renderer::showing, showingPreview): the exact frame at
    // exactSize, or a preview at any size (the steering may since have moved the size a new one would have).
    bool exactShown = false;
    bool previewShown = false;
    // The image on screen is the renderer's exact image, or there is none yet (the first frame of a scene): an
    // exact frame in slices would be drawn over it slice by slice, so adaptive quality shows a preview first.
    bool exactImageOnScreen = false;
};

// The frame a decision renders: `frame` at `size`, and for a preview with its ray step `rayStepScale` times
// `resolvedStepMm` (the renderer's step for frame.raycast, Renderer::resolveStepMm). An exact frame is `frame`
// at `size`, nothing else changed, so it is what `curette render` renders.
FrameDescription decidedFrame(FrameDescription frame, FrameKind kind, glm::ivec2 size, double rayStepScale, double resolvedStepMm);

class ViewFrameLoop {
public:
    explicit ViewFrameLoop(FrameLoopSettings settings = {});

    FrameDecision decide(const FrameLoopInputs& inputs);
    // What a decision's render cost (wall ms, after the GPU finished; without step I's slices): a preview's
    // steers the preview resolution.
    void rendered(const FrameDecision& decision, double ms);

    const FrameLoopSettings& settings() const { return settings_; }
    void setQuality(ViewQuality quality) { settings_.quality = quality; }
    double previewScale() const { return previewScale_; }
    glm::ivec2 previewSize(glm::ivec2 exactSize) const;
    // The time of the last motion (-infinity before any).
    double lastMotion() const { return lastMotion_; }

private:
    FrameLoopSettings settings_;
    double previewScale_;
    double lastMotion_;
    double lastPrecomputeEdit_;                   // when step I's inputs last changed (-infinity: not since the first frame)
    std::optional<std::uint64_t> precomputeInputs_;   // as of the last decision
};

}  // namespace curette
