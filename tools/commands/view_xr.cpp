// curette view --xr --scene S: the scene in a head-mounted display through OpenXR (the Khronos loader finds
// the active runtime: Monado, SteamVR, WiVRn, or whatever XR_RUNTIME_JSON names). The volume stands at real
// size on a table in the room (render/model/tracked_view.h); each frame both eyes are rendered from the poses
// and asymmetric fields of view the runtime located, through one renderer, so the ambient occlusion volume
// (V_AO, CAO steps I-V) is computed once a frame and both eyes read it; the eye images go into the session's
// swapchains (xr/xr_session.h). A small window holds the GLX context the runtime binds to and mirrors the
// right eye's frame (rendered last). Every frame is an exact one (no preview loop yet: on a software renderer
// this is slow).
//
// The controllers are action sources like the hidapi devices (xr/controller_actions.h, input/tracked_hand.h):
// the left hand's squeeze holds tool 0, the right hand's tool 1, each following its grip, its thumbstick
// scaling it; a button cycles the shading; their actions go through the session step every command runs (session/session_step.h).
// Prints each session state as it changes and, at the end, the frames rendered, the time per eye and where
// each tool was left.
#include "tools/commands/view_xr.h"

#include "base/atomic_file.h"
#include "base/error.h"
#include "render/presenter.h"
#include "render/renderer.h"
#include "render/stereo_render.h"
#include "input/tracked_hand.h"
#include "session/interaction.h"
#include "session/loaded_scene.h"
#include "session/session_step.h"
#include "xr/controller_actions.h"
#include "xr/xr_session.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <thread>

namespace curette::commands {

namespace {

volatile std::sig_atomic_t quitRequested = 0;
void requestQuit(int) { quitRequested = 1; }

// The views of a frame as `render --xr-views` reads them (tools/tracked_views_file.h).
void saveViews(const std::filesystem::path& path, RoomSpace space, const xr::Session& session, const std::array<TrackedView, 2>& views) {
    nlohmann::json list = nlohmann::json::array();
    for (const TrackedView& v : views)
        list.push_back({{"position_m", {v.positionM.x, v.positionM.y, v.positionM.z}},
                        {"orientation", {v.orientation.x, v.orientation.y, v.orientation.z, v.orientation.w}},
                        {"fov_rad", {v.fov.angleLeft, v.fov.angleRight, v.fov.angleUp, v.fov.angleDown}}});
    nlohmann::json doc = {{"space", space == RoomSpace::Stage ? "stage" : "local"},
                          {"recommended_size", {session.recommendedSize(0).x, session.recommendedSize(0).y}},
                          {"views", list}};
    writeFileAtomically(path, doc.dump(2) + "\n");
}

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

}  // namespace

int viewXr(const CommandLine& cl) {
    for (const char* option : {"play", "record", "screenshot", "window-shot", "idle-seconds", "frame-log", "quality"})
        if (cl.value(option)) throw InputError("<command line>", std::string("--") + option, "not with --xr");
    std::optional<int> frameLimit;
    if (auto n = cl.value("frames")) frameLimit = CommandLine::parseInt("frames", *n, 1, 100000000);
    std::optional<std::string> saveViewsPath = cl.value("save-views");
    const std::string scenePath = cl.required("scene");
    LoadedScene loaded = loadSceneWithVolume(scenePath);
    glm::ivec2 windowSize = CommandLine::parseSize("size", cl.valueOr("size", "320x240"));
    auto window = gl::createWindowContext("curette - " + scenePath + " (OpenXR)", windowSize);
    Renderer renderer(*window, loaded.volume, loaded.scene.transferFunction);
    configureRenderer(loaded, renderer);
    SessionStep step(InteractionState::fromScene(loaded.scene), initialFrame(loaded.scene, renderer.geometry()));
    step.attachRemoval(loaded.volume.dims, loaded.volume.indexToWorld, loaded.removal.get());   // the scene's drilling
    const glm::vec4 background(loaded.scene.background);

    window->makeCurrent();
    glfwSwapInterval(0);   // the runtime's xrWaitFrame paces the loop; the mirror must not wait for the monitor
    xr::Session session("curette", [](XrSessionState state) { std::printf("xr session state %s\n", xr::sessionStateName(state)); });
    const RoomAnchor anchor = tableAnchor(renderer.geometry(), session.roomSpace());
    std::printf("xr runtime: %s; system: %s; eyes %dx%d and %dx%d; %s space; volume centre at %.3f, %.3f, %.3f m\n", session.runtimeName().c_str(),
                session.systemName().c_str(), session.recommendedSize(0).x, session.recommendedSize(0).y, session.recommendedSize(1).x,
                session.recommendedSize(1).y, session.roomSpace() == RoomSpace::Stage ? "stage" : "local", anchor.volumeCentreRoomM.x,
                anchor.volumeCentreRoomM.y, anchor.volumeCentreRoomM.z);
    std::fflush(stdout);
    xr::ControllerActions controllers(session.instance(), session.session());
    std::array<input::TrackedHand, 2> hands{input::TrackedHand(0), input::TrackedHand(1)};

    std::signal(SIGINT, requestQuit);
    std::signal(SIGTERM, requestQuit);
    Presenter presenter;
    std::array<std::vector<double>, 2> eyeMs;
    std::size_t framesRendered = 0;
    XrTime lastDisplayTime = 0;   // the frame before's, for the hands' time step
    while (session.pollEvents()) {
        glfwPollEvents();
        const bool quit = window->shouldClose() || quitRequested;
        if (quit || (frameLimit && framesRendered >= static_cast<std::size_t>(*frameLimit))) session.requestExit();
        if (!session.running()) {   // idle, ready to begin or stopped: the runtime's next event
            if (quit) break;        // never begun (no READY yet): nothing to walk down
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
            continue;
        }
        xr::Session::Frame frame = session.beginFrame();
        const double dtSeconds = lastDisplayTime > 0 ? 1e-9 * static_cast<double>(frame.displayTime - lastDisplayTime) : 0.0;
        lastDisplayTime = frame.displayTime;
        // The hands' actions, applied to the scene as every device's are.
        std::array<xr::HandState, 2> handStates = controllers.sync(frame.displayTime, session.space());
        std::vector<input::Action> actions;
        for (std::size_t h = 0; h < 2; ++h) {
            const xr::HandState& s = handStates[h];
            input::HandSample sample{s.tracked, anchor.roomToWorldMm(s.grip.positionM), RoomAnchor::roomOrientationToWorld(s.grip.orientation),
                                     s.squeeze, s.shadingPressed, s.thumbstick.y, dtSeconds};
            for (input::Action& a : hands[h].step(sample)) actions.push_back(std::move(a));
        }
        step.apply(actions, session.recommendedSize(0).y);
        step.syncTo(renderer, loaded.tracts);
        const FrameDescription& base = step.frame();
        if (frame.shouldRender && frame.viewsValid) {
            for (int eye = 0; eye < 2; ++eye) {
                auto start = std::chrono::steady_clock::now();
                const TrackedView& view = frame.views[static_cast<std::size_t>(eye)];
                TrackedEye ev = trackedEye(base, view, anchor, session.recommendedSize(eye));
                Image image = renderTrackedEye(renderer, ev);
                session.submitEye(eye, toRgba8(image, background), ev.size, ev.renderedFov, view);
                eyeMs[static_cast<std::size_t>(eye)].push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
            }
            ++framesRendered;
            if (saveViewsPath) saveViews(*saveViewsPath, session.roomSpace(), session, frame.views);
            // The mirror: the last eye's whole frame, fitted into the window.
            const glm::ivec2 fb = window->framebufferSize(), out = renderer.outputSize();
            const double scale = std::min(double(fb.x) / out.x, double(fb.y) / out.y);
            const glm::ivec2 shown = glm::max(glm::ivec2(glm::dvec2(out) * scale), glm::ivec2(1));
            presenter.present(renderer.outputTexture(), (fb - shown) / 2, shown, fb, background);
            window->swapBuffers();
        }
        session.endFrame();
    }
    for (int eye = 0; eye < 2; ++eye) {
        Spread s = spread(eyeMs[static_cast<std::size_t>(eye)]);
        std::printf("xr %s eye: %zu frames, %.1f ms per frame (min %.1f, max %.1f)\n", eye == 0 ? "left" : "right", s.count, s.mean, s.min, s.max);
    }
    std::printf("xr session over: %zu frames rendered\n", framesRendered);
    for (const MeshState& m : step.state().meshes)
        std::printf("xr tool %d \"%s\" left at %.3f, %.3f, %.3f mm\n", m.id, m.name.c_str(), m.pose.position.x, m.pose.position.y, m.pose.position.z);
    return 0;
}

}  // namespace curette::commands
