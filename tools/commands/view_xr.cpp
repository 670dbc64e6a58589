// curette view --xr --scene S: the scene in a head-mounted display through OpenXR (the Khronos loader finds
// the active runtime: Monado, SteamVR, WiVRn, or whatever XR_RUNTIME_JSON names). The volume stands at real
// size on a table in the room (render/model/tracked_view.h); each frame both eyes are rendered from the poses
// and asymmetric fields of view the runtime located, through one renderer, so the ambient occlusion volume
// (V_AO, CAO steps I-V) is computed once a frame and both eyes read it; the eye images go into the session's
// swapchains (xr/xr_session.h). A small window holds the GLX context the runtime binds to and mirrors the
// right eye's frame (rendered last); with --headless there is no window: a headless EGL context is bound
// through XR_MNDX_egl_enable, where the runtime offers it (Monado does). --quality adaptive (the default on a software
// renderer) previews while the scene or the head moves and computes the exact frame in slices once still,
// submitting the held eyes meanwhile; exact (a GPU's default) renders both eyes exact every frame
// (viewer/xr_frame_loop.h). The loop is tools/xr_loop.h's.
//
// The controllers are action sources like the hidapi devices (xr/controller_actions.h, session/xr_hands.h):
// the left hand's squeeze holds tool 0, the right hand's tool 1, each following its grip, its thumbstick
// scaling it, its trigger drilling and its erase button erasing with it; a thumbstick flick left undoes a
// stroke, right redoes it; a hand holding its volume button carries the whole scene in the room (the carve
// does not change: session/xr_hands.h); a button cycles the shading; their actions go through the session
// step every command runs (session/session_step.h). --record F.jsonl records the session (head, eyes, hands
// and poses per frame) for `replay`. Prints each session state as it changes and, at the end, the frames
// rendered, the time per eye, each frame's passes, where each tool and the volume were left and what was drilled.
#include "tools/commands/view_xr.h"

#include "base/error.h"
#include "render/renderer.h"
#include "session/interaction.h"
#include "session/loaded_scene.h"
#include "session/session_step.h"
#include "tools/xr_loop.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <optional>

namespace curette::commands {

namespace {

// Mean, smallest and largest of a list of times.
struct Spread {
    double mean = 0, min = 0, max = 0;
    std::size_t count = 0;
};
Spread spread(const std::vector<double>& values) {
    Spread s;
    s.count = values.size();
    if (values.empty()) return s;
    for (double v : values) s.mean += v;
    s.mean /= static_cast<double>(values.size());
    s.min = *std::min_element(values.begin(), values.end());
    s.max = *std::max_element(values.begin(), values.end());
    return s;
}

// The scene path as seen from the session file, so the pair can move together.
std::string sceneFromSession(const std::filesystem::path& scene, const std::filesystem::path& session) {
    std::error_code ec;
    std::filesystem::path relative = std::filesystem::relative(std::filesystem::absolute(scene), std::filesystem::absolute(session).parent_path(), ec);
    return ec || relative.empty() ? std::filesystem::absolute(scene).string() : relative.string();
}

}  // namespace

int viewXr(const CommandLine& cl) {
    for (const char* option : {"play", "screenshot", "window-shot", "idle-seconds", "frame-log"})
        if (cl.value(option)) throw InputError("<command line>", std::string("--") + option, "not with --xr");
    if (cl.flag("headless") && cl.value("size")) throw InputError("<command line>", "--size", "not with --headless (there is no mirror window)");
    XrLoopOptions options;
    if (auto n = cl.value("frames")) options.frameLimit = CommandLine::parseInt("frames", *n, 1, 100000000);
    if (auto v = cl.value("save-views")) options.saveViews = *v;
    const std::string scenePath = cl.required("scene");
    if (auto r = cl.value("record")) {
        options.record = *r;
        options.sceneInSession = sceneFromSession(scenePath, *r);
    }
    LoadedScene loaded = loadSceneWithVolume(scenePath);
    // Headless: an EGL context the runtime binds through XR_MNDX_egl_enable (no window, no mirror).
    const bool headless = cl.flag("headless");
    std::unique_ptr<gl::WindowContext> window;
    std::unique_ptr<gl::Context> context;
    if (headless) {
        context = gl::createHeadlessContext();
    } else {
        window = gl::createWindowContext("curette - " + scenePath + " (OpenXR)", CommandLine::parseSize("size", cl.valueOr("size", "320x240")));
    }
    gl::Context& gl = headless ? *context : *window;
    options.loop.quality = defaultViewQuality(gl.info().softwareRenderer);
    if (auto q = cl.value("quality")) {
        std::optional<ViewQuality> quality = parseViewQuality(*q);
        if (!quality) throw InputError("<command line>", "--quality", "exact or adaptive", "\"" + *q + "\"");
        options.loop.quality = *quality;
    }
    Renderer renderer(gl, loaded.volume, loaded.scene.transferFunction);
    configureRenderer(loaded, renderer);
    SessionStep step(InteractionState::fromScene(loaded.scene), initialFrame(loaded.scene, renderer.geometry()));
    step.attachRemoval(loaded.volume.dims, loaded.volume.indexToWorld, loaded.removal.get());   // the scene's drilling

    XrLoopResult result = runXrLoop(gl, window.get(), renderer, step, loaded, options);
    std::printf("xr quality: %s\n", viewQualityName(options.loop.quality));
    // Per eye, the frames that rendered what they submitted: exact ones (in slices: the sum of the eye's slices)
    // and previews.
    for (bool exact : {true, false}) {
        for (std::size_t eye = 0; eye < 2; ++eye) {
            std::vector<double> ms;
            for (const XrFrameTiming& t : result.rendered)
                if (exact ? t.submittedExact : t.step == XrStep::Preview) ms.push_back(t.eyeMs[eye]);
            if (ms.empty() && !exact) continue;
            Spread s = spread(ms);
            std::printf("xr %s eye: %zu %s frames, %.1f ms per frame (min %.1f, max %.1f)\n", eye == 0 ? "left" : "right", s.count,
                        exact ? "exact" : "preview", s.mean, s.min, s.max);
        }
    }
    std::size_t heldFrames = result.rendered.size() - result.newImages();
    if (heldFrames > 0) std::printf("xr held eyes submitted again on %zu frames (the exact frame in slices, or nothing new)\n", heldFrames);
    std::printf("xr session over: %zu frames rendered\n", result.newImages());
    // The passes each frame ran for its first eye (the second reuses its V_AO): a moved volume runs no CAO step.
    for (const XrFrameTiming& t : result.rendered) {
        if (t.firstEye.passes.empty()) continue;
        std::string passes;
        for (const FrameTimings::Entry& e : t.firstEye.passes) passes += (passes.empty() ? "" : ", ") + std::string(passInfo(e.pass).name);
        std::printf("xr %s %zu passes: %s\n", t.step == XrStep::Preview ? "preview" : "frame", t.frame, passes.c_str());
    }
    const RoomAnchor& a = result.finalAnchor;
    const glm::dvec3 c = a.volumeCentreRoomM + 0.0;           // + 0.0: a zero prints without its sign
    const glm::dvec4 q = glm::dvec4(a.volumeTurnRoom.w, a.volumeTurnRoom.x, a.volumeTurnRoom.y, a.volumeTurnRoom.z) + 0.0;
    std::printf("xr volume left at %.4f, %.4f, %.4f m in the room, turned by [%.4f, %.4f, %.4f, %.4f]", c.x, c.y, c.z, q.x, q.y, q.z, q.w);
    if (a.volumeScale != 1.0) std::printf(", scaled by %.4f", a.volumeScale);
    std::printf("\n");
    for (const MeshState& m : step.state().meshes)
        std::printf("xr tool %d \"%s\" left at %.3f, %.3f, %.3f mm\n", m.id, m.name.c_str(), m.pose.position.x, m.pose.position.y, m.pose.position.z);
    const InteractionState& state = step.state();
    if (state.removal && !state.removal->empty())
        std::printf("drilled %.3f mL; removal %s\n", state.removal->drilledVolumeMm3() / 1000.0, state.removal->digest().c_str());
    return 0;
}

}  // namespace curette::commands
