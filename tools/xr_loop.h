#pragma once
// The frame loop of a head-mounted display session (OpenXR through xr/), shared by `view --xr` and `bench xr`:
// each frame the controllers' states (xr/controller_actions.h) become actions through session/xr_hands.h and
// the session step, then the frame loop's decision (viewer/xr_frame_loop.h) is run: both eyes rendered from the
// views the runtime located, through one renderer (one V_AO a frame, both eyes read it), exact or as previews,
// or the next slices of the exact frame with the held images submitted again; a small window mirrors the last
// eye rendered. With a recording path
// every stepped frame is recorded (session version 7: head, eyes, hands, the volume's place, poses), so `replay`
// re-renders it headless and re-derives its poses and the volume's place from the hands.

#include "gl/context.h"
#include "render/model/frame_plan.h"
#include "render/model/tracked_view.h"
#include "render/renderer.h"
#include "session/loaded_scene.h"
#include "session/session_step.h"
#include "viewer/xr_frame_loop.h"

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace curette {

struct XrLoopOptions {
    std::optional<int> frameLimit;                    // frames rendered before curette asks to end the session
    std::optional<std::filesystem::path> record;      // a session file (JSON Lines)
    std::string sceneInSession;                       // the scene as the session's header names it
    std::optional<std::filesystem::path> saveViews;   // the last rendered frame's views (render --xr-views)
    bool printStates = true;                          // "xr session state X" lines as the state changes
    FrameLoopSettings loop;                           // quality (exact: every frame exact and whole), budgets
    HeadStillness stillness;
    bool endAfterExact = false;                       // ask to end the session once an exact frame is submitted
                                                      // after the last motion (bench xr)
};

// A frame that submitted eyes: what it did, wall time per eye (render, read back, submit; an exact frame in
// slices: the sum of its eye's slices, on the frame that submits it) and the first eye's pass times (the
// second eye reuses its V_AO: steps I-V run at most once a frame; in slices, summed over the left eye's).
struct XrFrameTiming {
    std::size_t frame = 0;                  // among the frames stepped
    XrStep step = XrStep::ExactWhole;       // Hold and ExactSlice frames submitted the held images
    bool submittedExact = false;            // the eyes submitted are exact (ExactWhole, or the slices' last)
    bool moved = false;                     // the scene or the head counted as moved
    double displayS = 0;                    // the display time, from the first frame's
    double wallS = 0;                       // wall time when the frame ended, from the first frame's begin
    double workMs = 0;                      // wall time of this frame's rendering (step I's slices included)
    std::array<double, 2> eyeMs{};
    FrameTimings firstEye;
};

struct XrLoopResult {
    std::string runtime, system;
    RoomSpace space = RoomSpace::Stage;
    std::array<glm::ivec2, 2> recommendedSize{};
    RoomAnchor anchor;        // the volume on its table, at the start
    RoomAnchor finalAnchor;   // where the hands left it
    std::size_t framesStepped = 0;
    std::vector<XrFrameTiming> rendered;   // every frame that submitted eyes
    std::size_t newImages() const;         // of them, those that rendered the eyes they submitted
};

// Runs the session until the runtime ends it (or frameLimit frames, or the window closes, or SIGINT/SIGTERM).
// `context` is the one `renderer` renders in: a window's GLX context (then `mirror` is that window, which
// shows the last eye) or, with `mirror` null, a headless EGL context bound through XR_MNDX_egl_enable.
XrLoopResult runXrLoop(gl::Context& context, gl::WindowContext* mirror, Renderer& renderer, SessionStep& step, const LoadedScene& loaded,
                       const XrLoopOptions& options);

// Eye `eye` of a frame rendered from `views` with the step's frame (render/model/tracked_view.h).
std::array<TrackedEye, 2> xrEyes(const FrameDescription& base, const std::array<TrackedView, 2>& views, const RoomAnchor& anchor,
                                 const std::array<glm::ivec2, 2>& recommendedSize);

// The CAO exactness contract on a head-mounted display's frame: `eyes` rendered (both) in their mode (cao or
// lao), then again in the other one, in the same renderer; true when V_AO and both eye images are the same
// bit for bit. `images` are the first rendering's eye images.
bool xrCaoEqualsLao(Renderer& renderer, const std::array<TrackedEye, 2>& eyes, const std::array<Image, 2>& images);

}  // namespace curette
