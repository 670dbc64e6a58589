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
#include "tools/commands/view_xr.h"
#include "session/interaction.h"
#include "session/live_input.h"
#include "session/loaded_scene.h"
#include "session/removal_file.h"
#include "session/session_step.h"
#include "viewer/clearance_readout.h"
#include "viewer/ruler.h"
#include "viewer/slice_panel.h"
#include "viewer/view_layout.h"
#include "viewer/view_panels.h"
#include "viewer/view_sidebar.h"
#include "viewer/viewer_driver.h"
#include "base/error.h"
#include "base/log.h"
#include "input/hid/fake_backend.h"
#include "render/clip_mesh_overlay.h"
#include "render/image_texture.h"
#include "render/reference/surface_pick.h"
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
#include <fstream>

namespace curette::commands {

namespace {

// GLFW key for each input::Key (keyboard_mouse.h).
constexpr int kGlfwKeys[] = {GLFW_KEY_W, GLFW_KEY_A, GLFW_KEY_S, GLFW_KEY_D, GLFW_KEY_Q, GLFW_KEY_E, GLFW_KEY_UP, GLFW_KEY_DOWN,
                             GLFW_KEY_LEFT, GLFW_KEY_RIGHT, GLFW_KEY_PAGE_UP, GLFW_KEY_PAGE_DOWN, GLFW_KEY_TAB, GLFW_KEY_R,
                             GLFW_KEY_INSERT, GLFW_KEY_DELETE, GLFW_KEY_1, GLFW_KEY_2, GLFW_KEY_3, GLFW_KEY_4, GLFW_KEY_5,
                             GLFW_KEY_C, GLFW_KEY_F9, GLFW_KEY_P, GLFW_KEY_F12, GLFW_KEY_6, GLFW_KEY_I, GLFW_KEY_J, GLFW_KEY_K,
                             GLFW_KEY_L, GLFW_KEY_O, GLFW_KEY_LEFT_SHIFT, GLFW_KEY_B, GLFW_KEY_N,
                             GLFW_KEY_UNKNOWN, GLFW_KEY_UNKNOWN};   // Undo, Redo: Ctrl combinations (undoRedoKeys)
static_assert(std::size(kGlfwKeys) == static_cast<std::size_t>(input::Key::Count));

// Ctrl+Z -> Undo, Ctrl+Shift+Z or Ctrl+Y -> Redo, for a key pressed with `mods` (GLFW modifier bits).
std::uint64_t undoRedoKeys(int key, int mods) {
    if (!(mods & GLFW_MOD_CONTROL)) return 0;
    if (key == GLFW_KEY_Z) return input::KeyboardMouseState::keyBit((mods & GLFW_MOD_SHIFT) ? input::Key::Redo : input::Key::Undo);
    if (key == GLFW_KEY_Y) return input::KeyboardMouseState::keyBit(input::Key::Redo);
    return 0;
}

// Presses latched between frames: a key pressed and released while a slow frame renders still counts. The
// window's own keys (help, side bar, views) are latched apart: they are not scene input and are not recorded.
std::uint64_t latchedKeys = 0;
std::vector<int> latchedWindowKeys;
// Any event (a key, the mouse, the window resized or uncovered) since the last frame: the window is drawn again
// for a short while after one, and not at all while nothing happens.
bool windowEvent = true;
void latchKey(GLFWwindow*, int key, int, int action, int mods) {
    windowEvent = true;
    if (action != GLFW_PRESS) return;
    for (int k = 0; k < static_cast<int>(input::Key::Count); ++k)
        if (kGlfwKeys[k] == key && key != GLFW_KEY_UNKNOWN) latchedKeys |= std::uint64_t{1} << k;
    latchedKeys |= undoRedoKeys(key, mods);
    latchedWindowKeys.push_back(key);
}
void noteCursor(GLFWwindow*, double, double) { windowEvent = true; }
// Ctrl + left presses, latched like the keys: a click pressed and released between two polls still counts.
std::vector<glm::dvec2> latchedCtrlClicks;
void noteButton(GLFWwindow* w, int button, int action, int mods) {
    windowEvent = true;
    if (button == GLFW_MOUSE_BUTTON_LEFT && action == GLFW_PRESS && (mods & GLFW_MOD_CONTROL)) {
        glm::dvec2 at;
        glfwGetCursorPos(w, &at.x, &at.y);
        latchedCtrlClicks.push_back(at);
    }
}
void noteScroll(GLFWwindow*, double, double) { windowEvent = true; }
void noteRefresh(GLFWwindow*) { windowEvent = true; }
void noteSize(GLFWwindow*, int, int) { windowEvent = true; }

// How long the window keeps drawing after an event (Dear ImGui's hover and fade need a few frames).
constexpr double kRedrawAfterEventSeconds = 0.5;

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
    ClipMeshOverlay meshOverlay{};    // the clip meshes over the presented image ("show tools")
    ViewerReport report{};
    ClearanceReadout clearance{loaded};   // the selected tool's live distance to the protected structures
    SlicePanel slices{loaded, step.state()};   // axial, coronal, sagittal through the crosshair
    std::array<ImageTexture, 3> sliceTextures{};
    Ruler ruler{};
    bool slicesShown = false;             // the Slices tab is open (its images are made only then)
    bool measuring = false;               // M: clicks (Ctrl + click in the view, a click on a slice) place ruler points
    std::optional<glm::dvec2> viewClick{};   // a Ctrl + left click in the 3-D view this iteration (framebuffer pixels)
    std::unique_ptr<LiveRecording> recording{};
    std::size_t played = 0;           // --play: the recorded frames followed
    bool orbiting = false, dragging = false, stereoKeyWasDown = false, exportKeyWasDown = false;
    glm::dvec2 lastCursor{0.0};
    int screenshots = 0;
    double previous = glfwGetTime();
    std::deque<std::string> messages{};
    // The window's own state: not scene input, not recorded.
    bool sidebarOpen = true, helpOpen = false, developerTimings = false;
    OrbitCamera homeCamera{};             // Home puts the camera back here (the scene's)
    ViewLayout layout{};
    ViewRect markerRect{};
    double lastEvent = -1e9;
    std::unique_ptr<std::ofstream> frameLog{};   // --frame-log: one line per presented frame
    double started = glfwGetTime();
    double idleSeconds = 0;               // --play: stay this long after the last frame before the screenshot
    double playEndedAt = -1;
    std::string windowShot{};             // --play: the whole window, panels included (--window-shot)
    bool windowShotWritten = false;
    double settledAt = -1;                // when the view first settled: the exact image, the report current, nothing to do
    bool exportRequested = false;
    bool idle = false;                    // the last iteration had nothing to render
    bool renderedBefore = false;          // the last iteration rendered: its side bar was drawn before the new image
    bool welcomed = false;                // the window was drawn once before the first image was rendered

    void message(std::string m) {
        std::printf("%s\n", m.c_str());
        messages.push_back(std::move(m));
        if (messages.size() > 6) messages.pop_front();
    }

    FrameDescription& frame() { return step.frame(); }
    InteractionState& state() { return step.state(); }
    glm::vec4 background() const { return glm::vec4(loaded.scene.background); }
    bool keyDown(int key) { return !ImGui::GetIO().WantCaptureKeyboard && glfwGetKey(window.window(), key) == GLFW_PRESS; }

    void startRecording(const std::filesystem::path& path, double now) {
        recording = std::make_unique<LiveRecording>(path, std::filesystem::absolute(scenePath).string(), state(), live, now);
        message("recording the session to " + std::filesystem::absolute(path).string() + " (F9 stops)");
    }
    void stopRecording() {
        recording->finish();
        message("wrote the session " + std::filesystem::absolute(recording->path()).string() + " (" + std::to_string(recording->frames()) + " frames)");
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
    std::vector<SettingEdit> drawSidebar();
    void statusLines();
    void viewTab();
    void windowKeys(const Polled& p);
    bool renderAndPresent(const Polled& p, bool moved, bool& presented);
    void logPresent(double now, const char* event);
    void refreshReport(double now);
    void pickInView();
    void placePoint(glm::dvec3 world, double uncertaintyMm);
    void refreshSlices();
    void slicesTab();
    void drawRuler();
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
    glm::ivec2 windowPoints;
    glfwGetWindowSize(w, &windowPoints.x, &windowPoints.y);
    glm::ivec2 framebuffer = window.framebufferSize();
    double pixelsPerPoint = windowPoints.y > 0 ? static_cast<double>(framebuffer.y) / windowPoints.y : 1.0;
    // A window too narrow for the side bar and a view beside it shows the view alone.
    layout = viewLayout(framebuffer, pixelsPerPoint, sidebarOpen && framebuffer.x >= 2 * kMinSidebarPoints * pixelsPerPoint);
    p.framebuffer = layout.view.size;   // the image is rendered for the view, not the window

    // The camera: left drag orbits, the wheel zooms. It changes before input is applied, and the recorded
    // frame holds the camera the input was applied with.
    glm::dvec2 cursor;
    glfwGetCursorPos(w, &cursor.x, &cursor.y);
    glm::dvec2 delta = (cursor - lastCursor) * pixelsPerPoint;
    lastCursor = cursor;
    bool inView = layout.view.contains(cursor * pixelsPerPoint) || orbiting || dragging;
    bool left = inView && !io.WantCaptureMouse && glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    bool right = inView && !io.WantCaptureMouse && glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    // Shift + left drag turns the selected light instead (an input action, so sessions record it).
    bool shift = glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS || glfwGetKey(w, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
    // Ctrl + left click picks the first visible surface under the cursor (the crosshair, the ruler) instead.
    bool ctrl = glfwGetKey(w, GLFW_KEY_LEFT_CONTROL) == GLFW_PRESS || glfwGetKey(w, GLFW_KEY_RIGHT_CONTROL) == GLFW_PRESS;
    for (glm::dvec2 at : latchedCtrlClicks)
        if (layout.view.contains(at * pixelsPerPoint) && !io.WantCaptureMouse) viewClick = at * pixelsPerPoint;
    latchedCtrlClicks.clear();
    p.cameraBefore = frame().camera;
    if (left && orbiting && !shift && !ctrl) frame().camera.orbit(-0.4 * delta.x / pixelsPerPoint, 0.4 * delta.y / pixelsPerPoint);
    if (inView && !io.WantCaptureMouse && io.MouseWheel != 0) frame().camera.zoom(std::pow(0.9, io.MouseWheel));

    // Keyboard and mouse as the input pipeline sees them.
    if (!io.WantCaptureKeyboard) {
        p.keys.keys = latchedKeys;
        for (int k = 0; k < static_cast<int>(input::Key::Count); ++k)
            if (kGlfwKeys[k] != GLFW_KEY_UNKNOWN && glfwGetKey(w, kGlfwKeys[k]) == GLFW_PRESS) p.keys.keys |= std::uint64_t{1} << k;
        if (glfwGetKey(w, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS) p.keys.press(input::Key::Fine);
        // Undo and redo stay down while their keys are (one press, one step: the keyboard mapper acts on presses).
        int mods = (ctrl ? GLFW_MOD_CONTROL : 0) | (shift ? GLFW_MOD_SHIFT : 0);
        for (int key : {GLFW_KEY_Z, GLFW_KEY_Y})
            if (glfwGetKey(w, key) == GLFW_PRESS) p.keys.keys |= undoRedoKeys(key, mods);
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
            changes = step.apply(input.actions, p.framebuffer.y, drawSidebar(), "<panel>");
        } catch (const InputError& e) {   // a panel value the scene reader refuses: said, not applied
            messages.push_back(e.what());
        }
    } else if (played < play->frames.size()) {
        step.follow(play->frames[played], loaded.scene.file.parent_path(), play->file.string() + " line " + std::to_string(played + 2));
        ++played;
    }
    if (play) drawSidebar();   // shown as live; a played session's edits come from its file
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

// The status at the top of the side bar: what is on screen, what is being computed, recording, messages.
void ViewWindow::statusLines() {
    if (!renderer.showsAnImage()) ImGui::TextWrapped("preparing the first image: the labels, shaders and the clip maps");
    ImGui::Text("%s", shadingModeName(frame().shading));
    tooltip("the shading mode: keys 1-6 choose one, C the next");
    ImGui::SameLine();
    ImGui::TextColored(viewer.shownExact ? ImVec4(0.4f, 1, 0.4f, 1) : ImVec4(1, 0.8f, 0.3f, 1), "%s", viewer.shownExact ? "FULL QUALITY" : "PREVIEW");
    tooltip("PREVIEW: a quick image while something moves; FULL QUALITY: the exact image, ambient occlusion exact under the carve");
    const float bar = ImGui::GetContentRegionAvail().x;
    if (*renderer.exactProgressLabel()) {   // the exact frame in slices (the preview stays on screen meanwhile)
        ImGui::TextWrapped("computing: %s", renderer.exactProgressLabel());
        char text[32];
        std::snprintf(text, sizeof text, "%.0f %%", 100 * renderer.exactProgress());
        ImGui::ProgressBar(static_cast<float>(renderer.exactProgress()), ImVec2(bar, 0), text);
    }
    if (renderer.labelFieldPending()) {   // built before anything is drawn (a new scene, a label style edit)
        ImGui::TextWrapped("computing: %s", Renderer::labelFieldProgressLabel());
        char text[32];
        std::snprintf(text, sizeof text, "%.0f %%", 100 * renderer.labelFieldProgress());
        ImGui::ProgressBar(static_cast<float>(renderer.labelFieldProgress()), ImVec2(bar, 0), text);
        tooltip("the labels' smoothed colours, computed once per label style; the image follows when done");
    }
    if (int maps = renderer.clipMapsToDraw(frame()); maps > 1) {   // a mesh an iteration
        ImGui::TextWrapped("computing: %s (%d tools to go)", Renderer::clipMapsProgressLabel(), maps);
        tooltip("each tool's depth maps, drawn once per shape and size");
    }
    if (renderer.precomputePending(frame())) {
        ImGui::TextWrapped("computing: %s", Renderer::precomputeProgressLabel());
        char text[32];
        std::snprintf(text, sizeof text, "%.0f %%", 100 * renderer.precomputeProgress());
        ImGui::ProgressBar(static_cast<float>(renderer.precomputeProgress()), ImVec2(bar, 0), text);
        tooltip("ambient occlusion of every voxel, computed once per transfer function; shaded without it until done");
    }
    if (clearance.applies()) {
        int selected = live.pipeline().keyboardSelection();
        if (std::optional<plan::Clearance> c = clearance.of(state(), selected)) {
            ImVec4 colour = c->mm <= 0 ? ImVec4(1, 0.3f, 0.3f, 1) : ImVec4(0.85f, 0.85f, 0.85f, 1);
            ImGui::TextColored(colour, "\"%s\" to protected: %s%.1f mm", state().meshes[static_cast<std::size_t>(selected)].name.c_str(),
                               c->mm > 0 ? ">= " : "", c->mm);
            if (ImGui::IsItemHovered())
                ImGui::SetTooltip("the selected tool's surface to the nearest protected structure, live: the gap lies in [%.1f, %.1f] mm.\n"
                                  "The plan's margins (from what is removed) follow once the tools are still.", c->mm, c->mm + c->uncertaintyMm);
        } else if (selected >= 0 && selected < static_cast<int>(state().meshes.size())) {
            note("distance to protected structures: preparing");
        }
    }
    if (recording) ImGui::TextColored(ImVec4(1, 0.3f, 0.3f, 1), "REC %zu frames (F9 stops)", recording->frames());
    for (const std::string& m : messages) ImGui::TextWrapped("%s", m.c_str());
}

// Standard views, stereo, resolution, the devices and who holds which mesh, the developer's timings.
void ViewWindow::viewTab() {
    const InteractionState& s = state();
    if (ImGui::Button("Home")) frame().camera = homeCamera;
    tooltip("the scene's view (Home key)");
    static const char* const kLetters[] = {"A", "P", "L", "R", "S", "I"};
    for (int v = 0; v < static_cast<int>(StandardView::Count); ++v) {
        ImGui::SameLine();
        if (ImGui::Button(kLetters[v])) frame().camera = viewedFrom(frame().camera, static_cast<StandardView>(v));
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("view from %s", standardViewName(static_cast<StandardView>(v)));
    }
    ImGui::Text("stereo: %s (F3)", stereoModeName(viewer.stereo));
    float scale = static_cast<float>(viewer.renderScale);
    if (ImGui::SliderFloat("resolution", &scale, 0.25f, 1.0f)) viewer.renderScale = scale;
    tooltip("the full-quality image's size as a share of the view's: lower is faster");
    if (ImGui::Checkbox("full quality every frame", &exactEveryFrame)) viewer.loop.setQuality(exactEveryFrame ? ViewQuality::Exact : ViewQuality::Adaptive);
    tooltip("no previews: every frame exact, however long it takes (a GPU's default)");
    auto meshLabel = [&](int index) {
        return index >= 0 && index < static_cast<int>(s.meshes.size()) ? "\"" + s.meshes[static_cast<std::size_t>(index)].name + "\"" : std::string("no mesh");
    };
    ImGui::Separator();
    ImGui::TextDisabled("devices");
    const input::Mapper& mapper = live.pipeline().mapper();
    for (std::size_t b = 0; b < mapper.config().bindings.size(); ++b) {
        const input::DeviceBinding& binding = mapper.config().bindings[b];
        int device = mapper.boundDevice(static_cast<int>(b));
        if (device < 0) continue;
        std::string product;
        for (const auto& d : live.devices().devices())
            if (d->info.id == device) product = d->info.product;
        ImGui::TextWrapped("%s (%s) holds %s", binding.family.c_str(), product.c_str(), meshLabel(mapper.heldMesh(static_cast<int>(b))).c_str());
    }
    ImGui::Text("keyboard holds %s (Tab: next)", meshLabel(live.pipeline().keyboardSelection()).c_str());
    ImGui::Text("light %d of %zu (O: next)", s.selectedLight + 1, s.lights.size());
    ImGui::Checkbox("developer timings", &developerTimings);
    tooltip("the time of each pass of the frame plan (docs/architecture.md)");
    if (developerTimings) {
        ImGui::Text("frame %.1f ms, AO %.1f ms, %dx%d", viewer.lastFrameMs, viewer.lastTimings.ambientOcclusionMs(), renderer.outputSize().x,
                    renderer.outputSize().y);
        for (const FrameTimings::Entry& e : viewer.lastTimings.passes) ImGui::Text("  %-20s %8.1f ms", passInfo(e.pass).name, e.ms);
        ImGui::Text("report %.0f ms", report.ms());
    }
}

// The side bar (viewer/view_layout.h): the status, then tabs for the plan, the tools and settings, the view.
// Returns the settings panels' edits.
std::vector<SettingEdit> ViewWindow::drawSidebar() {
    std::vector<SettingEdit> edits;
    drawHelpWindow(&helpOpen, layout.view);
    if (layout.sidebar.area() == 0) return edits;
    ImGui::SetNextWindowPos(ImVec2(static_cast<float>(layout.sidebar.origin.x), static_cast<float>(layout.sidebar.origin.y)));
    ImGui::SetNextWindowSize(ImVec2(static_cast<float>(layout.sidebar.size.x), static_cast<float>(layout.sidebar.size.y)));
    const ImGuiWindowFlags fixed = ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                                   ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoBringToFrontOnFocus;
    ImGui::Begin("side bar", nullptr, fixed);
    ImGui::PushItemWidth(-ImGui::GetContentRegionAvail().x * 0.45f);   // labels keep the right part of the bar
    statusLines();
    if (ImGui::SmallButton("help (F1)")) helpOpen = true;
    ImGui::SameLine();
    if (ImGui::SmallButton("fold (F2)")) sidebarOpen = false;
    if (ImGui::BeginTabBar("tabs")) {
        if (ImGui::BeginTabItem("Plan")) {
            if (const std::optional<plan::Report>& r = report.report()) drawPlanTable(*r, report.current(renderer.clipMeshes(), state()));
            else note("the report follows once the tools are still");
            if (ImGui::Button("write the plan (F5)")) exportRequested = true;
            tooltip("the report, the removed region and the exports, into a new folder beside where curette was started");
            drawTractLegend(state());
            ImGui::EndTabItem();
        }
        slicesShown = false;
        if (ImGui::BeginTabItem("Slices")) {
            slicesShown = true;
            slicesTab();
            ImGui::EndTabItem();
        }
        if (ImGui::BeginTabItem("Tools & settings")) {
            edits = panels.draw(state(), frame().camera, live.pipeline());
            ImGui::EndTabItem();
        }
        if (ImGui::BeginTabItem("View")) {
            viewTab();
            ImGui::EndTabItem();
        }
        ImGui::EndTabBar();
    }
    ImGui::PopItemWidth();
    ImGui::End();
    return edits;
}

// The window's own keys: help, the side bar, Home.
void ViewWindow::windowKeys(const Polled&) {
    bool typing = ImGui::GetIO().WantCaptureKeyboard;
    for (int key : latchedWindowKeys) {
        if (key == GLFW_KEY_F1 || (!typing && (key == GLFW_KEY_H || key == GLFW_KEY_SLASH))) helpOpen = !helpOpen;
        if (key == GLFW_KEY_ESCAPE) helpOpen = false, ruler.clear();
        if (key == GLFW_KEY_M && !typing) {
            measuring = !measuring;
            if (!measuring) ruler.clear();
        }
        if (key == GLFW_KEY_F2) sidebarOpen = !sidebarOpen;
        if (key == GLFW_KEY_HOME && !typing) frame().camera = homeCamera;
        if (key == GLFW_KEY_F5) exportRequested = true;
    }
    latchedWindowKeys.clear();
}

void ViewWindow::logPresent(double now, const char* event) {
    if (!frameLog) return;
    *frameLog << "{\"t\": " << now - started << ", \"event\": \"" << event << "\", \"exact\": " << (viewer.shownExact ? "true" : "false")
              << ", \"progress\": " << renderer.exactProgress() << ", \"work\": \"" << renderer.exactProgressLabel() << "\"}\n";
    frameLog->flush();
}

// The viewer's iteration (shared with bench view), then the screenshot (P, F12) and the image presented into the
// view. `presented`: whether the window is to be drawn this iteration (a new image, or an event shortly before).
bool ViewWindow::renderAndPresent(const Polled& p, bool moved, bool& presented) {
    bool stereoKeyDown = keyDown(GLFW_KEY_F3);
    if (stereoKeyDown && !stereoKeyWasDown) viewer.stereo = nextStereoMode(viewer.stereo);
    stereoKeyWasDown = stereoKeyDown;
    ViewerIteration it = stepViewer(viewer, renderer, step, loaded.tracts, p.framebuffer, p.now, moved, background());
    idle = it.decision.render == FrameKind::None && it.decision.precomputeBudgetMs == 0;
    bool stereo = viewer.stereo != StereoMode::Off;
    if (state().screenshot) {
        std::filesystem::path name = std::filesystem::absolute("curette-screenshot-" + std::to_string(++screenshots) + ".png");
        try {
            writePng(name, stereo ? viewer.stereoView.image() : renderer.readImage(), background());
            message("saved the view to " + name.string());
        } catch (const std::exception& e) {
            message(std::string("could not save the screenshot: ") + e.what());
        }
    }
    // The side bar is laid out before the image is rendered, so an iteration after a render draws once more:
    // the status then says what the image on screen is (FULL QUALITY, not the PREVIEW before it).
    presented = it.rendered || renderedBefore || p.now - lastEvent < kRedrawAfterEventSeconds || (play && playEndedAt < 0);   // a played session: until its last image
    renderedBefore = it.rendered;
    if (!presented) return true;
    if (!renderer.showsAnImage() && !stereo) {   // no image yet (the label field is being built): the side bar alone
        presenter.clear(window.framebufferSize(), background());
        return true;
    }
    presenter.present(stereo ? viewer.stereoView.texture() : renderer.outputTexture(), layout.view.origin, layout.view.size,
                      window.framebufferSize(), background());
    if (play && played == play->frames.size() && viewer.shownExact && playEndedAt < 0) {   // the last frame, exact
        playEndedAt = p.now;
        std::vector<std::uint8_t> whole = window.readBackBuffer();
        glm::ivec2 fb = window.framebufferSize();
        std::vector<std::uint8_t> view(static_cast<std::size_t>(layout.view.size.x) * layout.view.size.y * 4);
        for (int y = 0; y < layout.view.size.y; ++y)
            std::copy_n(whole.data() + (static_cast<std::size_t>(y + layout.view.origin.y) * fb.x + layout.view.origin.x) * 4,
                        static_cast<std::size_t>(layout.view.size.x) * 4, view.data() + static_cast<std::size_t>(y) * layout.view.size.x * 4);
        writePngRgba8(playScreenshot, layout.view.size.x, layout.view.size.y, view);
        std::printf("played %zu frames of %s; wrote %s (%dx%d)\n", played, play->file.c_str(), playScreenshot.c_str(), layout.view.size.x,
                    layout.view.size.y);
        std::printf("layout: window %dx%d, view %dx%d at %d,%d, side bar %dx%d at %d,%d, marker %dx%d at %d,%d\n", fb.x, fb.y,
                    layout.view.size.x, layout.view.size.y, layout.view.origin.x, layout.view.origin.y, layout.sidebar.size.x,
                    layout.sidebar.size.y, layout.sidebar.origin.x, layout.sidebar.origin.y, markerRect.size.x, markerRect.size.y,
                    markerRect.origin.x, markerRect.origin.y);
    }
    // The clip meshes over the image in the view (not in stereo), the keyboard's mesh highlighted; after the played
    // session's screenshot above, which is the renderer's image alone.
    if (!stereo && state().clipMeshDisplay.show.value_or(true))
        meshOverlay.draw(renderer.clipMeshes(), frame(), state().clipMeshDisplay.display,
                         std::min(live.pipeline().keyboardSelection(), renderer.clipMeshes().count() - 1), layout.view.origin, layout.view.size,
                         window.framebufferSize());
    return true;
}

// The removal report once the meshes and the settings it reads are still; F5 (or the button) writes it and the
// plan's exports, computing the report first when it is not there yet.
void ViewWindow::refreshReport(double now) {
    report.refresh(reporter, renderer.clipMeshes(), state(), now);
    if (exportRequested) message(report.exportPlan(reporter, renderer.clipMeshes(), state(), fileNameTimestamp()));
    exportRequested = false;
}

// A Ctrl + click in the 3-D view: the first visible surface under the cursor (the CPU twin of the image's ray,
// render/reference/surface_pick.h) becomes the crosshair and, when measuring, a ruler point.
void ViewWindow::pickInView() {
    if (!viewClick) return;
    glm::dvec2 at = *viewClick - glm::dvec2(layout.view.origin);
    viewClick.reset();
    FrameDescription shown = frame();
    shown.size = layout.view.size;
    const double stepMm = renderer.resolveStepMm(shown.raycast);
    std::optional<glm::dvec3> hit = reference::pickFirstVisible(loaded.volume, state().transferFunction, shown, stepMm,
                                                                glm::ivec2(glm::floor(at)), plan::insideAnyMesh(state().posedMeshes()));
    if (!hit) {
        message("nothing visible under the cursor");
        return;
    }
    placePoint(*hit, 0.5 * stepMm);
}

// A picked point: the slices go through it; when measuring it is also the ruler's next point.
void ViewWindow::placePoint(glm::dvec3 world, double uncertaintyMm) {
    slices.setCrosshair(world);
    if (!measuring) return;
    ruler.place({world, uncertaintyMm});
    if (std::optional<RulerLength> l = ruler.length()) {
        char text[64];
        std::snprintf(text, sizeof text, "ruler: %.1f mm (+-%.1f)", l->mm, l->uncertaintyMm);
        message(text);
    }
}

void ViewWindow::refreshSlices() {
    slices.takeRemovedRegion(report.computedCount(), reporter);
    if (slices.update(state(), live.pipeline().keyboardSelection()))
        for (SliceAxis a : kSliceAxes) sliceTextures[static_cast<std::size_t>(a)].update(slices.image(a).image);
}

// The slices tab: the three views one under another (the wheel scrolls a slice, a click moves the crosshair
// there and, when measuring, places a ruler point), the ruler.
void ViewWindow::slicesTab() {
    if (ImGui::Checkbox("measure (M)", &measuring) && !measuring) ruler.clear();
    tooltip("a ruler: Ctrl + click two points in the 3-D view (on the first visible surface) or click them on a slice");
    if (std::optional<RulerLength> l = ruler.length()) {
        ImGui::SameLine();
        ImGui::Text("%.1f mm (+-%.1f)", l->mm, l->uncertaintyMm);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("from (%.1f, %.1f, %.1f) to (%.1f, %.1f, %.1f) RAS mm; each point within %.2f / %.2f mm of where it was picked",
                              ruler.first()->world.x, ruler.first()->world.y, ruler.first()->world.z, ruler.second()->world.x,
                              ruler.second()->world.y, ruler.second()->world.z, ruler.first()->uncertaintyMm, ruler.second()->uncertaintyMm);
    } else if (measuring) {
        ImGui::SameLine();
        ImGui::TextDisabled(ruler.first() ? "pick the second point" : "pick the first point");
    }
    ImGui::BeginChild("slices", ImVec2(0, 0), false, ImGuiWindowFlags_NoScrollWithMouse);
    std::optional<glm::dvec3> clicked = slices.draw({sliceTextures[0].name(), sliceTextures[1].name(), sliceTextures[2].name()},
                                                    ImGui::GetContentRegionAvail().x);
    ImGui::EndChild();
    // A slice pixel is the scan's smallest spacing: the point lies within half a pixel diagonal of the click.
    if (clicked) placePoint(*clicked, 0.5 * std::sqrt(2.0) * slices.image(SliceAxis::Axial).plane.pixelMm);
}

// The ruler in the 3-D view: its points projected with the camera of the image, the length beside the line.
void ViewWindow::drawRuler() {
    if (!ruler.first()) return;
    const glm::dmat4 viewProjection = frame().camera.viewProjection(layout.view.size);
    auto onScreen = [&](glm::dvec3 world) -> std::optional<ImVec2> {
        glm::dvec4 clip = viewProjection * glm::dvec4(world, 1.0);
        if (clip.w <= 0) return std::nullopt;
        glm::dvec2 ndc = glm::dvec2(clip) / clip.w;
        return ImVec2(static_cast<float>(layout.view.origin.x + 0.5 * (ndc.x + 1) * layout.view.size.x),
                      static_cast<float>(layout.view.origin.y + 0.5 * (1 - ndc.y) * layout.view.size.y));
    };
    ImDrawList* draw = ImGui::GetBackgroundDrawList();
    const ImU32 colour = IM_COL32(255, 230, 80, 255);
    std::optional<ImVec2> a = onScreen(ruler.first()->world);
    std::optional<ImVec2> b = ruler.second() ? onScreen(ruler.second()->world) : std::nullopt;
    if (a) draw->AddCircleFilled(*a, 4, colour);
    if (b) draw->AddCircleFilled(*b, 4, colour);
    if (a && b) {
        draw->AddLine(*a, *b, colour, 2);
        char text[32];
        std::snprintf(text, sizeof text, "%.1f mm", ruler.length()->mm);
        draw->AddText(ImVec2(0.5f * (a->x + b->x) + 6, 0.5f * (a->y + b->y) - 16), colour, text);
    }
}

bool ViewWindow::iterate() {
    Polled p = poll();
    if (windowEvent) lastEvent = p.now, windowEvent = false;
    windowKeys(p);
    pickInView();
    InputFrame input;
    StepChanges changes = applyInput(p, input);
    bool cameraMoving = !(frame().camera == p.cameraBefore);
    record(p, input);
    markerRect = drawOrientationMarker(frame().camera, layout.view);
    drawRuler();
    ImGui::Render();
    if (!welcomed) {   // the first image of a scene takes seconds here: the window and the side bar come first
        presenter.clear(window.framebufferSize(), background());
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        window.swapBuffers();
        logPresent(p.now, "preparing");
        welcomed = true;
        return true;
    }
    bool presented = false;
    if (p.framebuffer.x > 0 && p.framebuffer.y > 0) {
        if (!renderAndPresent(p, changes.any() || cameraMoving, presented)) return false;
        refreshReport(p.now);
        if (slicesShown) refreshSlices();   // uploaded before the side bar's draw data is rendered below
    }
    state().screenshot = false;
    if (presented) {
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        // The window as a user sees it once the played session has ended: the iteration after the last
        // image, whose side bar describes that image.
        if (playEndedAt >= 0 && playEndedAt < p.now && !windowShot.empty() && !windowShotWritten) {
            glm::ivec2 fb = window.framebufferSize();
            writePngRgba8(windowShot, fb.x, fb.y, window.readBackBuffer());
            std::printf("wrote the window to %s\n", windowShot.c_str());
            windowShotWritten = true;
        }
        window.swapBuffers();
        logPresent(p.now, !renderer.showsAnImage() ? "preparing" : viewer.shownExact ? "exact" : "preview");
    }
    if (presented && !play) settledAt = -1;   // live: each settling is logged
    if (settledAt < 0 && (!play || playEndedAt >= 0) && viewer.shownExact && report.current(renderer.clipMeshes(), state()) && idle) {
        settledAt = p.now;
        logPresent(p.now, "settled");
    }
    // A played session ends after its last image, or with --idle-seconds that long after the view settled.
    if (playEndedAt >= 0 && (windowShot.empty() || windowShotWritten) && (idleSeconds == 0 || (settledAt >= 0 && p.now - settledAt >= idleSeconds))) {
        logPresent(p.now, "exit");
        return false;
    }
    // At most 120 frames a second while something happens; idle, a slower poll (devices are drained each
    // iteration) and nothing drawn.
    double period = presented || !idle ? 1.0 / 120.0 : 1.0 / 30.0;
    double spare = period - (glfwGetTime() - p.now);
    if (spare > 0) glfwWaitEventsTimeout(spare);
    return true;
}

int view(const CommandLine& cl) {
    if (cl.flag("xr")) return viewXr(cl);
    for (const char* option : {"frames", "save-views"})
        if (cl.value(option)) throw InputError("<command line>", std::string("--") + option, "together with --xr");
    if (cl.flag("headless")) throw InputError("<command line>", "--headless", "together with --xr");
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
    step.attachRemoval(loaded.volume.dims, loaded.volume.indexToWorld, play ? sessionStartRemoval(*play, loaded).get() : loaded.removal.get());
    ViewPanels panels(loaded, shippedPresetDirectory());
    LiveInput live(openHid(!cl.flag("no-devices") && !play), mapping, 40.0, 60.0);
    ViewWindow viewWindow{*window, loaded, scenePath, renderer, step, panels, live, play, cl.valueOr("screenshot", "curette-play.png"),
                          ViewerState(loopSettings), loopSettings.quality == ViewQuality::Exact, Presenter(),
                          CarveReporter(loaded, renderer.geometry(), programVersion())};
    if (auto path = cl.value("record")) viewWindow.startRecording(*path, glfwGetTime());
    viewWindow.homeCamera = step.frame().camera;
    if (auto log = cl.value("frame-log")) {
        viewWindow.frameLog = std::make_unique<std::ofstream>(*log);
        if (!*viewWindow.frameLog) throw InputError("<command line>", "--frame-log", "a file that can be written", "\"" + *log + "\"");
    }
    if (auto idle = cl.value("idle-seconds")) viewWindow.idleSeconds = CommandLine::parseDouble("idle-seconds", *idle, 0, 3600);
    viewWindow.windowShot = cl.valueOr("window-shot", "");
    if ((cl.value("idle-seconds") || cl.value("window-shot")) && !play)
        throw InputError("<command line>", cl.value("idle-seconds") ? "--idle-seconds" : "--window-shot", "together with --play F (the session to play)");

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;
    glfwSetKeyCallback(window->window(), latchKey);   // ImGui chains to these
    glfwSetCursorPosCallback(window->window(), noteCursor);
    glfwSetMouseButtonCallback(window->window(), noteButton);
    glfwSetScrollCallback(window->window(), noteScroll);
    glfwSetWindowRefreshCallback(window->window(), noteRefresh);
    glfwSetFramebufferSizeCallback(window->window(), noteSize);
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
              {"screenshot", true, "with --play: the PNG of the 3-D view after the last frame (default curette-play.png)"},
              {"window-shot", true, "with --play: also the PNG of the whole window, side bar included"},
              {"idle-seconds", true, "with --play: stay this long after the view has settled (exact, nothing to do) before exiting"},
              {"frame-log", true, "write one JSON line per frame drawn to the window (and one when the view settles)"},
              {"xr", false, "in a head-mounted display through OpenXR (the active runtime; tools/commands/view_xr.cpp); --size is then the mirror window's"},
              {"frames", true, "with --xr: end the session after N rendered frames", "N"},
              {"headless", false, "with --xr: no window; a headless EGL context bound through XR_MNDX_egl_enable (where the runtime offers it)"},
              {"save-views", true, "with --xr: write the last rendered frame's eye views (the JSON render --xr-views reads)", "F.json"}}},
            &view};
}

}  // namespace curette::commands
