#include "viewer/view_frame_inputs.h"

namespace curette {

FrameLoopInputs frameLoopInputs(const Renderer& renderer, const ViewFrameLoop& loop, const FrameDescription& frame, double now,
                                bool moved, double movedAt) {
    FrameLoopInputs in;
    in.now = now;
    in.moved = moved;
    in.movedAt = movedAt;
    in.precomputePending = renderer.precomputePending(frame);
    in.precomputeInputs = renderer.precomputeInputsVersion();
    in.exactSize = frame.size;
    in.exactImageOnScreen = !renderer.showsAnImage() || renderer.lastFrameExact();
    double stepMm = renderer.resolveStepMm(frame.raycast);
    in.exactShown = renderer.showing(frame);
    std::optional<glm::ivec2> previewSize = renderer.shownPreviewSize();
    in.previewShown = previewSize &&
                      renderer.showingPreview(decidedFrame(frame, FrameKind::Preview, *previewSize, loop.settings().previewStepScale, stepMm));
    return in;
}

bool renderDecidedImage(Renderer& renderer, const FrameDecision& decision, const FrameDescription& decided) {
    if (decision.render == FrameKind::Preview) renderer.renderPreview(decided);
    if (decision.render == FrameKind::Exact) {
        if (decision.exactBudgetMs > 0) return renderer.advanceExact(decided, decision.exactBudgetMs, decision.exactSliceUnits);
        renderer.render(decided);
    }
    return decision.render != FrameKind::None;
}

}  // namespace curette
