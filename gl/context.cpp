#include "gl/context.h"

#include "base/error.h"
#include "base/log.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cstdlib>
#include <cstring>
#include <string>

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

// ---- headless: EGL on the surfaceless platform -------------------------------------------------------------

namespace {

class EglContext final : public Context {
public:
    EglContext() {
        if (!epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_MESA_platform_surfaceless"))
            throw SystemError("EGL has no surfaceless platform (EGL_MESA_platform_surfaceless); install "
                              "libegl1-mesa-dev and libgl1-mesa-dri");
        display_ = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        EGLint major = 0, minor = 0;
        if (display_ == EGL_NO_DISPLAY || !eglInitialize(display_, &major, &minor))
            throw SystemError("cannot initialise EGL on the surfaceless platform (error 0x" + hex(eglGetError()) + ")");
        if (!eglBindAPI(EGL_OPENGL_API)) throw SystemError("EGL cannot bind the desktop OpenGL API");
        EGLint flags = debugOutputRequested() ? EGL_CONTEXT_OPENGL_DEBUG_BIT_KHR : 0;
        const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                     EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                     EGL_CONTEXT_FLAGS_KHR, flags, EGL_NONE};
        context_ = eglCreateContext(display_, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
        if (context_ == EGL_NO_CONTEXT)
            throw SystemError("the EGL driver cannot create an OpenGL 4.5 core context (error 0x" +
                              hex(eglGetError()) + "); curette needs OpenGL 4.5 with compute shaders");
        makeCurrent();
        checkRequirementsAndQuery();
        installDebugOutput();
    }
    ~EglContext() override {
        eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
        eglTerminate(display_);
    }
    void makeCurrent() override {
        if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
            throw SystemError("eglMakeCurrent failed (error 0x" + hex(eglGetError()) + ")");
    }

private:
    static std::string hex(EGLint value) {
        char text[16];
        std::snprintf(text, sizeof text, "%x", static_cast<unsigned>(value));
        return text;
    }
    EGLDisplay display_ = EGL_NO_DISPLAY;
    EGLContext context_ = EGL_NO_CONTEXT;
};

}  // namespace

std::unique_ptr<Context> createHeadlessContext() { return std::make_unique<EglContext>(); }

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
    context->checkRequirementsAndQuery();
    context->installDebugOutput();
    return context;
}

}  // namespace curette::gl
