// curette view --scene S: the interactive viewer. Left drag orbits, the wheel zooms; the selected clip mesh
// moves with W/A/S/D/Q/E (camera frame), rotates with the arrow keys and PgUp/PgDn, and follows a right
// drag in the view plane; Tab selects the next mesh; 1-5 pick the shading; P saves a screenshot. The frame
// is re-rendered only when something it depends on changed, at reduced resolution while dragging
// (llvmpipe renders on the CPU).
#include "app/command_line.h"
#include "app/commands/commands.h"
#include "app/loaded_scene.h"
#include "base/error.h"
#include "render/gl/program.h"
#include "render/renderer.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include <glm/gtc/quaternion.hpp>

#include <chrono>
#include <cstdio>

namespace curette::commands {

namespace {

struct ViewerState {
    FrameDescription frame;
    bool orbiting = false, dragging = false;
    glm::dvec2 lastCursor{0};
    double renderScale = 1.0;   // resolution while idle
    double dragScale = 0.5;     // resolution while the mouse drags
    bool dirty = true;
    int screenshots = 0;
    int selectedMesh = 0;
    double translationMmPerSecond = 40.0, rotationDegPerSecond = 60.0;
};

const ShadingMode kModes[] = {ShadingMode::Solid, ShadingMode::Phong, ShadingMode::Lao, ShadingMode::Cao, ShadingMode::Dos};

}  // namespace

int view(const Arguments& args) {
    CommandLine cl(args, {{"scene", true, "scene file (JSON)"}, {"size", true, "window size WxH (default 1024x768)"}});
    glm::ivec2 windowSize = CommandLine::parseSize("size", cl.valueOr("size", "1024x768"));
    std::string scenePath = cl.required("scene");
    LoadedScene loaded = loadSceneWithVolume(scenePath);

    auto window = gl::createWindowContext("curette - " + scenePath, windowSize);
    Renderer renderer(*window, loaded.volume, loaded.scene.transferFunction);
    configureRenderer(loaded, renderer);
    gl::Program present = gl::Program::graphics("present.vert", "present.frag");
    gl::VertexArray emptyVertexArray = gl::createVertexArray();
    clip::ClipMeshSet& meshes = renderer.clipMeshes();

    ViewerState state;
    state.frame = initialFrame(loaded.scene, renderer.geometry());

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;
    ImGui_ImplGlfw_InitForOpenGL(window->window(), true);
    ImGui_ImplOpenGL3_Init("#version 450");

    double lastFrameMs = 0, lastAmbientMs = 0;
    auto previous = std::chrono::steady_clock::now();
    while (!window->shouldClose()) {
        glfwPollEvents();
        auto now = std::chrono::steady_clock::now();
        double dt = std::min(0.1, std::chrono::duration<double>(now - previous).count());
        previous = now;
        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        ImGuiIO& io = ImGui::GetIO();
        GLFWwindow* w = window->window();

        // Mouse: left drag orbits, right drag moves the selected mesh in the view plane, the wheel zooms.
        glm::dvec2 cursor;
        glfwGetCursorPos(w, &cursor.x, &cursor.y);
        glm::dvec2 delta = cursor - state.lastCursor;
        state.lastCursor = cursor;
        bool left = !io.WantCaptureMouse && glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
        bool right = !io.WantCaptureMouse && glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
        if (left && state.orbiting && delta != glm::dvec2(0)) {
            state.frame.camera.orbit(-0.4 * delta.x, 0.4 * delta.y);
            state.dirty = true;
        }
        bool hasMesh = meshes.count() > 0;
        state.selectedMesh = hasMesh ? state.selectedMesh % meshes.count() : 0;
        clip::RigidPose pose = hasMesh ? meshes.pose(state.selectedMesh) : clip::RigidPose{};
        const OrbitCamera& camera = state.frame.camera;
        if (right && state.dragging && hasMesh && delta != glm::dvec2(0)) {
            double mmPerPixel = 2.0 * camera.distanceMm * std::tan(glm::radians(camera.fovYDeg) / 2.0) / std::max(1, window->framebufferSize().y);
            pose.position += mmPerPixel * (delta.x * camera.right() - delta.y * camera.up());
        }
        if ((state.orbiting || state.dragging) && !left && !right) state.dirty = true;  // back to full resolution
        state.orbiting = left;
        state.dragging = right;
        if (!io.WantCaptureMouse && io.MouseWheel != 0) {
            state.frame.camera.zoom(std::pow(0.9, io.MouseWheel));
            state.dirty = true;
        }

        // Keys: the selected mesh moves in the camera frame at a set speed.
        bool screenshot = false;
        if (!io.WantCaptureKeyboard) {
            auto held = [&](int key) { return glfwGetKey(w, key) == GLFW_PRESS ? 1.0 : 0.0; };
            glm::dvec3 move = (held(GLFW_KEY_D) - held(GLFW_KEY_A)) * camera.right() + (held(GLFW_KEY_E) - held(GLFW_KEY_Q)) * camera.up() +
                              (held(GLFW_KEY_W) - held(GLFW_KEY_S)) * camera.forward();
            glm::dvec3 spin = (held(GLFW_KEY_UP) - held(GLFW_KEY_DOWN)) * camera.right() +
                              (held(GLFW_KEY_RIGHT) - held(GLFW_KEY_LEFT)) * camera.up() +
                              (held(GLFW_KEY_PAGE_UP) - held(GLFW_KEY_PAGE_DOWN)) * camera.forward();
            if (hasMesh) {
                pose.position += move * state.translationMmPerSecond * dt;
                if (glm::length(spin) > 0)
                    pose.orientation = glm::normalize(glm::angleAxis(glm::radians(state.rotationDegPerSecond * dt), glm::normalize(spin)) * pose.orientation);
            }
            if (ImGui::IsKeyPressed(GLFW_KEY_TAB) && hasMesh) state.selectedMesh = (state.selectedMesh + 1) % meshes.count();
            for (int m = 0; m < 5; ++m)
                if (ImGui::IsKeyPressed(GLFW_KEY_1 + m) && state.frame.shading != kModes[m]) state.frame.shading = kModes[m], state.dirty = true;
            screenshot = ImGui::IsKeyPressed(GLFW_KEY_P);
        }
        if (hasMesh && !(pose == meshes.pose(state.selectedMesh))) {
            meshes.setPose(state.selectedMesh, pose);
            state.dirty = true;
        }

        // Overlay: frame time, AO time, the shading and the selected mesh.
        ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_Always);
        ImGui::Begin("curette", nullptr, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove);
        ImGui::Text("frame %.1f ms (AO %.1f ms) | %s | %dx%d", lastFrameMs, lastAmbientMs, shadingModeName(state.frame.shading),
                    renderer.outputSize().x, renderer.outputSize().y);
        int mode = 0;
        for (int m = 0; m < 5; ++m)
            if (kModes[m] == state.frame.shading) mode = m;
        const char* names[] = {"solid", "phong", "lao", "cao", "dos"};
        if (ImGui::Combo("shading (1-5)", &mode, names, 5)) state.frame.shading = kModes[mode], state.dirty = true;
        if (hasMesh) {
            ImGui::Text("mesh %d/%d \"%s\" at (%.0f, %.0f, %.0f) mm (Tab: next)", state.selectedMesh + 1, meshes.count(),
                        meshes.name(state.selectedMesh).c_str(), pose.position.x, pose.position.y, pose.position.z);
        }
        float scale = static_cast<float>(state.renderScale);
        if (ImGui::SliderFloat("resolution", &scale, 0.25f, 1.0f)) state.renderScale = scale, state.dirty = true;
        ImGui::TextUnformatted("left drag: orbit  wheel: zoom  right drag / WASDQE / arrows: move mesh  P: screenshot");
        ImGui::End();
        ImGui::Render();

        glm::ivec2 framebuffer = window->framebufferSize();
        if (framebuffer.x > 0 && framebuffer.y > 0) {
            bool interacting = state.orbiting || state.dragging;
            double scaleNow = interacting ? std::min(state.dragScale, state.renderScale) : state.renderScale;
            glm::ivec2 renderSize = glm::max(glm::ivec2(glm::dvec2(framebuffer) * scaleNow), glm::ivec2(1));
            if (renderSize != state.frame.size) state.frame.size = renderSize, state.dirty = true;
            if (state.dirty) {
                auto start = std::chrono::steady_clock::now();
                renderer.render(state.frame);
                glFinish();
                lastFrameMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
                lastAmbientMs = 0;
                for (const auto& [pass, ms] : renderer.collectTimings())
                    if (pass.rfind("IV", 0) == 0 || pass.rfind("V ", 0) == 0 || pass.rfind("I ", 0) == 0) lastAmbientMs += ms;
                state.dirty = false;
            }
            if (screenshot) {
                std::string name = "curette-screenshot-" + std::to_string(++state.screenshots) + ".png";
                writePng(name, renderer.readImage(), glm::vec4(loaded.scene.background));
                std::printf("saved %s\n", name.c_str());
            }
            glBindFramebuffer(GL_FRAMEBUFFER, 0);
            glViewport(0, 0, framebuffer.x, framebuffer.y);
            glDisable(GL_DEPTH_TEST);
            glBindTextureUnit(0, renderer.outputTexture());
            present.set("background", glm::vec4(loaded.scene.background));
            present.use();
            glBindVertexArray(emptyVertexArray.name());
            glDrawArrays(GL_TRIANGLES, 0, 3);
        }
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        window->swapBuffers();
    }
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    return 0;
}

}  // namespace curette::commands
