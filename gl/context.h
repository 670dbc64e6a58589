#pragma once
// One interface for the two ways curette gets a GL 4.5 core context: headless (EGL on Mesa's surfaceless
// platform, llvmpipe on machines without a GPU; the default for everything but the viewer) and windowed
// (GLFW). GL calls are loaded through libepoxy, which serves both.

#include <glm/glm.hpp>

#include <memory>
#include <string>

struct GLFWwindow;

namespace curette::gl {

struct ContextInfo {
    std::string vendor, renderer, version, glslVersion;
    int max3DTextureSize = 0;
    int maxTextureSize = 0;
    int maxComputeWorkGroupCount[3] = {0, 0, 0};
    bool timerQueries = false;
    bool softwareRenderer = false;   // llvmpipe/softpipe: timer queries do not time compute work
};

class Context {
public:
    virtual ~Context() = default;
    virtual void makeCurrent() = 0;
    const ContextInfo& info() const { return info_; }

protected:
    // Checks GL 4.5 core + compute shaders on the current context and fills info_; throws SystemError that
    // says which requirement the driver lacks.
    void checkRequirementsAndQuery();
    // Routes GL debug output to the log (debug builds, or CURETTE_GL_DEBUG=1).
    void installDebugOutput();
    ContextInfo info_;
};

// Headless EGL context with no surface (render into our own framebuffers/images).
std::unique_ptr<Context> createHeadlessContext();

class WindowContext : public Context {
public:
    ~WindowContext() override;
    void makeCurrent() override;
    GLFWwindow* window() const { return window_; }
    glm::ivec2 framebufferSize() const;
    void swapBuffers();
    bool shouldClose() const;

private:
    friend std::unique_ptr<WindowContext> createWindowContext(const std::string&, glm::ivec2);
    GLFWwindow* window_ = nullptr;
};

// Opens a window with a GL 4.5 core context (needs a display). Throws SystemError when there is none.
std::unique_ptr<WindowContext> createWindowContext(const std::string& title, glm::ivec2 size);

// True when a display is reachable for GLFW (DISPLAY or WAYLAND_DISPLAY set).
bool displayAvailable();

}  // namespace curette::gl
