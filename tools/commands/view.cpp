// curette view --scene S: the interactive viewer. Devices (hidapi: gamepads, SpaceMice) and the keyboard and
// mouse drive the clip meshes through the mapping (input/mapping.h); left drag orbits the camera and the wheel
// zooms; Shift + left drag or I/J/K/L turns the selected light (O: the next one), as recorded input actions. F9 (or a mapped button) starts and stops recording a session; P or F12 saves a screenshot. The overlay
// shows which device holds which mesh, the shading, and the time of every pass of the frame plan. What to render
// each frame is the frame loop's decision (viewer/view_frame_loop.h), run by the viewer's iteration
// (viewer/viewer_driver.h, the same one `curette bench view` runs headless): with
// --quality adaptive (the default on a software renderer) previews at reduced resolution while something moves
// and the exact frame once the motion has settled; step I runs in slices with a preview meanwhile, so the window
// never freezes for it; the overlay says PREVIEW or EXACT and shows step I's progress. The plan panel shows the removal report (removed mL,
// the structures and bundles the carve touches or must spare, margins; protected ones in red when touched),
// of the state on screen (its TF and bundles too), updated 0.2 s after the meshes or those settings stop changing; F5 writes the report and the plan's exports (session/carve_report.h).
// The settings panels (viewer/view_panels.h) turn every widget into a setting edit that the session step
// applies with the frame's actions (and a recording records). --play F plays a recorded session in this
// loop instead of live input (its poses, lights and edits through SessionStep::follow), then writes a
// screenshot of the window without the overlay (--screenshot) and exits.
#include "session/carve_report.h"
#include "tools/command_line.h"
#include "tools/commands/commands.h"
#include "session/interaction.h"
#include "session/live_input.h"
#include "session/loaded_scene.h"
#include "session/session_step.h"
#include "viewer/view_panels.h"
#include "viewer/viewer_driver.h"
#include "base/error.h"
#include "base/log.h"
#include "input/hid/fake_backend.h"
#include "render/presenter.h"
#include "render/renderer.h"
#include "render/stereo_render.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <deque>

namespace curette::commands {

namespace {

// GLFW key for each input::Key (keyboard_mouse.h).
constexpr int kGlfwKeys[] = {GLFW_KEY_W, GLFW_KEY_A, GLFW_KEY_S, GLFW_KEY_D, GLFW_KEY_Q, GLFW_KEY_E, GLFW_KEY_UP, GLFW_KEY_DOWN,
                             GLFW_KEY_LEFT, GLFW_KEY_RIGHT, GLFW_KEY_PAGE_UP, GLFW_KEY_PAGE_DOWN, GLFW_KEY_TAB, GLFW_KEY_R,
                             GLFW_KEY_INSERT, GLFW_KEY_DELETE, GLFW_KEY_1, GLFW_KEY_2, GLFW_KEY_3, GLFW_KEY_4, GLFW_KEY_5,
                             GLFW_KEY_C, GLFW_KEY_F9, GLFW_KEY_P, GLFW_KEY_F12, GLFW_KEY_6, GLFW_KEY_I, GLFW_KEY_J, GLFW_KEY_K,
                             GLFW_KEY_L, GLFW_KEY_O};
static_assert(std::size(kGlfwKeys) == static_cast<std::size_t>(input::Key::Count));

// Presses latched between frames: a key pressed and released while a slow frame renders still counts.
std::uint32_t latchedKeys = 0;
void latchKey(GLFWwindow*, int key, int, int action, int) {
    if (action != GLFW_PRESS) return;
    for (int k = 0; k < static_cast<int>(input::Key::Count); ++k)
        if (kGlfwKeys[k] == key) latchedKeys |= 1u << k;
}

std::unique_ptr<input::HidBackend> openHid(bool wanted) {
    if (wanted) {
        try {
            return input::createHidapiBackend();
        } catch (const SystemError& e) {
            log::warn(std::string("no HID devices: ") + e.what() + "; keyboard and mouse only");
        }
    }
    return std::make_unique<input::FakeHidBackend>(std::make_shared<input::FakeHidBackend::Ports>());  // no devices
}

// Ctrl-C or a terminal closing ends the loop like closing the window, so a recording is finished and kept.
volatile std::sig_atomic_t quitRequested = 0;
void requestQuit(int) { quitRequested = 1; }

// The current time for a file name (ISO 8601 with '-' for ':', which some file systems refuse).
std::string fileNameTimestamp() {
    std::string stamp = currentTimeIso8601();
    for (char& c : stamp)
        if (c == ':') c = '-';
    return stamp;
}

std::string sessionFileName() { return "curette-session-" + fileNameTimestamp() + ".jsonl"; }

// The window around the viewer's iteration (viewer/viewer_driver.h): what view() sets up, and what only a
// window has between frames (the cursor, the overlay's messages, the recording, the keys pressed once).
struct ViewWindow {
    gl::WindowContext& window;
    const LoadedScene& loaded;
    std::string scenePath;
    Renderer& renderer;
    SessionStep& step;
    ViewPanels& panels;
    LiveInput& live;
    const std::optional<Session>& play;
    std::string playScreenshot;       // --play: the PNG written after the last frame
    ViewerState viewer;
    bool exactEveryFrame;
    Presenter presenter;
    CarveReporter reporter;
    ViewerReport report{};
    std::unique_ptr<LiveRecording> recording{};
    std::size_t played = 0;           // --play: the recorded frames followed
    bool orbiting = false, dragging = false, stereoKeyWasDown = false, exportKeyWasDown = false;
    glm::dvec2 lastCursor{0.0};
    int screenshots = 0;
    double previous = glfwGetTime();
    std::deque<std::string> messages{};

    FrameDescription& frame() { return step.frame(); }
    InteractionState& state() { return step.state(); }
    glm::vec4 background() const { return glm::vec4(loaded.scene.background); }
    bool keyDown(int key) { return !ImGui::GetIO().WantCaptureKeyboard && glfwGetKey(window.window(), key) == GLFW_PRESS; }

    void startRecording(const std::filesystem::path& path, double now) {
        recording = std::make_unique<LiveRecording>(path, std::filesystem::absolute(scenePath).string(), state(), live, now);
        std::printf("recording %s\n", path.c_str());
    }
    void stopRecording() {
        recording->finish();
        std::printf("wrote %s (%zu frames)\n", recording->path().c_str(), recording->frames());
        recording.reset();
    }

    // One frame of the window; false when the loop is to end (a played session's last image is written).
    bool iterate();

private:
    struct Polled {
        double now = 0, dt = 0;
        glm::ivec2 framebuffer{0};
        OrbitCamera cameraBefore;
        input::KeyboardMouseState keys;
    };
    Polled poll();
    StepChanges applyInput(const Polled& p, InputFrame& input);
    void record(const Polled& p, const InputFrame& input);
    void drawOverlay();
    bool renderAndPresent(const Polled& p, bool moved);
    void refreshReport(double now);
};

// Events, the camera and the keys of this frame.
ViewWindow::Polled ViewWindow::poll() {
    Polled p;
    glfwPollEvents();
    p.now = glfwGetTime();
    p.dt = std::min(0.1, p.now - previous);
    previous = p.now;
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    ImGuiIO& io = ImGui::GetIO();
    GLFWwindow* w = window.window();
    p.framebuffer = window.framebufferSize();
    glm::ivec2 windowPoints;
    glfwGetWindowSize(w, &windowPoints.x, &windowPoints.y);
    double pixelsPerPoint = windowPoints.y > 0 ? static_cast<double>(p.framebuffer.y) / windowPoints.y : 1.0;

    // The camera: left drag orbits, the wheel zooms. It changes before input is applied, and the recorded
    // frame holds the camera the input was applied with.
    glm::dvec2 cursor;
    glfwGetCursorPos(w, &cursor.x, &cursor.y);
    glm::dvec2 delta = (cursor - lastCursor) * pixelsPerPoint;
    lastCursor = cursor;
    bool left = !io.WantCaptureMouse && glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    bool right = !io.WantCaptureMouse && glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    // Shift + left drag turns the selected light instead (an input action, so sessions record it).
    bool shift = glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS || glfwGetKey(w, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
    p.cameraBefore = frame().camera;
    if (left && orbiting && !shift) frame().camera.orbit(-0.4 * delta.x / pixelsPerPoint, 0.4 * delta.y / pixelsPerPoint);
    if (!io.WantCaptureMouse && io.MouseWheel != 0) frame().camera.zoom(std::pow(0.9, io.MouseWheel));

    // Keyboard and mouse as the input pipeline sees them.
    if (!io.WantCaptureKeyboard) {
        p.keys.keys = latchedKeys;
        for (int k = 0; k < static_cast<int>(input::Key::Count); ++k)
            if (glfwGetKey(w, kGlfwKeys[k]) == GLFW_PRESS) p.keys.keys |= 1u << k;
    }
    latchedKeys = 0;
    if (right && dragging) p.keys.rightDragPixels = delta;
    if (left && orbiting && shift) p.keys.lightDragPixels = delta;
    orbiting = left;
    dragging = right;
    return p;
}

// Devices and keys -> actions -> the scene (the session step every command runs), or the played session's next
// frame. The mesh panel's hold requests of the frame before go in with this frame's input (and its recorded frame).
StepChanges ViewWindow::applyInput(const Polled& p, InputFrame& input) {
    input = live.step(p.now, p.keys, p.dt, static_cast<int>(state().meshes.size()), panels.takeHoldRequests());
    StepChanges changes;
    if (!play) {
        try {
            changes = step.apply(input.actions, p.framebuffer.y, panels.draw(state(), frame().camera, live.pipeline()));
        } catch (const InputError& e) {   // a panel value the scene reader refuses: said, not applied
            messages.push_back(e.what());
        }
    } else if (played < play->frames.size()) {
        step.follow(play->frames[played], loaded.scene.file.parent_path(), play->file.string() + " line " + std::to_string(played + 2));
        ++played;
    }
    for (std::string& m : panels.takeMessages()) messages.push_back(std::move(m));
    for (std::string& m : live.takeMessages()) {
        messages.push_back(std::move(m));
        if (messages.size() > 6) messages.pop_front();
    }
    return changes;
}

// F9 (or a mapped button) starts and stops recording; a recording takes the frame as input applied it.
void ViewWindow::record(const Polled& p, const InputFrame& input) {
    if (recording) {
        if (state().toggleRecording) stopRecording();
        else recording->addFrame(p.now, p.dt, p.framebuffer, frame().camera, state(), p.keys, input);
    } else if (state().toggleRecording) {
        startRecording(sessionFileName(), p.now);
    }
    state().toggleRecording = false;
}

// Overlay: timings, shading, who holds which mesh, recording, device messages, the removal report.
void ViewWindow::drawOverlay() {
    const InteractionState& s = state();
    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_Always);
    ImGui::Begin("curette", nullptr, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove);
    // Shading changes only through input (1-6, C, mapped buttons), so a session replays it from its reports.
    ImGui::Text("frame %.1f ms | AO %.1f ms | shading %s (1-6, C) | %dx%d | stereo %s (F3)", viewer.lastFrameMs,
                viewer.lastTimings.ambientOcclusionMs(), shadingModeName(frame().shading), renderer.outputSize().x, renderer.outputSize().y,
                stereoModeName(viewer.stereo));
    // What is on screen: the exact frame (CAO == LAO, full resolution) or a preview; step I's progress.
    ImGui::TextColored(viewer.shownExact ? ImVec4(0.4f, 1, 0.4f, 1) : ImVec4(1, 0.8f, 0.3f, 1), "%s", viewer.shownExact ? "EXACT" : "PREVIEW");
    ImGui::SameLine();
    if (ImGui::Checkbox("exact every frame", &exactEveryFrame)) viewer.loop.setQuality(exactEveryFrame ? ViewQuality::Exact : ViewQuality::Adaptive);
    if (renderer.exactProgress() > 0) {   // the exact frame in slices (the preview stays on screen meanwhile)
        ImGui::ProgressBar(static_cast<float>(renderer.exactProgress()), ImVec2(320, 0), "");
        ImGui::SameLine();
        ImGui::Text("exact frame %.0f %%", 100 * renderer.exactProgress());
    }
    if (renderer.precomputePending(frame())) {
        ImGui::ProgressBar(static_cast<float>(renderer.precomputeProgress()), ImVec2(320, 0), "");
        ImGui::SameLine();
        ImGui::Text("step I (LAO precompute) %.0f %%: shaded without AO until done", 100 * renderer.precomputeProgress());
    }
    for (const FrameTimings::Entry& e : viewer.lastTimings.passes) ImGui::Text("  %-22s %8.1f ms", passInfo(e.pass).name, e.ms);
    auto meshLabel = [&](int index) {
        return index >= 0 && index < static_cast<int>(s.meshes.size()) ? "mesh " + std::to_string(index) + " \"" + s.meshes[static_cast<std::size_t>(index)].name + "\""
                                                                      : std::string("no mesh");
    };
    const input::Mapper& mapper = live.pipeline().mapper();
    for (std::size_t b = 0; b < mapper.config().bindings.size(); ++b) {
        const input::DeviceBinding& binding = mapper.config().bindings[b];
        int device = mapper.boundDevice(static_cast<int>(b));
        if (device < 0) continue;
        std::string product;
        for (const auto& d : live.devices().devices())
            if (d->info.id == device) product = d->info.product;
        ImGui::Text("%s #%d (device %d, %s) -> %s", binding.family.c_str(), binding.index, device, product.c_str(),
                    meshLabel(mapper.heldMesh(static_cast<int>(b))).c_str());
    }
    ImGui::Text("keyboard -> %s (Tab: next)", meshLabel(live.pipeline().keyboardSelection()).c_str());
    if (recording) ImGui::TextColored(ImVec4(1, 0.3f, 0.3f, 1), "REC %s: %zu frames (F9 stops)", recording->path().c_str(), recording->frames());
    for (const std::string& m : messages) ImGui::TextWrapped("%s", m.c_str());
    if (const std::optional<plan::Report>& r = report.report()) {
        ImGui::Separator();
        ImGui::Text("removed %.2f +-%.2f mL%s (%.0f ms; F5 writes the plan)", r->removedMl, r->removedUncertaintyMl,
                    report.current(renderer.clipMeshes(), s) ? "" : " (updating)", report.ms());
        for (const plan::StructureRow& row : r->structures) {
            if (!row.touched && !row.isProtected) continue;
            ImVec4 colour = row.isProtected && row.touched ? ImVec4(1, 0.3f, 0.3f, 1) : ImVec4(0.85f, 0.85f, 0.85f, 1);
            ImGui::TextColored(colour, "  %-24s %7.3f +-%.3f mL %5.1f %%  %s %5.1f +-%.2f mm", row.name.c_str(), row.removedMl,
                               row.removedUncertaintyMl, 100 * row.share, row.touched ? "depth" : "margin",
                               row.touched ? row.intrusionDepthMm : row.marginMm,
                               row.touched ? row.intrusionUncertaintyMm : row.marginUncertaintyMm);
        }
        for (const plan::BundleRow& b : r->bundles) {
            ImVec4 colour = b.isProtected && b.cut ? ImVec4(1, 0.3f, 0.3f, 1) : ImVec4(0.85f, 0.85f, 0.85f, 1);
            ImGui::TextColored(colour, "  %-24s %5llu of %llu cut  %6.1f mm removed  margin %5.1f +-%.1f mm", b.name.c_str(),
                               static_cast<unsigned long long>(b.cut), static_cast<unsigned long long>(b.streamlines), b.removedLengthMm,
                               b.marginMm, b.marginUncertaintyMm);
        }
        for (const std::string& warning : r->warnings()) ImGui::TextColored(ImVec4(1, 0.3f, 0.3f, 1), "%s", warning.c_str());
    }
    float scale = static_cast<float>(viewer.renderScale);
    if (ImGui::SliderFloat("resolution", &scale, 0.25f, 1.0f)) viewer.renderScale = scale;
    ImGui::Text("light %d of %zu (O: next; I/J/K/L or Shift + left drag: turn it)", s.selectedLight + 1, s.lights.size());
    ImGui::TextUnformatted("left drag: orbit  wheel: zoom  WASDQE, arrows, PgUp/PgDn, right drag: move mesh\n"
                           "Tab: next mesh  R: reset  Ins/Del: add/remove  F9: record  P: screenshot  F3: stereo");
    ImGui::End();
    ImGui::Render();
}

// The viewer's iteration (shared with bench view), then the screenshot (P, F12) and the image presented. Returns
// false after a played session's last frame, exact, is written without the overlay.
bool ViewWindow::renderAndPresent(const Polled& p, bool moved) {
    bool stereoKeyDown = keyDown(GLFW_KEY_F3);
    if (stereoKeyDown && !stereoKeyWasDown) viewer.stereo = nextStereoMode(viewer.stereo);
    stereoKeyWasDown = stereoKeyDown;
    stepViewer(viewer, renderer, step, loaded.tracts, p.framebuffer, p.now, moved, background());
    bool stereo = viewer.stereo != StereoMode::Off;
    if (state().screenshot) {
        std::string name = "curette-screenshot-" + std::to_string(++screenshots) + ".png";
        writePng(name, stereo ? viewer.stereoView.image() : renderer.readImage(), background());
        std::printf("saved %s\n", name.c_str());
    }
    presenter.present(stereo ? viewer.stereoView.texture() : renderer.outputTexture(), p.framebuffer, background());
    if (play && played == play->frames.size() && viewer.shownExact) {   // the last frame, exact, without the overlay
        writePngRgba8(playScreenshot, p.framebuffer.x, p.framebuffer.y, window.readBackBuffer());
        std::printf("played %zu frames of %s; wrote %s (%dx%d)\n", played, play->file.c_str(), playScreenshot.c_str(), p.framebuffer.x,
                    p.framebuffer.y);
        return false;
    }
    return true;
}

// The removal report once the meshes and the settings it reads are still; F5 writes it and the plan's exports.
void ViewWindow::refreshReport(double now) {
    report.refresh(reporter, renderer.clipMeshes(), state(), now);
    bool exportKeyDown = keyDown(GLFW_KEY_F5);
    if (exportKeyDown && !exportKeyWasDown && report.report()) {
        messages.push_back(report.exportPlan(reporter, renderer.clipMeshes(), state(), fileNameTimestamp()));
        std::printf("%s\n", messages.back().c_str());
        if (messages.size() > 6) messages.pop_front();
    }
    exportKeyWasDown = exportKeyDown;
}

bool ViewWindow::iterate() {
    Polled p = poll();
    InputFrame input;
    StepChanges changes = applyInput(p, input);
    bool cameraMoving = !(frame().camera == p.cameraBefore);
    record(p, input);
    drawOverlay();
    if (p.framebuffer.x > 0 && p.framebuffer.y > 0) {
        if (!renderAndPresent(p, changes.any() || cameraMoving)) return false;
        refreshReport(p.now);
    }
    state().screenshot = false;
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    window.swapBuffers();
    // At most 120 frames a second when idle: devices are drained each frame, and nothing spins.
    double spare = 1.0 / 120.0 - (glfwGetTime() - p.now);
    if (spare > 0) glfwWaitEventsTimeout(spare);
    return true;
}

int view(const CommandLine& cl) {
    glm::ivec2 windowSize = CommandLine::parseSize("size", cl.valueOr("size", "1024x768"));
    std::optional<Session> play;
    if (auto p = cl.value("play")) play = readSession(*p, false);
    if (cl.value("screenshot") && !play) throw InputError("<command line>", "--screenshot", "together with --play F (the session to play)");
    std::string scenePath = play && !cl.value("scene") ? sessionScenePath(*play).string() : cl.required("scene");
    input::MappingConfig mapping = cl.value("mapping") ? input::loadMapping(*cl.value("mapping")) : input::defaultMapping();
    LoadedScene loaded = loadSceneWithVolume(scenePath);

    std::optional<ViewQuality> quality;
    if (auto q = cl.value("quality")) {
        quality = parseViewQuality(*q);
        if (!quality) throw InputError("<command line>", "--quality", "exact or adaptive", "\"" + *q + "\"");
    }
    auto window = gl::createWindowContext("curette - " + scenePath, windowSize);
    FrameLoopSettings loopSettings;
    // A played session is for its last image: exact every frame unless asked otherwise.
    loopSettings.quality = quality.value_or(play ? ViewQuality::Exact : defaultViewQuality(window->info().softwareRenderer));
    Renderer renderer(*window, loaded.volume, loaded.scene.transferFunction);
    configureRenderer(loaded, renderer);
    SessionStep step(play ? InteractionState::fromSessionStart(play->header, loaded.scene, loaded.scene.file.parent_path(), play->file.string())
                          : InteractionState::fromScene(loaded.scene),
                     initialFrame(loaded.scene, renderer.geometry()));
    ViewPanels panels(loaded, shippedPresetDirectory());
    LiveInput live(openHid(!cl.flag("no-devices") && !play), mapping, 40.0, 60.0);
    ViewWindow viewWindow{*window, loaded, scenePath, renderer, step, panels, live, play, cl.valueOr("screenshot", "curette-play.png"),
                          ViewerState(loopSettings), loopSettings.quality == ViewQuality::Exact, Presenter(),
                          CarveReporter(loaded, renderer.geometry(), programVersion())};
    if (auto path = cl.value("record")) viewWindow.startRecording(*path, glfwGetTime());

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;
    glfwSetKeyCallback(window->window(), latchKey);   // ImGui chains to it
    ImGui_ImplGlfw_InitForOpenGL(window->window(), true);
    ImGui_ImplOpenGL3_Init("#version 450");

    std::signal(SIGINT, requestQuit);
    std::signal(SIGTERM, requestQuit);
    viewWindow.previous = glfwGetTime();
    while (!window->shouldClose() && !quitRequested && viewWindow.iterate()) {}
    if (viewWindow.recording) viewWindow.stopRecording();
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    return 0;
}

}  // namespace

Command viewCommand() {
    return {{"view", "--scene S", "the interactive viewer: devices, keyboard and mouse, settings panels, the removal report; F9 records a session, --play F plays one",
             {{"scene", true, "scene file (JSON)"},
              {"size", true, "window size WxH (default 1024x768)", "WxH"},
              {"mapping", true, "device mapping JSON (default: the shipped assets/input/default_mapping.json)"},
              {"record", true, "record a session to this file from the start (F9 toggles recording too)"},
              {"no-devices", false, "keyboard and mouse only (do not open HID devices)"},
              {"quality", true, "exact|adaptive: previews while moving, exact when still (default: adaptive on a software renderer, exact on a GPU; --play: exact)", "exact|adaptive"},
              {"play", true, "play this recorded session in the viewer's loop instead of live input, then screenshot and exit"},
              {"screenshot", true, "with --play: the PNG of the window after the last frame (default curette-play.png)"}}},
            &view};
}

}  // namespace curette::commands
