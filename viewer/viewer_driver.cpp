#include "viewer/viewer_driver.h"

#include "viewer/view_frame_inputs.h"

#include <chrono>

namespace curette {

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) { return std::chrono::duration<double, std::milli>(Clock::now() - start).count(); }

}  // namespace

glm::ivec2 exactFrameSize(const ViewerState& viewer, glm::ivec2 framebuffer) {
    return glm::max(glm::ivec2(glm::dvec2(framebuffer) * viewer.renderScale), glm::ivec2(1));
}

FrameDescription viewerFrame(const ViewerState& viewer, const SessionStep& step, glm::ivec2 framebuffer) {
    FrameDescription frame = step.frame();
    frame.shading = step.state().shading;
    frame.size = exactFrameSize(viewer, framebuffer);
    return frame;
}

ViewerIteration stepViewer(ViewerState& viewer, Renderer& renderer, SessionStep& step, const std::vector<Tractogram>& tracts,
                           glm::ivec2 framebuffer, double now, bool moved, glm::vec4 background, double movedAt) {
    step.syncTo(renderer, tracts);   // meshes, and the setting edits of panels or a session
    FrameDescription frame = viewerFrame(viewer, step, framebuffer);
    const glm::ivec2 exactSize = frame.size;
    FrameLoopInputs in = frameLoopInputs(renderer, viewer.loop, frame, now, moved, movedAt);
    ViewerIteration it;
    it.precomputing = in.precomputePending;
    it.decision = viewer.loop.decide(in);
    // What a frame needs prepared, in slices before it, the image on screen kept and nothing drawn meanwhile (the
    // window presents the progress): the label field (a labelled scene's first frame, a label style edit), then
    // the clip maps while several meshes need them (a scene's first frame, meshes added) a mesh an iteration;
    // the last mesh's are drawn with its frame, so dragging one mesh's size keeps its frame rate.
    auto prepare = [&](auto work) {
        auto start = Clock::now();
        work();
        renderer.finish();
        it.decision = FrameDecision{};
        viewer.shownExact = false;   // the image kept is of the state before (a played session's end waits for the new one)
        it.preparing = true;
        it.rendered = true;
        it.ms = msSince(start);
        return it;
    };
    if (renderer.labelFieldPending())
        return prepare([&] { renderer.advanceLabelField(viewer.loop.settings().precomputeBudgetMs, viewer.loop.settings().labelSlicePlanes); });
    if (!it.decision.inMotion && renderer.clipMapsToDraw(frame) > 1) return prepare([&] { renderer.advanceClipMaps(frame); });
    const FrameDecision& d = it.decision;
    double stepMm = renderer.resolveStepMm(frame.raycast);
    if (d.render != FrameKind::None) frame.size = d.size;
    auto start = Clock::now();
    if (viewer.stereo != StereoMode::Off) {
        // The pair is two exact frames at the decided size (render/stereo_render.h); no slices, no steering.
        it.rendered = viewer.stereoView.update(renderer, frame, viewer.stereo, kDefaultEyeSeparationMm, background);
        if (it.rendered) viewer.shownExact = frame.size == exactSize;
        it.renderMs = msSince(start);
    } else {
        if (d.precomputeBudgetMs > 0) renderer.advancePrecompute(d.precomputeBudgetMs);
        auto imageStart = Clock::now();
        bool shown = renderDecidedImage(renderer, d, decidedFrame(frame, d.render, frame.size, d.rayStepScale, stepMm));
        renderer.finish();
        it.renderMs = msSince(imageStart);
        viewer.loop.rendered(d, it.renderMs);
        it.exactCompleted = d.render == FrameKind::Exact && shown;
        it.rendered = shown || d.precomputeBudgetMs > 0 || (d.render == FrameKind::Exact && d.exactBudgetMs > 0);
        viewer.shownExact = renderer.lastFrameExact();
    }
    renderer.finish();
    it.ms = msSince(start);
    it.passes = renderer.collectTimings();
    if (it.rendered) {
        viewer.lastFrameMs = it.ms;
        viewer.lastTimings = it.passes;
    }
    return it;
}

void ViewerReport::compute(CarveReporter& reporter, clip::ClipMeshSet& meshes, const InteractionState& state) {
    auto start = Clock::now();
    reported_ = reportInputs(meshes, state);
    report_ = reporter.compute(meshes, state);
    ++computed_;
    ms_ = msSince(start);
}

void ViewerReport::refresh(CarveReporter& reporter, clip::ClipMeshSet& meshes, const InteractionState& state, double now) {
    ReportInputs inputs = reportInputs(meshes, state);
    if (inputs != seen_) seen_ = inputs, changedAt_ = now;
    if (inputs != reported_ && now - changedAt_ >= kDelaySeconds) compute(reporter, meshes, state);
}

std::string ViewerReport::exportPlan(CarveReporter& reporter, clip::ClipMeshSet& meshes, const InteractionState& state,
                                     const std::string& timestamp) {
    if (!current(meshes, state)) compute(reporter, meshes, state);
    std::string name = "curette-plan-" + timestamp;
    if (exports_++ > 0) name += "-" + std::to_string(exports_);
    std::filesystem::path dir = std::filesystem::absolute(name);
    try {
        reporter.write(dir, *report_, state, PlanExportOptions{});
        return "wrote the plan to " + dir.string();
    } catch (const std::exception& e) {
        return std::string("could not write the plan: ") + e.what();
    }
}

}  // namespace curette
