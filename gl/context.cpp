#include "gl/context.h"

#include "base/error.h"
#include "base/log.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

// EGL_EXT_device_drm_render_node (epoxy's generated header predates it).
#ifndef EGL_DRM_RENDER_NODE_FILE_EXT
#define EGL_DRM_RENDER_NODE_FILE_EXT 0x3377
#endif

namespace curette::gl {

namespace {

std::string glString(GLenum name) {
    const GLubyte* s = glGetString(name);
    return s ? reinterpret_cast<const char*>(s) : "";
}

void GLAPIENTRY debugCallback(GLenum, GLenum type, GLuint, GLenum severity, GLsizei, const GLchar* message,
                              const void*) {
    if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
    std::string text = std::string("GL: ") + message;
    if (type == GL_DEBUG_TYPE_ERROR)
        log::error(text);
    else
        log::debug(text);
}

bool debugOutputRequested() {
#ifndef NDEBUG
    return true;
#else
    const char* env = std::getenv("CURETTE_GL_DEBUG");
    return env && std::strcmp(env, "0") != 0;
#endif
}

}  // namespace

void Context::checkRequirementsAndQuery() {
    info_.vendor = glString(GL_VENDOR);
    info_.renderer = glString(GL_RENDERER);
    info_.version = glString(GL_VERSION);
    info_.glslVersion = glString(GL_SHADING_LANGUAGE_VERSION);
    int version = epoxy_gl_version();
    if (version < 45)
        throw SystemError("the OpenGL driver offers " + info_.version + " (" + info_.renderer +
                          "); curette needs OpenGL 4.5 core. On Debian, install libgl1-mesa-dri (llvmpipe "
                          "provides 4.5 on the CPU)");
    if (!epoxy_has_gl_extension("GL_ARB_compute_shader") && version < 43)
        throw SystemError("the OpenGL driver (" + info_.renderer + ") has no compute shaders; curette needs them");
    glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &info_.max3DTextureSize);
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &info_.maxTextureSize);
    for (GLuint i = 0; i < 3; ++i) glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, i, &info_.maxComputeWorkGroupCount[i]);
    GLint bits = 0;
    glGetQueryiv(GL_TIME_ELAPSED, GL_QUERY_COUNTER_BITS, &bits);
    info_.timerQueries = bits > 0;
    info_.softwareRenderer = info_.renderer.find("llvmpipe") != std::string::npos ||
                             info_.renderer.find("softpipe") != std::string::npos;
    log::info("GL context: " + info_.renderer + ", " + info_.version);
}

void Context::installDebugOutput() {
    if (!debugOutputRequested()) return;
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(debugCallback, nullptr);
}

// ---- headless: EGL on the device platform or the surfaceless platform ------------------------------------

namespace {

std::string hex(EGLint value) {
    char text[16];
    std::snprintf(text, sizeof text, "%x", static_cast<unsigned>(value));
    return text;
}

std::string eglError() { return "error 0x" + hex(eglGetError()); }

// Whether the space-separated `list` holds `name` (a whole word, not a prefix of a longer one).
bool listHas(const std::string& list, const std::string& name) {
    std::size_t at = 0;
    while ((at = list.find(name, at)) != std::string::npos) {
        bool startsWord = at == 0 || list[at - 1] == ' ';
        std::size_t end = at + name.size();
        if (startsWord && (end == list.size() || list[end] == ' ')) return true;
        at = end;
    }
    return false;
}

std::string text(const char* s) { return s ? s : ""; }

// The devices of EGL_EXT_device_enumeration, in EGL's order (the index --gpu N names).
std::vector<EGLDeviceEXT> eglDeviceHandles() {
    EGLint count = 0;
    if (!eglQueryDevicesEXT(0, nullptr, &count) || count <= 0) return {};
    std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
    if (!eglQueryDevicesEXT(count, devices.data(), &count)) return {};
    devices.resize(static_cast<std::size_t>(count));
    return devices;
}

}  // namespace

bool EglDevice::hasExtension(const std::string& name) const { return listHas(extensions, name); }

std::string EglDevice::describe() const {
    std::string line = std::to_string(index) + ": " + (software ? "software" : "hardware");
    if (!eglVendor.empty()) line += ", " + eglVendor + " (EGL " + eglVersion + ")";
    if (!driver.empty()) line += ", driver " + driver;
    if (!drmRenderNode.empty()) line += ", " + drmRenderNode;
    else if (!drmDeviceFile.empty()) line += ", " + drmDeviceFile;
    if (!problem.empty()) line += " (cannot be opened: " + problem + ")";
    return line;
}

bool EglPlatforms::hasClientExtension(const std::string& name) const { return listHas(clientExtensions, name); }

std::string EglPlatforms::describeDevices() const {
    if (!deviceEnumeration || !platformDevice)
        return "no EGL device platform (EGL_EXT_device_enumeration, EGL_EXT_platform_device)";
    if (devices.empty()) return "the EGL device platform lists no devices";
    std::string list = "devices: ";
    for (const EglDevice& d : devices) list += (d.index ? "; " : "") + d.describe();
    return list;
}

EglPlatforms queryEglPlatforms() {
    EglPlatforms p;
    p.clientExtensions = text(eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS));
    p.surfaceless = p.hasClientExtension("EGL_MESA_platform_surfaceless");
    p.deviceEnumeration = (p.hasClientExtension("EGL_EXT_device_enumeration") && p.hasClientExtension("EGL_EXT_device_query")) ||
                          p.hasClientExtension("EGL_EXT_device_base");
    p.platformDevice = p.hasClientExtension("EGL_EXT_platform_device");
    if (!p.deviceEnumeration || !p.platformDevice) return p;
    std::vector<EGLDeviceEXT> handles = eglDeviceHandles();
    for (std::size_t i = 0; i < handles.size(); ++i) {
        EglDevice d;
        d.index = static_cast<int>(i);
        d.extensions = text(eglQueryDeviceStringEXT(handles[i], EGL_EXTENSIONS));
        d.software = d.hasExtension("EGL_MESA_device_software");
        if (d.hasExtension("EGL_EXT_device_drm")) d.drmDeviceFile = text(eglQueryDeviceStringEXT(handles[i], EGL_DRM_DEVICE_FILE_EXT));
        if (d.hasExtension("EGL_EXT_device_drm_render_node"))
            d.drmRenderNode = text(eglQueryDeviceStringEXT(handles[i], EGL_DRM_RENDER_NODE_FILE_EXT));
        EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, handles[i], nullptr);
        EGLint major = 0, minor = 0;
        if (display == EGL_NO_DISPLAY || !eglInitialize(display, &major, &minor)) {
            d.problem = "eglInitialize failed, " + eglError();
        } else {
            d.eglVendor = text(eglQueryString(display, EGL_VENDOR));
            d.eglVersion = std::to_string(major) + "." + std::to_string(minor);
            if (listHas(text(eglQueryString(display, EGL_EXTENSIONS)), "EGL_MESA_query_driver")) {
                auto driverName = reinterpret_cast<const char* (*)(EGLDisplay)>(eglGetProcAddress("eglGetDisplayDriverName"));
                if (driverName) d.driver = text(driverName(display));
            }
        }
        p.devices.push_back(std::move(d));
    }
    return p;
}

std::string HeadlessTarget::describe() const {
    return platform == HeadlessPlatform::Device ? "EGL device " + std::to_string(device) + " (EGL_EXT_platform_device)"
                                                : std::string("EGL surfaceless (EGL_MESA_platform_surfaceless)");
}

std::vector<HeadlessTarget> headlessTargets(const EglPlatforms& p, const GpuChoice& choice) {
    const bool deviceUsable = p.deviceEnumeration && p.platformDevice;
    const std::vector<EglDevice> none;
    const std::vector<EglDevice>& devices = deviceUsable ? p.devices : none;
    auto firstDevice = [&](bool software) -> const EglDevice* {
        for (const EglDevice& d : devices)
            if (d.software == software && d.problem.empty()) return &d;
        return nullptr;
    };
    const HeadlessTarget surfaceless{HeadlessPlatform::Surfaceless, -1};
    std::vector<HeadlessTarget> targets;
    switch (choice.kind) {
        case GpuChoice::Kind::Automatic:
            if (const EglDevice* d = firstDevice(false)) targets.push_back({HeadlessPlatform::Device, d->index});
            if (p.surfaceless) targets.push_back(surfaceless);
            if (const EglDevice* d = firstDevice(true)) targets.push_back({HeadlessPlatform::Device, d->index});
            if (targets.empty())
                throw SystemError("EGL offers no headless platform: neither a device (" + p.describeDevices() +
                                  ") nor Mesa's surfaceless platform; on Debian install libegl1 and libgl1-mesa-dri, or the GPU "
                                  "vendor's EGL driver");
            break;
        case GpuChoice::Kind::Device:
            if (choice.device < 0 || choice.device >= static_cast<int>(devices.size()))
                throw SystemError("there is no EGL device " + std::to_string(choice.device) + "; " + p.describeDevices());
            targets.push_back({HeadlessPlatform::Device, choice.device});
            break;
        case GpuChoice::Kind::Software:
            if (const EglDevice* d = firstDevice(true)) targets.push_back({HeadlessPlatform::Device, d->index});
            else if (p.surfaceless) targets.push_back(surfaceless);
            else throw SystemError("EGL offers no software renderer: no EGL_MESA_device_software device (" + p.describeDevices() +
                                   ") and no surfaceless platform; on Debian install libgl1-mesa-dri");
            break;
        case GpuChoice::Kind::Surfaceless:
            if (!p.surfaceless)
                throw SystemError("EGL has no surfaceless platform (EGL_MESA_platform_surfaceless: Mesa's); " + p.describeDevices());
            targets.push_back(surfaceless);
            break;
    }
    return targets;
}

namespace {

// The platform an initialised `display` belongs to, found by asking EGL for each platform's display (EGL
// hands out one display per platform and native display), not taken from what was asked for.
std::string platformOf(EGLDisplay display) {
    const std::string client = text(eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS));
    if (listHas(client, "EGL_EXT_platform_device")) {
        std::vector<EGLDeviceEXT> devices = eglDeviceHandles();
        for (std::size_t i = 0; i < devices.size(); ++i)
            if (eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr) == display)
                return HeadlessTarget{HeadlessPlatform::Device, static_cast<int>(i)}.describe();
    }
    if (listHas(client, "EGL_MESA_platform_surfaceless") &&
        eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr) == display)
        return HeadlessTarget{HeadlessPlatform::Surfaceless, -1}.describe();
    return "an EGL display of no platform curette knows";
}

class EglContext final : public Context {
public:
    explicit EglContext(HeadlessTarget target) {
        if (target.platform == HeadlessPlatform::Surfaceless) {
            display_ = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        } else {
            std::vector<EGLDeviceEXT> devices = eglDeviceHandles();
            if (target.device < 0 || target.device >= static_cast<int>(devices.size()))
                throw SystemError("there is no EGL device " + std::to_string(target.device));
            display_ = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[static_cast<std::size_t>(target.device)], nullptr);
        }
        const std::string where = target.describe();
        EGLint major = 0, minor = 0;
        if (display_ == EGL_NO_DISPLAY || !eglInitialize(display_, &major, &minor))
            throw SystemError("cannot initialise " + where + " (" + eglError() + ")");
        if (!eglBindAPI(EGL_OPENGL_API)) throw SystemError(where + " cannot bind the desktop OpenGL API");
        const std::string displayExtensions = text(eglQueryString(display_, EGL_EXTENSIONS));
        // Mesa and NVIDIA create contexts without a config and make them current without a surface; a driver
        // that cannot gets a config for a 1x1 pbuffer, the surface curette never draws to.
        const bool configless = listHas(displayExtensions, "EGL_KHR_no_config_context") || listHas(displayExtensions, "EGL_MESA_configless_context");
        const bool surfaceless = listHas(displayExtensions, "EGL_KHR_surfaceless_context");
        EGLConfig config = EGL_NO_CONFIG_KHR;
        if (!configless || !surfaceless) {
            const EGLint wanted[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_RED_SIZE, 8,
                                     EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_NONE};
            EGLint found = 0;
            if (!eglChooseConfig(display_, wanted, &config, 1, &found) || found < 1)
                throw SystemError(where + " has no EGL config for OpenGL with a pbuffer (" + eglError() + ")");
        }
        EGLint flags = debugOutputRequested() ? EGL_CONTEXT_OPENGL_DEBUG_BIT_KHR : 0;
        const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                     EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                     EGL_CONTEXT_FLAGS_KHR, flags, EGL_NONE};
        context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, attributes);
        if (context_ == EGL_NO_CONTEXT)
            throw SystemError(where + " cannot create an OpenGL 4.5 core context (" + eglError() +
                              "); curette needs OpenGL 4.5 with compute shaders");
        if (!surfaceless) {
            const EGLint size[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
            surface_ = eglCreatePbufferSurface(display_, config, size);
            if (surface_ == EGL_NO_SURFACE) {
                eglDestroyContext(display_, context_);
                throw SystemError(where + " can neither make a context current without a surface nor create a pbuffer (" + eglError() + ")");
            }
        }
        makeCurrent();
        info_.platform = platformOf(display_);
        checkRequirementsAndQuery();
        installDebugOutput();
    }
    ~EglContext() override {
        // Release only this context; another one (on another device, say) may be the current one. The display
        // stays initialised: see queryEglPlatforms.
        if (eglGetCurrentContext() == context_) eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (surface_ != EGL_NO_SURFACE) eglDestroySurface(display_, surface_);
        if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
    }
    void makeCurrent() override {
        if (!eglMakeCurrent(display_, surface_, surface_, context_)) throw SystemError("eglMakeCurrent failed (" + eglError() + ")");
    }

private:
    EGLDisplay display_ = EGL_NO_DISPLAY;
    EGLContext context_ = EGL_NO_CONTEXT;
    EGLSurface surface_ = EGL_NO_SURFACE;
};

}  // namespace

std::unique_ptr<Context> createHeadlessContext(const GpuChoice& choice) {
    std::vector<HeadlessTarget> targets = headlessTargets(queryEglPlatforms(), choice);
    std::string failures;
    for (const HeadlessTarget& target : targets) {
        try {
            auto context = std::make_unique<EglContext>(target);
            if (choice.kind == GpuChoice::Kind::Software && !context->info().softwareRenderer)
                throw SystemError(target.describe() + " renders on " + context->info().renderer +
                                  ", not on a software renderer (--gpu llvmpipe); set LIBGL_ALWAYS_SOFTWARE=1 for Mesa's");
            return context;
        } catch (const SystemError& e) {
            if (choice.kind != GpuChoice::Kind::Automatic) throw;
            log::warn(std::string("headless GL: ") + e.what() + (&target != &targets.back() ? "; trying the next platform" : ""));
            failures += std::string(failures.empty() ? "" : "; ") + e.what();
        }
    }
    throw SystemError("no headless OpenGL 4.5 context on any EGL platform: " + failures);
}

// ---- windowed: GLFW ---------------------------------------------------------------------------------------

bool displayAvailable() {
    const char* x = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    return (x && *x) || (wayland && *wayland);
}

WindowContext::~WindowContext() {
    if (window_) glfwDestroyWindow(window_);
    glfwTerminate();
}

void WindowContext::makeCurrent() { glfwMakeContextCurrent(window_); }

glm::ivec2 WindowContext::framebufferSize() const {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    return {w, h};
}

void WindowContext::swapBuffers() { glfwSwapBuffers(window_); }

std::vector<std::uint8_t> WindowContext::readBackBuffer() const {
    glm::ivec2 size = framebufferSize();
    std::vector<std::uint8_t> bottomUp(static_cast<std::size_t>(size.x) * static_cast<std::size_t>(size.y) * 4);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, size.x, size.y, GL_RGBA, GL_UNSIGNED_BYTE, bottomUp.data());
    std::vector<std::uint8_t> out(bottomUp.size());
    std::size_t row = static_cast<std::size_t>(size.x) * 4;
    for (int y = 0; y < size.y; ++y)
        std::copy_n(bottomUp.data() + static_cast<std::size_t>(size.y - 1 - y) * row, row, out.data() + static_cast<std::size_t>(y) * row);
    return out;
}
bool WindowContext::shouldClose() const { return glfwWindowShouldClose(window_); }

std::unique_ptr<WindowContext> createWindowContext(const std::string& title, glm::ivec2 size) {
    if (!displayAvailable()) throw SystemError("no display (DISPLAY/WAYLAND_DISPLAY unset): use `curette render`");
    glfwSetErrorCallback([](int code, const char* text) { log::warn("GLFW error " + std::to_string(code) + ": " + text); });
    if (!glfwInit()) throw SystemError("GLFW cannot initialise (is the display reachable?)");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, debugOutputRequested() ? GLFW_TRUE : GLFW_FALSE);
    std::unique_ptr<WindowContext> context(new WindowContext());
    context->window_ = glfwCreateWindow(size.x, size.y, title.c_str(), nullptr, nullptr);
    if (!context->window_)
        throw SystemError("the display's OpenGL driver cannot create a 4.5 core context; curette needs OpenGL 4.5 "
                          "with compute shaders");
    context->makeCurrent();
    glfwSwapInterval(1);
    context->info_.platform = "GLFW window";
    context->checkRequirementsAndQuery();
    context->installDebugOutput();
    return context;
}

}  // namespace curette::gl
