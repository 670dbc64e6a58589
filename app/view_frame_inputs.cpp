#include "app/view_frame_inputs.h"

namespace curette {

FrameLoopInputs frameLoopInputs(const Renderer& renderer, const ViewFrameLoop& loop, const FrameDescription& frame, double now,
                                bool moved) {
    FrameLoopInputs in;
    in.now = now;
    in.moved = moved;
    in.precomputePending = renderer.precomputePending(frame);
    in.exactSize = frame.size;
    double stepMm = renderer.resolveStepMm(frame.raycast);
    in.shown = [&renderer, &loop, frame, stepMm](FrameKind kind, glm::ivec2 size) {
        FrameDescription f = decidedFrame(frame, kind, size, loop.settings().previewStepScale, stepMm);
        return kind == FrameKind::Exact ? renderer.showing(f) : renderer.showingPreview(f);
    };
    return in;
}

}  // namespace curette
