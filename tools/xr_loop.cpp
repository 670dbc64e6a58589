#include "tools/xr_loop.h"

#include "base/atomic_file.h"
#include "input/hid/fake_backend.h"
#include "input/mapping.h"
#include "render/presenter.h"
#include "render/model/stereo.h"
#include "render/stereo_render.h"
#include "session/live_input.h"
#include "session/xr_hands.h"
#include "xr/controller_actions.h"
#include "xr/xr_session.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <nlohmann/json.hpp>

#include <algorithm>
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
    if (anchor.volumeScale != 1.0) doc["volume"]["scale"] = anchor.volumeScale;
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

std::size_t XrLoopResult::newImages() const {
    return static_cast<std::size_t>(std::count_if(rendered.begin(), rendered.end(), [](const XrFrameTiming& t) {
        return t.step == XrStep::ExactWhole || t.step == XrStep::Preview || t.submittedExact;
    }));
}

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
    XrFrameLoop loop(options.loop, options.stillness);
    // The eyes last submitted, sent again while nothing new is rendered (the exact frame in slices, a still
    // scene): the images and the views and fields of view they were rendered for.
    struct HeldEyes {
        std::array<std::vector<std::uint8_t>, 2> rgba8;
        std::array<glm::ivec2, 2> size{};
        std::array<FieldOfView, 2> fov{};
        std::array<TrackedView, 2> views{};
        bool any = false;
    } held;
    // The exact frame under way in slices: its eyes (fixed when it started), the left eye's image once done.
    struct ExactJob {
        std::array<TrackedEye, 2> eyes;
        std::array<TrackedView, 2> views;
        std::size_t eye = 0;
        std::array<Image, 2> images;
        std::array<double, 2> ms{};
        FrameTimings firstEye;
    };
    std::optional<ExactJob> job;
    auto hold = [&](const std::array<TrackedEye, 2>& eyes, const std::array<Image, 2>& images, const std::array<TrackedView, 2>& views) {
        for (std::size_t e = 0; e < 2; ++e) {
            held.rgba8[e] = toRgba8(images[e], background);
            held.size[e] = eyes[e].size;
            held.fov[e] = eyes[e].renderedFov;
            held.views[e] = views[e];
        }
        held.any = true;
        if (options.saveViews) saveViews(*options.saveViews, session.roomSpace(), session.recommendedSize(0), views, hands.anchor());
    };
    auto submitHeld = [&] {
        if (!held.any) return false;
        for (int eye = 0; eye < 2; ++eye) {
            const auto e = static_cast<std::size_t>(eye);
            session.submitEye(eye, held.rgba8[e], held.size[e], held.fov[e], held.views[e]);
        }
        return true;
    };
    const auto loopStart = std::chrono::steady_clock::now();
    auto msSince = [](std::chrono::steady_clock::time_point t) { return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count(); };
    bool exactSinceMotion = false;
    XrTime firstDisplayTime = 0, lastDisplayTime = 0;   // the frame before's, for the hands' time step
    while (session.pollEvents()) {
        if (mirror) glfwPollEvents();
        const bool quit = (mirror && mirror->shouldClose()) || quitRequested;
        const bool done = options.endAfterExact && exactSinceMotion;
        if (quit || done || (options.frameLimit && result.newImages() >= static_cast<std::size_t>(*options.frameLimit))) session.requestExit();
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
        const RoomAnchor anchorBefore = hands.anchor();
        const StepChanges changes = step.apply(hands.step(record.hands, dtSeconds), session.recommendedSize(0).y);
        record.anchor = hands.anchor();
        step.syncTo(renderer, loaded.tracts);
        const std::size_t index = result.framesStepped++;
        if (frame.shouldRender && frame.viewsValid) {
            record.views = frame.views;
            std::array<TrackedEye, 2> eyes = xrEyes(step.frame(), frame.views, hands.anchor(), result.recommendedSize);
            XrFrameInputs in;
            in.now = 1e-9 * static_cast<double>(frame.displayTime - firstDisplayTime);
            in.sceneMoved = changes.any() || !(hands.anchor() == anchorBefore);
            in.head = frame.views[0];
            in.precomputePending = renderer.precomputePending(eyes[0].frame);
            in.precomputeInputs = renderer.precomputeInputsVersion();
            in.recommendedSize = result.recommendedSize[0];
            const XrFrameDecision decision = loop.decide(in);
            if (decision.moved) exactSinceMotion = false;
            XrFrameTiming timing;
            timing.frame = index;
            timing.step = decision.step;
            timing.moved = decision.moved;
            timing.displayS = in.now;
            renderer.collectTimings();   // the times of this frame alone
            const auto workStart = std::chrono::steady_clock::now();
            if (decision.frame.precomputeBudgetMs > 0) renderer.advancePrecompute(decision.frame.precomputeBudgetMs);
            bool submitted = false, rendered = false;
            switch (decision.step) {
                case XrStep::ExactWhole: {   // both eyes rendered whole and submitted (exact quality: as a GPU does)
                    std::array<Image, 2> images;
                    for (int eye = 0; eye < 2; ++eye) {
                        const auto e = static_cast<std::size_t>(eye);
                        auto start = std::chrono::steady_clock::now();
                        images[e] = renderTrackedEye(renderer, eyes[e]);
                        session.submitEye(eye, toRgba8(images[e], background), eyes[e].size, eyes[e].renderedFov, frame.views[e]);
                        timing.eyeMs[e] = msSince(start);
                        if (eye == 0) timing.firstEye = renderer.collectTimings();
                    }
                    if (options.saveViews) saveViews(*options.saveViews, session.roomSpace(), session.recommendedSize(0), frame.views, hands.anchor());
                    timing.submittedExact = submitted = rendered = true;
                    break;
                }
                case XrStep::Preview: {   // both eyes at the preview size, without steps I, IV and V
                    std::array<TrackedEye, 2> previews = xrEyes(step.frame(), frame.views, hands.anchor(),
                                                                {loop.previewSize(result.recommendedSize[0]), loop.previewSize(result.recommendedSize[1])});
                    std::array<Image, 2> images;
                    for (std::size_t e = 0; e < 2; ++e) {
                        auto start = std::chrono::steady_clock::now();
                        const FrameDescription& f = previews[e].frame;
                        renderer.renderPreview(decidedFrame(f, FrameKind::Preview, f.size, decision.frame.rayStepScale, renderer.resolveStepMm(f.raycast)));
                        images[e] = cropImage(renderer.readImage(), previews[e].cropOrigin, previews[e].size);
                        timing.eyeMs[e] = msSince(start);
                        if (e == 0) timing.firstEye = renderer.collectTimings();
                    }
                    hold(previews, images, frame.views);
                    loop.previewSubmitted(decision, timing.eyeMs[0] + timing.eyeMs[1]);
                    submitted = submitHeld();
                    rendered = true;
                    break;
                }
                case XrStep::ExactSlice: {   // the next slices of one eye's exact frame; the held eyes meanwhile
                    if (decision.startExact || !job) job = ExactJob{eyes, frame.views, 0, {}, {}, {}};
                    const TrackedEye& eye = job->eyes[job->eye];
                    auto start = std::chrono::steady_clock::now();
                    const bool eyeDone = renderer.advanceExact(eye.frame, decision.frame.exactBudgetMs, decision.frame.exactSliceUnits);
                    if (eyeDone) job->images[job->eye] = cropImage(renderer.readImage(), eye.cropOrigin, eye.size);
                    job->ms[job->eye] += msSince(start);
                    if (job->eye == 0) for (const FrameTimings::Entry& p : renderer.collectTimings().passes) job->firstEye.passes.push_back(p);
                    if (eyeDone && ++job->eye == 2) {
                        hold(job->eyes, job->images, job->views);
                        loop.exactSubmitted();
                        timing.eyeMs = job->ms;
                        timing.firstEye = job->firstEye;
                        timing.submittedExact = true;
                        job.reset();
                    }
                    submitted = submitHeld();
                    break;
                }
                case XrStep::Hold: submitted = submitHeld(); break;
            }
            if (decision.step != XrStep::ExactSlice) job.reset();
            if (timing.submittedExact) exactSinceMotion = true;
            renderer.finish();
            timing.workMs = msSince(workStart);
            timing.wallS = 1e-3 * msSince(loopStart);
            if (submitted) result.rendered.push_back(timing);
            if (mirror && rendered) {   // the last eye's whole frame, fitted into the window
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
