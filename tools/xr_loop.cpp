#include "tools/xr_loop.h"

#include "base/atomic_file.h"
#include "input/hid/fake_backend.h"
#include "input/mapping.h"
#include "render/presenter.h"
#include "render/stereo_render.h"
#include "session/live_input.h"
#include "session/xr_hands.h"
#include "xr/controller_actions.h"
#include "xr/xr_session.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <nlohmann/json.hpp>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <thread>

namespace curette {

namespace {

volatile std::sig_atomic_t quitRequested = 0;
void requestQuit(int) { quitRequested = 1; }

// The views of a frame as `render --xr-views` reads them (tools/tracked_views_file.h).
void saveViews(const std::filesystem::path& path, RoomSpace space, glm::ivec2 recommendedSize, const std::array<TrackedView, 2>& views,
               const RoomAnchor& anchor) {
    nlohmann::json list = nlohmann::json::array();
    for (const TrackedView& v : views)
        list.push_back({{"position_m", {v.positionM.x, v.positionM.y, v.positionM.z}},
                        {"orientation", {v.orientation.x, v.orientation.y, v.orientation.z, v.orientation.w}},
                        {"fov_rad", {v.fov.angleLeft, v.fov.angleRight, v.fov.angleUp, v.fov.angleDown}}});
    nlohmann::json doc = {{"space", space == RoomSpace::Stage ? "stage" : "local"},
                          {"recommended_size", {recommendedSize.x, recommendedSize.y}},
                          {"views", list}};
    const glm::dquat& q = anchor.volumeTurnRoom;
    doc["volume"] = {{"centre_m", {anchor.volumeCentreRoomM.x, anchor.volumeCentreRoomM.y, anchor.volumeCentreRoomM.z}}, {"turn", {q.x, q.y, q.z, q.w}}};
    writeFileAtomically(path, doc.dump(2) + "\n");
}

SessionXrHand recordedHand(const xr::HandState& s) {
    SessionXrHand h;
    h.tracked = s.tracked;
    if (s.tracked) h.grip = s.grip;
    h.squeeze = s.squeeze;
    h.trigger = s.trigger;
    h.thumbstick = s.thumbstick;
    h.shadingPressed = s.shadingPressed;
    h.moveVolume = s.moveVolume;
    h.erase = s.erase;
    return h;
}

}  // namespace

std::array<TrackedEye, 2> xrEyes(const FrameDescription& base, const std::array<TrackedView, 2>& views, const RoomAnchor& anchor,
                                 const std::array<glm::ivec2, 2>& recommendedSize) {
    return {trackedEye(base, views[0], anchor, recommendedSize[0]), trackedEye(base, views[1], anchor, recommendedSize[1])};
}

bool xrCaoEqualsLao(Renderer& renderer, const std::array<TrackedEye, 2>& eyes, const std::array<Image, 2>& images) {
    if (!renderer.ambientOcclusion()) return false;
    std::vector<std::uint16_t> ambient = renderer.ambientOcclusion()->readAmbient();
    bool same = true;
    for (std::size_t e = 0; e < 2; ++e) {
        TrackedEye other = eyes[e];
        other.frame.shading = eyes[e].frame.shading == ShadingMode::Cao ? ShadingMode::Lao : ShadingMode::Cao;
        Image image = renderTrackedEye(renderer, other);
        same = same && image.pixels.size() == images[e].pixels.size() &&
               std::memcmp(image.pixels.data(), images[e].pixels.data(), image.pixels.size() * sizeof(glm::vec4)) == 0;
        if (e == 0) same = same && renderer.ambientOcclusion()->readAmbient() == ambient;
    }
    return same;
}

XrLoopResult runXrLoop(gl::Context& context, gl::WindowContext* mirror, Renderer& renderer, SessionStep& step, const LoadedScene& loaded,
                       const XrLoopOptions& options) {
    XrLoopResult result;
    const glm::vec4 background(loaded.scene.background);
    context.makeCurrent();
    if (mirror) glfwSwapInterval(0);   // the runtime's xrWaitFrame paces the loop; the mirror must not wait for the monitor
    const bool printStates = options.printStates;
    xr::Session session("curette", mirror ? xr::GlBinding::Glx : xr::GlBinding::Egl, [printStates](XrSessionState state) {
        if (printStates) std::printf("xr session state %s\n", xr::sessionStateName(state));
    });
    result.runtime = session.runtimeName();
    result.system = session.systemName();
    result.space = session.roomSpace();
    result.recommendedSize = {session.recommendedSize(0), session.recommendedSize(1)};
    result.anchor = tableAnchor(renderer.geometry(), session.roomSpace());
    const RoomAnchor& anchor = result.anchor;   // on its table, until a hand moves it (hands.anchor())
    std::printf("xr runtime: %s; system: %s; eyes %dx%d and %dx%d; %s space; volume centre at %.3f, %.3f, %.3f m\n", session.runtimeName().c_str(),
                session.systemName().c_str(), session.recommendedSize(0).x, session.recommendedSize(0).y, session.recommendedSize(1).x,
                session.recommendedSize(1).y, session.roomSpace() == RoomSpace::Stage ? "stage" : "local", anchor.volumeCentreRoomM.x,
                anchor.volumeCentreRoomM.y, anchor.volumeCentreRoomM.z);
    std::fflush(stdout);
    xr::ControllerActions controllers(session.instance(), session.session());
    XrHands hands(anchor);

    // A recording: no HID devices take part in an XR session, so its input is the empty device set under the
    // default mapping (a valid header that `replay --from-reports` reads like any other) and the hands.
    std::optional<LiveInput> noDevices;
    std::optional<LiveRecording> recording;
    if (options.record) {
        noDevices.emplace(std::make_unique<input::FakeHidBackend>(std::make_shared<input::FakeHidBackend::Ports>()), input::defaultMapping(), 40.0, 60.0);
        SessionXr xr{session.roomSpace(), result.recommendedSize, session.runtimeName(), session.systemName()};
        recording.emplace(*options.record, options.sceneInSession, step.state(), *noDevices, 0.0, 5.0, xr);
    }

    std::signal(SIGINT, requestQuit);
    std::signal(SIGTERM, requestQuit);
    Presenter presenter;
    XrTime firstDisplayTime = 0, lastDisplayTime = 0;   // the frame before's, for the hands' time step
    while (session.pollEvents()) {
        if (mirror) glfwPollEvents();
        const bool quit = (mirror && mirror->shouldClose()) || quitRequested;
        if (quit || (options.frameLimit && result.rendered.size() >= static_cast<std::size_t>(*options.frameLimit))) session.requestExit();
        if (!session.running()) {   // idle, ready to begin or stopped: the runtime's next event
            if (quit) break;        // never begun (no READY yet): nothing to walk down
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
            continue;
        }
        xr::Session::Frame frame = session.beginFrame();
        const double dtSeconds = lastDisplayTime > 0 ? 1e-9 * static_cast<double>(frame.displayTime - lastDisplayTime) : 0.0;
        if (firstDisplayTime == 0) firstDisplayTime = frame.displayTime;
        lastDisplayTime = frame.displayTime;
        // The hands' actions, applied to the scene as every device's are.
        std::array<xr::HandState, 2> handStates = controllers.sync(frame.displayTime, session.space());
        SessionXrFrame record;
        record.displayTimeNs = frame.displayTime;
        record.head = frame.head;
        for (std::size_t h = 0; h < 2; ++h) record.hands[h] = recordedHand(handStates[h]);
        step.apply(hands.step(record.hands, dtSeconds), session.recommendedSize(0).y);
        record.anchor = hands.anchor();
        step.syncTo(renderer, loaded.tracts);
        const std::size_t index = result.framesStepped++;
        if (frame.shouldRender && frame.viewsValid) {
            record.views = frame.views;
            std::array<TrackedEye, 2> eyes = xrEyes(step.frame(), frame.views, hands.anchor(), result.recommendedSize);
            XrFrameTiming timing;
            timing.frame = index;
            renderer.collectTimings();   // the times of this frame alone
            for (int eye = 0; eye < 2; ++eye) {
                auto start = std::chrono::steady_clock::now();
                const TrackedEye& ev = eyes[static_cast<std::size_t>(eye)];
                Image image = renderTrackedEye(renderer, ev);
                session.submitEye(eye, toRgba8(image, background), ev.size, ev.renderedFov, frame.views[static_cast<std::size_t>(eye)]);
                timing.eyeMs[static_cast<std::size_t>(eye)] = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
                if (eye == 0) timing.firstEye = renderer.collectTimings();
            }
            result.rendered.push_back(timing);
            if (options.saveViews) saveViews(*options.saveViews, session.roomSpace(), session.recommendedSize(0), frame.views, hands.anchor());
            if (mirror) {   // the last eye's whole frame, fitted into the window
                const glm::ivec2 fb = mirror->framebufferSize(), out = renderer.outputSize();
                const double scale = std::min(double(fb.x) / out.x, double(fb.y) / out.y);
                const glm::ivec2 shown = glm::max(glm::ivec2(glm::dvec2(out) * scale), glm::ivec2(1));
                presenter.present(renderer.outputTexture(), (fb - shown) / 2, shown, fb, background);
                mirror->swapBuffers();
            }
        }
        if (recording) {
            const double now = 1e-9 * static_cast<double>(frame.displayTime - firstDisplayTime);
            recording->addFrame(now, dtSeconds, session.recommendedSize(0), step.frame().camera, step.state(), input::KeyboardMouseState{},
                                InputFrame{}, record);
        }
        session.endFrame();
    }
    result.finalAnchor = hands.anchor();
    if (recording) {
        recording->finish();
        std::printf("xr session recorded: %s, %zu frames\n", recording->path().c_str(), recording->frames());
    }
    return result;
}

}  // namespace curette
