#pragma once
// The viewer's iteration, one definition for the window (tools/commands/view.cpp) and `curette bench view`
// (tools/bench/bench_view.cpp), so what the bench measures is what the window does: the session step synced to
// the renderer, the frame loop's decision (viewer/view_frame_loop.h) and its execution (step I's slices, the
// preview or the exact frame, or a stereo pair). What only a window has (events, the overlay, presenting,
// recording) stays with the window; ViewerState is what the two share between iterations.

#include "session/carve_report.h"
#include "session/session_step.h"
#include "viewer/view_frame_loop.h"
#include "render/renderer.h"
#include "render/stereo_render.h"

#include <optional>
#include <string>

namespace curette {

struct ViewerState {
    explicit ViewerState(FrameLoopSettings settings) : loop(settings) {}

    ViewFrameLoop loop;
    double renderScale = 1.0;             // the exact frame's resolution over the window's (the preview's is the loop's)
    bool shownExact = false;              // the image on screen is the exact frame (stereo: both eyes exact at full size)
    // F3 cycles stereo (off, side-by-side, anaglyph; render/model/stereo.h): a way of showing, not a scene action,
    // so sessions do not record it.
    StereoMode stereo = StereoMode::Off;
    StereoView stereoView;
    double lastFrameMs = 0;               // the work of the last iteration that changed the image
    FrameTimings lastTimings;             // and its passes
};

// One iteration as run.
struct ViewerIteration {
    FrameDecision decision;
    bool precomputing = false;            // step I was pending when the loop decided
    bool preparing = false;               // it ran a slice of the label field and drew nothing
                                          // (Renderer::advanceLabelField)
    bool rendered = false;                // the image shown changed, or step I or an exact frame in slices advanced
                                          // (the window presents it: the progress bar moves)
    bool exactCompleted = false;          // an exact frame was finished by it (in slices: by its last)
    double ms = 0;                        // wall time of its work: step I's slices, the render, finish
    double renderMs = 0;                  // of it, the image
    FrameTimings passes;                  // GPU time per pass (render/model/frame_plan.h)
};

// The exact frame's size in a framebuffer of `framebuffer` pixels (times the user's resolution scale).
glm::ivec2 exactFrameSize(const ViewerState& viewer, glm::ivec2 framebuffer);

// The frame the step describes, with the state's shading, at the exact frame's size for `framebuffer`.
FrameDescription viewerFrame(const ViewerState& viewer, const SessionStep& step, glm::ivec2 framebuffer);

// One iteration at `now` (seconds, any origin) into a framebuffer of `framebuffer` pixels; `moved`: the camera or
// the step's state changed since the last one, at `movedAt` where known (FrameLoopInputs::movedAt).
ViewerIteration stepViewer(ViewerState& viewer, Renderer& renderer, SessionStep& step, const std::vector<Tractogram>& tracts,
                           glm::ivec2 framebuffer, double now, bool moved, glm::vec4 background,
                           double movedAt = std::numeric_limits<double>::quiet_NaN());

// The plan overlay's removal report: recomputed once what it depends on (reportInputs: the meshes, the TF, the
// bundles) has been still for kDelaySeconds (a report costs a GPU pass and a CPU pass over the grid; while a
// mesh moves or a TF point is dragged, the frames come first).
class ViewerReport {
public:
    static constexpr double kDelaySeconds = 0.2;

    // After an iteration: recompute when the report's inputs changed and have been still long enough.
    void refresh(CarveReporter& reporter, clip::ClipMeshSet& meshes, const InteractionState& state, double now);
    // F5: the report of the current state and the plan's exports into a new folder named after `timestamp`.
    // Returns the line the overlay shows (written, or why not).
    std::string exportPlan(CarveReporter& reporter, clip::ClipMeshSet& meshes, const InteractionState& state, const std::string& timestamp);

    const std::optional<plan::Report>& report() const { return report_; }
    bool current(const clip::ClipMeshSet& meshes, const InteractionState& state) const { return reported_ == reportInputs(meshes, state); }
    double ms() const { return ms_; }
    // How many reports have been computed: changes exactly when the reporter's field (and so its removed region)
    // does, which is when the slice panel must take the region again.
    std::uint64_t computedCount() const { return computed_; }

private:
    void compute(CarveReporter& reporter, clip::ClipMeshSet& meshes, const InteractionState& state);

    std::optional<plan::Report> report_;
    std::optional<ReportInputs> reported_, seen_;
    double changedAt_ = -1e9, ms_ = 0;
    int exports_ = 0;
    std::uint64_t computed_ = 0;
};

}  // namespace curette
