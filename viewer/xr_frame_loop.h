#pragma once
// The headset's frame loop as decisions (`view --xr`, `bench xr`; executed by tools/xr_loop.cpp), GL-free like
// the monitor's (viewer/view_frame_loop.h), whose policy it runs: previews while something moved within the
// settle time, the exact frame once still, `--quality exact` exact every frame. What a headset adds:
//
//   - A frame every xrWaitFrame. The runtime expects a projection layer each frame, so nothing ever blocks on
//     the exact frame: it is computed in slices of the per-frame budget (Renderer::advanceExact), the left eye's
//     then the right's (the right finds V_AO current and casts its rays alone), and meanwhile the images last
//     submitted go out again with the poses they were rendered from (the compositor reprojects them to the
//     head). Whole, an exact frame on llvmpipe would hold one frame for seconds and the runtime would show
//     nothing new meanwhile. Both eyes are submitted together, exact or preview, never one of each.
//   - The exact frame is rendered from the eyes of the frame it started in (the held views), so jitter of the
//     head does not restart it; it is abandoned (and a preview follows) when something counts as motion.
//   - The head counts as moved when it is more than `positionMm` or `angleDeg` from where it last counted as
//     moved (HeadMotion), not at every change as the monitor's camera does: a tracked head is never still to
//     the bit, and under these bounds the compositor's reprojection of the held images is the better answer.
//     A slow drift counts each time it has added up to a bound.
//   - Previews are rendered per eye at the preview scale of the recommended size (trackedEye at the smaller
//     size: the same field of view at a coarser pitch) and submitted as they are: the projection view's
//     imageRect says their size and the compositor scales them to the field of view (OpenXR's own way to vary
//     the resolution; no upscaling pass, the swapchain keeps its recommended size).

#include "render/model/tracked_view.h"
#include "viewer/view_frame_loop.h"

#include <array>
#include <cstdint>
#include <optional>

namespace curette {

// How far the head may be from where it last counted as moved and still count as still.
struct HeadStillness {
    double positionMm = 5.0;   // the parallax error reprojection leaves stays under a few pixels at arm's length
    double angleDeg = 1.0;     // a turn the compositor corrects fully; tracking jitter is far below it
};

class HeadMotion {
public:
    explicit HeadMotion(HeadStillness stillness = {}) : stillness_(stillness) {}
    // Whether `head` counts as moved; it then becomes the pose later ones are measured from. The first pose
    // is where measuring starts (not a motion).
    bool moved(const TrackedView& head);

private:
    HeadStillness stillness_;
    std::optional<TrackedView> reference_;
};

// What one XR frame does.
enum class XrStep {
    ExactWhole,   // both eyes exact, each rendered whole (exact quality: every frame, as a GPU does)
    Preview,      // both eyes as previews at the preview size (after step I's slices, when decided)
    ExactSlice,   // the next slices of the exact frame (one eye's), the held images submitted meanwhile
    Hold,         // nothing to render: the held images submitted again
};
const char* xrStepName(XrStep step);

struct XrFrameInputs {
    double now = 0;                       // seconds (the frame's display time)
    bool sceneMoved = false;              // the step changed what the eyes show: a pose, the shading, the removal,
                                          // a setting, the volume's place in the room
    TrackedView head;                     // a pose rigid with the head (the left eye's view)
    bool precomputePending = false;       // step I is still to run (Renderer::precomputePending)
    std::uint64_t precomputeInputs = 0;   // Renderer::precomputeInputsVersion
    glm::ivec2 recommendedSize{1};        // the left eye's (the preview scale applies to both)
};

struct XrFrameDecision {
    XrStep step = XrStep::Hold;
    FrameDecision frame;                  // the monitor loop's: preview scale and ray step, budgets
    bool moved = false;                   // the scene or the head counted as moved this frame
    bool startExact = false;              // ExactSlice: a new exact frame, from this frame's eyes
};

class XrFrameLoop {
public:
    explicit XrFrameLoop(FrameLoopSettings settings = {}, HeadStillness stillness = {});

    XrFrameDecision decide(const XrFrameInputs& in);
    // What the executor submitted: a preview of this frame's state (at the left eye's recommended size scaled)
    // that took `ms` for both eyes (steers the preview scale), or the exact frame it was asked for (its last
    // slice done).
    void previewSubmitted(const XrFrameDecision& decision, double ms);
    void exactSubmitted();

    // An eye's preview image size bound: `recommended` at the preview scale.
    glm::ivec2 previewSize(glm::ivec2 recommended) const { return loop_.previewSize(recommended); }
    ViewQuality quality() const { return loop_.settings().quality; }
    const FrameLoopSettings& settings() const { return loop_.settings(); }

private:
    ViewFrameLoop loop_;
    HeadMotion head_;
    std::uint64_t generation_ = 0;        // counts motions: images of an older one show a past state
    enum class Held { None, Preview, Exact } held_ = Held::None;
    std::uint64_t heldGeneration_ = 0;
    std::optional<std::uint64_t> exactGeneration_;   // the exact frame under way, of this generation
};

}  // namespace curette
