#include "viewer/view_frame_loop.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace curette {

const char* viewQualityName(ViewQuality quality) { return quality == ViewQuality::Exact ? "exact" : "adaptive"; }

std::optional<ViewQuality> parseViewQuality(const std::string& text) {
    if (text == "exact") return ViewQuality::Exact;
    if (text == "adaptive") return ViewQuality::Adaptive;
    return std::nullopt;
}

ViewQuality defaultViewQuality(bool softwareRenderer) { return softwareRenderer ? ViewQuality::Adaptive : ViewQuality::Exact; }

const char* frameKindName(FrameKind kind) {
    switch (kind) {
        case FrameKind::None: return "none";
        case FrameKind::Preview: return "preview";
        case FrameKind::Exact: return "exact";
    }
    return "?";
}

FrameDescription decidedFrame(FrameDescription frame, FrameKind kind, glm::ivec2 size, double rayStepScale, double resolvedStepMm) {
    frame.size = size;
    if (kind == FrameKind::Preview && rayStepScale != 1.0) frame.raycast.stepMm = rayStepScale * resolvedStepMm;
    return frame;
}

ViewFrameLoop::ViewFrameLoop(FrameLoopSettings settings)
    : settings_(settings),
      previewScale_(settings.minPreviewScale),
      lastMotion_(-std::numeric_limits<double>::infinity()),
      lastPrecomputeEdit_(-std::numeric_limits<double>::infinity()) {}

glm::ivec2 ViewFrameLoop::previewSize(glm::ivec2 exactSize) const {
    return glm::max(glm::ivec2(glm::round(glm::dvec2(exactSize) * previewScale_)), glm::ivec2(1));
}

FrameDecision ViewFrameLoop::decide(const FrameLoopInputs& in) {
    if (in.moved) lastMotion_ = std::max(lastMotion_, std::isnan(in.movedAt) ? in.now : std::min(in.movedAt, in.now));
    // The first frame's inputs are where step I starts, not an edit.
    if (precomputeInputs_ && *precomputeInputs_ != in.precomputeInputs) lastPrecomputeEdit_ = in.now;
    precomputeInputs_ = in.precomputeInputs;
    FrameDecision d;
    d.inMotion = in.now - lastMotion_ < settings_.settleSeconds;
    bool adaptive = settings_.quality == ViewQuality::Adaptive;
    auto want = [&](FrameKind kind, glm::ivec2 size) {
        if (kind == FrameKind::Exact ? in.exactShown : in.previewShown) return;
        d.render = kind;
        d.size = size;
        d.rayStepScale = kind == FrameKind::Preview ? settings_.previewStepScale : 1.0;
    };
    if (in.precomputePending) {
        // No exact frame before step I is done: a slice of it, and the frame without AO (the renderer's preview).
        // No slice while step I's inputs are being edited: the next edit would start it over.
        bool editing = in.now - lastPrecomputeEdit_ < settings_.settleSeconds;
        d.precomputeBudgetMs = editing ? 0.0 : settings_.precomputeBudgetMs;
        want(FrameKind::Preview, previewSize(in.exactSize));
    } else if (adaptive && (d.inMotion || (in.exactImageOnScreen && !in.exactShown))) {
        want(FrameKind::Preview, previewSize(in.exactSize));
    } else {
        want(FrameKind::Exact, in.exactSize);
        if (d.render == FrameKind::Exact && adaptive) d.exactBudgetMs = settings_.exactBudgetMs, d.exactSliceUnits = settings_.exactSliceUnits;
    }
    return d;
}

void ViewFrameLoop::rendered(const FrameDecision& decision, double ms) {
    // Only previews in motion steer (a still preview, during step I, is drawn once: steering it would redraw it at
    // every new size, taking the frames from step I's slices).
    if (decision.render != FrameKind::Preview || !decision.inMotion || !(ms > 0)) return;
    // The cost of a frame grows with its pixels, the square of the scale: half the step to the scale that would
    // have met the target (a geometric mean), so one slow frame does not throw the resolution about.
    double ideal = previewScale_ * std::sqrt(settings_.previewTargetMs / ms);
    previewScale_ = std::clamp(std::sqrt(previewScale_ * ideal), settings_.minPreviewScale, settings_.maxPreviewScale);
}

}  // namespace curette
