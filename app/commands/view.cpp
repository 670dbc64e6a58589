// curette view --scene S: the interactive viewer. Left drag orbits, the wheel zooms, P saves a screenshot,
// 1/2 switch shading. The frame is re-rendered only when something it depends on changed, and at reduced
// resolution while the mouse is dragging (llvmpipe renders on the CPU).
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

#include <chrono>
#include <cstdio>

namespace curette::commands {

namespace {

struct ViewerState {
    FrameDescription frame;
    bool dragging = false;
    glm::dvec2 lastCursor{0};
    double renderScale = 1.0;       // resolution while idle
    double dragScale = 0.5;         // resolution while dragging
    bool dirty = true;
    int screenshots = 0;
};

}  // namespace

int view(const Arguments& args) {
    CommandLine cl(args, {{"scene", true, "scene file (JSON)"}, {"size", true, "window size WxH (default 1024x768)"}});
    glm::ivec2 windowSize = CommandLine::parseSize("size", cl.valueOr("size", "1024x768"));
    std::string scenePath = cl.required("scene");
    LoadedScene loaded = loadSceneWithVolume(scenePath);

    auto window = gl::createWindowContext("curette - " + scenePath, windowSize);
    Renderer renderer(*window, loaded.volume, loaded.scene.transferFunction);
    configureRenderer(loaded.scene, renderer);
    gl::Program present = gl::Program::graphics("present.vert", "present.frag");
    gl::VertexArray emptyVertexArray = gl::createVertexArray();

    ViewerState state;
    state.frame = initialFrame(loaded.scene, renderer.geometry());
    glfwSetWindowUserPointer(window->window(), &state);

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;
    ImGui_ImplGlfw_InitForOpenGL(window->window(), true);
    ImGui_ImplOpenGL3_Init("#version 450");

    double lastFrameMs = 0;
    const char* shadingNames[] = {"solid", "phong"};
    while (!window->shouldClose()) {
        glfwPollEvents();
        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        ImGuiIO& io = ImGui::GetIO();

        // Camera: orbit with the left button, zoom with the wheel (unless the overlay has the mouse).
        if (!io.WantCaptureMouse) {
            bool down = glfwGetMouseButton(window->window(), GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
            glm::dvec2 cursor;
            glfwGetCursorPos(window->window(), &cursor.x, &cursor.y);
            if (down && state.dragging) {
                glm::dvec2 delta = cursor - state.lastCursor;
                if (delta != glm::dvec2(0)) {
                    state.frame.camera.orbit(-0.4 * delta.x, 0.4 * delta.y);
                    state.dirty = true;
                }
            }
            if (state.dragging && !down) state.dirty = true;  // back to full resolution
            state.dragging = down;
            state.lastCursor = cursor;
            if (io.MouseWheel != 0) {
                state.frame.camera.zoom(std::pow(0.9, io.MouseWheel));
                state.dirty = true;
            }
        }
        if (!io.WantCaptureKeyboard) {
            if (ImGui::IsKeyPressed(GLFW_KEY_1)) state.frame.shading = ShadingMode::Solid, state.dirty = true;
            if (ImGui::IsKeyPressed(GLFW_KEY_2)) state.frame.shading = ShadingMode::Phong, state.dirty = true;
        }
        bool screenshot = !io.WantCaptureKeyboard && ImGui::IsKeyPressed(GLFW_KEY_P);

        // Overlay: one line with the frame time, and the settings.
        ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_Always);
        ImGui::Begin("curette", nullptr, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove);
        ImGui::Text("frame %.1f ms | %s | %dx%d", lastFrameMs, shadingModeName(state.frame.shading),
                    renderer.outputSize().x, renderer.outputSize().y);
        int shading = state.frame.shading == ShadingMode::Phong ? 1 : 0;
        if (ImGui::Combo("shading (1/2)", &shading, shadingNames, 2)) {
            state.frame.shading = shading ? ShadingMode::Phong : ShadingMode::Solid;
            state.dirty = true;
        }
        float scale = static_cast<float>(state.renderScale);
        if (ImGui::SliderFloat("resolution", &scale, 0.25f, 1.0f)) state.renderScale = scale, state.dirty = true;
        ImGui::TextUnformatted("drag: orbit  wheel: zoom  P: screenshot");
        ImGui::End();
        ImGui::Render();

        glm::ivec2 framebuffer = window->framebufferSize();
        if (framebuffer.x > 0 && framebuffer.y > 0) {
            double scaleNow = state.dragging ? std::min(state.dragScale, state.renderScale) : state.renderScale;
            glm::ivec2 renderSize = glm::max(glm::ivec2(glm::dvec2(framebuffer) * scaleNow), glm::ivec2(1));
            if (renderSize != state.frame.size) state.frame.size = renderSize, state.dirty = true;
            if (state.dirty) {
                auto start = std::chrono::steady_clock::now();
                renderer.render(state.frame);
                glFinish();
                lastFrameMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
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
