#include "viewer/xr_frame_loop.h"

#include <cmath>

namespace curette {

bool HeadMotion::moved(const TrackedView& head) {
    if (!reference_) {
        reference_ = head;
        return false;
    }
    const double distanceMm = 1000.0 * glm::length(head.positionM - reference_->positionM);
    // The angle of the turn between the two orientations: 2 acos |<q1, q2>|.
    const double cosHalf = std::min(1.0, std::abs(glm::dot(head.orientation, reference_->orientation)));
    const double angleDeg = glm::degrees(2.0 * std::acos(cosHalf));
    if (distanceMm <= stillness_.positionMm && angleDeg <= stillness_.angleDeg) return false;
    reference_ = head;
    return true;
}

const char* xrStepName(XrStep step) {
    switch (step) {
        case XrStep::ExactWhole: return "exact";
        case XrStep::Preview: return "preview";
        case XrStep::ExactSlice: return "exact slice";
        case XrStep::Hold: return "held";
    }
    return "?";
}

XrFrameLoop::XrFrameLoop(FrameLoopSettings settings, HeadStillness stillness) : loop_(settings), head_(stillness) {}

XrFrameDecision XrFrameLoop::decide(const XrFrameInputs& in) {
    XrFrameDecision d;
    const bool headMoved = head_.moved(in.head);   // always measured, so the reference follows the head
    d.moved = in.sceneMoved || headMoved;
    if (d.moved) ++generation_;
    if (loop_.settings().quality == ViewQuality::Exact) {
        d.step = XrStep::ExactWhole;
        return d;
    }
    FrameLoopInputs f;
    f.now = in.now;
    f.moved = d.moved;
    f.precomputePending = in.precomputePending;
    f.precomputeInputs = in.precomputeInputs;
    f.exactSize = in.recommendedSize;
    f.exactShown = heldGeneration_ == generation_ && held_ == Held::Exact;
    f.previewShown = heldGeneration_ == generation_ && held_ == Held::Preview;
    // Nothing held: nothing to submit while the exact frame is sliced, so a preview comes first.
    f.exactImageOnScreen = held_ == Held::None;
    d.frame = loop_.decide(f);
    switch (d.frame.render) {
        case FrameKind::Preview: d.step = XrStep::Preview; break;
        case FrameKind::Exact:
            d.step = XrStep::ExactSlice;
            d.startExact = exactGeneration_ != generation_;
            exactGeneration_ = generation_;
            break;
        case FrameKind::None: d.step = XrStep::Hold; break;
    }
    if (d.step != XrStep::ExactSlice) exactGeneration_.reset();   // a preview drawn abandons it
    return d;
}

void XrFrameLoop::previewSubmitted(const XrFrameDecision& decision, double ms) {
    held_ = Held::Preview;
    heldGeneration_ = generation_;
    loop_.rendered(decision.frame, ms);
}

void XrFrameLoop::exactSubmitted() {
    held_ = Held::Exact;
    heldGeneration_ = exactGeneration_.value_or(generation_);
    exactGeneration_.reset();
}

}  // namespace curette
