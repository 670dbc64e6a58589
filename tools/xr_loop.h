#pragma once
// The frame loop of a head-mounted display session (OpenXR through xr/), shared by `view --xr` and `bench xr`:
// each frame the controllers' states (xr/controller_actions.h) become actions through session/xr_hands.h and
// the session step, then both eyes are rendered from the views the runtime located, through one renderer (one
// V_AO a frame, both eyes read it), and submitted; a small window mirrors the last eye. With a recording path
// every stepped frame is recorded (session version 7: head, eyes, hands, the volume's place, poses), so `replay`
// re-renders it headless and re-derives its poses and the volume's place from the hands.

#include "gl/context.h"
#include "render/model/frame_plan.h"
#include "render/model/tracked_view.h"
#include "render/renderer.h"
#include "session/loaded_scene.h"
#include "session/session_step.h"

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
};

// A rendered frame: wall time per eye (render, read back, submit) and the first eye's pass times (the second
// eye reuses its V_AO: steps I-V run at most once a frame).
struct XrFrameTiming {
    std::size_t frame = 0;                  // among the frames stepped
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
    std::vector<XrFrameTiming> rendered;
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
