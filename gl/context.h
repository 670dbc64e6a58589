#pragma once
// One interface for the ways curette gets a GL 4.5 core context: headless (the default for everything but
// the viewer) and windowed (GLFW). GL calls are loaded through libepoxy, which serves both.
//
// Headless contexts come from one of two EGL platforms (docs/subsystems.md, "GL contexts"):
//  - the device platform (EGL_EXT_device_enumeration + EGL_EXT_platform_device): the GPUs EGL lists, each
//    opened directly; the only headless path on NVIDIA's and AMD's vendor drivers. Mesa lists its software
//    renderer here too (EGL_MESA_device_software), and every DRM device it drives;
//  - Mesa's surfaceless platform (EGL_MESA_platform_surfaceless): Mesa picks the GPU (llvmpipe without one).
// --gpu (GpuChoice, parsed by tools/command_line.h) picks one; the automatic choice is the first hardware
// device of the device platform, else the surfaceless platform, else the first (software) device.

#include <glm/glm.hpp>

#include <memory>
#include <string>
#include <vector>

struct GLFWwindow;

namespace curette::gl {

struct ContextInfo {
    std::string vendor, renderer, version, glslVersion;
    int max3DTextureSize = 0;
    int maxTextureSize = 0;
    int maxComputeWorkGroupCount[3] = {0, 0, 0};
    bool timerQueries = false;
    bool softwareRenderer = false;   // llvmpipe/softpipe: timer queries do not time compute work
    std::string platform;            // how the context was made: "EGL device 0 (EGL_EXT_platform_device)", ...
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

// What --gpu asks for.
struct GpuChoice {
    enum class Kind {
        Automatic,     // the first hardware device, else surfaceless, else the first device
        Device,        // device `device` of the device platform, nothing else
        Software,      // a CPU renderer: the device platform's software device, else surfaceless if it is one
        Surfaceless,   // Mesa's surfaceless platform (what curette used before the device platform)
    };
    Kind kind = Kind::Automatic;
    int device = -1;
    bool operator==(const GpuChoice&) const = default;
};

// One device of EGL_EXT_device_enumeration, as far as EGL describes it without a GL context.
struct EglDevice {
    int index = 0;
    std::string extensions;      // the device's own extension string
    bool software = false;       // EGL_MESA_device_software: a CPU renderer (llvmpipe)
    std::string drmDeviceFile;   // EGL_EXT_device_drm: /dev/dri/cardN (empty without)
    std::string drmRenderNode;   // EGL_EXT_device_drm_render_node: /dev/dri/renderDN (empty without)
    std::string eglVendor;       // of the device's display, once initialised (e.g. "Mesa Project", "NVIDIA")
    std::string eglVersion;
    std::string driver;          // EGL_MESA_query_driver's name (e.g. "swrast", "radeonsi"); empty without
    std::string problem;         // why its display cannot be initialised; empty when it can
    bool hasExtension(const std::string& name) const;
    std::string describe() const;   // one line: "0: software, Mesa Project (EGL 1.5), driver swrast"
};

struct EglPlatforms {
    std::string clientExtensions;
    bool surfaceless = false;         // EGL_MESA_platform_surfaceless
    bool deviceEnumeration = false;   // EGL_EXT_device_enumeration and EGL_EXT_device_query
    bool platformDevice = false;      // EGL_EXT_platform_device
    std::vector<EglDevice> devices;   // empty unless the device extensions exist
    bool hasClientExtension(const std::string& name) const;
    // "devices: 0: software, Mesa Project ...; 1: ..." or why there are none, for lists and errors.
    std::string describeDevices() const;
};

// What EGL offers in this process: the client extensions and every device (each device's display is
// initialised to read its vendor, and left initialised: EGL hands every caller the same display of a device,
// and eglTerminate is not reference-counted, so terminating it would break a live context on it).
EglPlatforms queryEglPlatforms();

enum class HeadlessPlatform { Surfaceless, Device };

// One way to make a headless context: a platform and, for the device platform, the device index.
struct HeadlessTarget {
    HeadlessPlatform platform = HeadlessPlatform::Surfaceless;
    int device = -1;
    bool operator==(const HeadlessTarget&) const = default;
    std::string describe() const;   // "EGL device 0 (EGL_EXT_platform_device)", "EGL surfaceless (...)"
};

// The targets to try, in order, for `choice` on `platforms` (a pure function, tested on made-up device
// lists). Automatic: the first hardware device, then surfaceless, then the first device; Device: that one;
// Software: the first software device, else surfaceless (whose renderer must then be a software one);
// Surfaceless: that platform. Throws SystemError naming what exists when nothing fits the choice (a device
// index out of range, a platform this EGL lacks).
std::vector<HeadlessTarget> headlessTargets(const EglPlatforms& platforms, const GpuChoice& choice);

// A headless EGL context with no surface (render into our own framebuffers/images) on the GPU `choice`
// names. Automatic tries each target in turn (logging why one failed); an explicit choice tries only its own.
std::unique_ptr<Context> createHeadlessContext(const GpuChoice& choice = {});

class WindowContext : public Context {
public:
    ~WindowContext() override;
    void makeCurrent() override;
    GLFWwindow* window() const { return window_; }
    glm::ivec2 framebufferSize() const;
    void swapBuffers();
    bool shouldClose() const;
    // The window's back buffer as 8-bit RGBA, row 0 at the top (what the next swapBuffers shows): for
    // screenshots of the window itself (`view --play`).
    std::vector<std::uint8_t> readBackBuffer() const;

private:
    friend std::unique_ptr<WindowContext> createWindowContext(const std::string&, glm::ivec2);
    GLFWwindow* window_ = nullptr;
};

// Opens a window with a GL 4.5 core context (needs a display). Throws SystemError when there is none.
std::unique_ptr<WindowContext> createWindowContext(const std::string& title, glm::ivec2 size);

// True when a display is reachable for GLFW (DISPLAY or WAYLAND_DISPLAY set).
bool displayAvailable();

}  // namespace curette::gl
