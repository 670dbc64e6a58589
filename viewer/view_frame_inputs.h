#pragma once
// What the viewer's frame loop (viewer/view_frame_loop.h, which knows no renderer) needs to know of a renderer
// this frame, for the viewer's iteration (viewer/viewer_driver.h), which the window and `bench view` share.

#include "viewer/view_frame_loop.h"
#include "render/renderer.h"

namespace curette {

// The loop's inputs for `frame` (its size is the exact frame's) on `renderer` at `now`, with the motion (at
// `movedAt`, FrameLoopInputs::movedAt): whether step I is pending, and whether the renderer already shows the
// frame the loop would decide on.
FrameLoopInputs frameLoopInputs(const Renderer& renderer, const ViewFrameLoop& loop, const FrameDescription& frame, double now,
                                bool moved, double movedAt = std::numeric_limits<double>::quiet_NaN());

// The image of `decision` on `renderer` (after step I's slices, which the caller runs and times apart): the
// preview or the exact frame `decided` (decidedFrame of the decision), the exact one in slices when the
// decision gives it a budget. Returns whether the image shown changed.
bool renderDecidedImage(Renderer& renderer, const FrameDecision& decision, const FrameDescription& decided);

}  // namespace curette
