#include "xr/xr_session.h"

#include "base/error.h"
#include "base/log.h"
#include "xr/xr_result.h"
#include "xr/xr_struct.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <epoxy/glx.h>

#define XR_USE_PLATFORM_XLIB
#define XR_USE_PLATFORM_EGL
#define XR_USE_GRAPHICS_API_OPENGL
#include <openxr/openxr_platform.h>

#include <algorithm>
#include <cstring>
#include <vector>

namespace curette::xr {

const char* sessionStateName(XrSessionState state) {
    switch (state) {
        case XR_SESSION_STATE_IDLE: return "IDLE";
        case XR_SESSION_STATE_READY: return "READY";
        case XR_SESSION_STATE_SYNCHRONIZED: return "SYNCHRONIZED";
        case XR_SESSION_STATE_VISIBLE: return "VISIBLE";
        case XR_SESSION_STATE_FOCUSED: return "FOCUSED";
        case XR_SESSION_STATE_STOPPING: return "STOPPING";
        case XR_SESSION_STATE_LOSS_PENDING: return "LOSS_PENDING";
        case XR_SESSION_STATE_EXITING: return "EXITING";
        default: return "UNKNOWN";
    }
}

namespace {

// The GLX binding of the context current on this thread (XR_KHR_opengl_enable's Xlib binding).
XrGraphicsBindingOpenGLXlibKHR currentGlxBinding() {
    auto binding = typed<XrGraphicsBindingOpenGLXlibKHR>(XR_TYPE_GRAPHICS_BINDING_OPENGL_XLIB_KHR);
    binding.xDisplay = glXGetCurrentDisplay();
    binding.glxContext = glXGetCurrentContext();
    binding.glxDrawable = glXGetCurrentDrawable();
    if (!binding.xDisplay || !binding.glxContext)
        throw SystemError("OpenXR needs a GLX context (an X11 window): the current GL context is not one");
    int configId = 0, screen = 0;
    glXQueryContext(binding.xDisplay, binding.glxContext, GLX_FBCONFIG_ID, &configId);
    glXQueryContext(binding.xDisplay, binding.glxContext, GLX_SCREEN, &screen);
    const int attributes[] = {GLX_FBCONFIG_ID, configId, None};
    int count = 0;
    GLXFBConfig* configs = glXChooseFBConfig(binding.xDisplay, screen, attributes, &count);
    if (!configs || count < 1) throw SystemError("OpenXR binding: the GLX context's framebuffer configuration cannot be found");
    binding.glxFBConfig = configs[0];
    int visual = 0;
    glXGetFBConfigAttrib(binding.xDisplay, configs[0], GLX_VISUAL_ID, &visual);
    binding.visualid = static_cast<std::uint32_t>(visual);
    XFree(configs);
    return binding;
}

// The EGL binding of the context current on this thread (XR_MNDX_egl_enable, OpenXR 1.0 registry:
// XrGraphicsBindingEGLMNDX { getProcAddress, display, config, context }; Debian's 1.0.20 headers define it
// under XR_USE_PLATFORM_EGL). A context made without a config (EGL_KHR_no_config_context) binds none.
XrGraphicsBindingEGLMNDX currentEglBinding() {
    auto binding = typed<XrGraphicsBindingEGLMNDX>(XR_TYPE_GRAPHICS_BINDING_EGL_MNDX);
    binding.getProcAddress = eglGetProcAddress;
    binding.display = eglGetCurrentDisplay();
    binding.context = eglGetCurrentContext();
    if (binding.display == EGL_NO_DISPLAY || binding.context == EGL_NO_CONTEXT)
        throw SystemError("OpenXR's EGL binding needs an EGL context: the current GL context is not one");
    EGLint configId = 0, count = 0;
    eglQueryContext(binding.display, binding.context, EGL_CONFIG_ID, &configId);
    const EGLint attributes[] = {EGL_CONFIG_ID, configId, EGL_NONE};
    EGLConfig config = nullptr;
    if (configId > 0 && eglChooseConfig(binding.display, attributes, &config, 1, &count) && count == 1) binding.config = config;
    return binding;
}

}  // namespace

// Whether the runtime offers `name`; throws when the loader finds no runtime at all.
bool runtimeOffers(const char* name) {
    std::uint32_t count = 0;
    XrResult r = xrEnumerateInstanceExtensionProperties(nullptr, 0, &count, nullptr);
    if (XR_FAILED(r))
        throw SystemError("no OpenXR runtime (XrResult " + std::to_string(static_cast<int>(r)) +
                          "): start Monado, SteamVR or WiVRn, or name a runtime's manifest in XR_RUNTIME_JSON");
    std::vector<XrExtensionProperties> properties(count, typed<XrExtensionProperties>(XR_TYPE_EXTENSION_PROPERTIES));
    check(XR_NULL_HANDLE, xrEnumerateInstanceExtensionProperties(nullptr, count, &count, properties.data()), "xrEnumerateInstanceExtensionProperties");
    return std::any_of(properties.begin(), properties.end(), [&](const XrExtensionProperties& p) { return std::strcmp(p.extensionName, name) == 0; });
}

TrackedView roomPose(const XrPosef& p) {
    TrackedView t;
    t.positionM = {p.position.x, p.position.y, p.position.z};
    t.orientation = glm::normalize(glm::dquat(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z));
    return t;
}

Session::Session(const std::string& applicationName, GlBinding glBinding, std::function<void(XrSessionState)> onState)
    : onState_(std::move(onState)) {
    if (!runtimeOffers(XR_KHR_OPENGL_ENABLE_EXTENSION_NAME))
        throw SystemError("the OpenXR runtime offers no OpenGL binding (XR_KHR_opengl_enable), which curette renders with");
    if (glBinding == GlBinding::Egl && !runtimeOffers(XR_MNDX_EGL_ENABLE_EXTENSION_NAME))
        throw SystemError("the OpenXR runtime offers no EGL binding (XR_MNDX_egl_enable): a headless session needs it; run with a window instead");
    // The EGL binding's swapchain images are still XR_KHR_opengl_enable's GL textures.
    const char* extensions[] = {XR_KHR_OPENGL_ENABLE_EXTENSION_NAME, XR_MNDX_EGL_ENABLE_EXTENSION_NAME};
    auto create = typed<XrInstanceCreateInfo>(XR_TYPE_INSTANCE_CREATE_INFO);
    std::snprintf(create.applicationInfo.applicationName, sizeof create.applicationInfo.applicationName, "%s", applicationName.c_str());
    create.applicationInfo.applicationVersion = 1;
    std::snprintf(create.applicationInfo.engineName, sizeof create.applicationInfo.engineName, "curette");
    create.applicationInfo.apiVersion = XR_MAKE_VERSION(1, 0, 0);
    create.enabledExtensionCount = glBinding == GlBinding::Egl ? 2 : 1;
    create.enabledExtensionNames = extensions;
    check(XR_NULL_HANDLE, xrCreateInstance(&create, &instance_), "xrCreateInstance");

    try {
        auto properties = typed<XrInstanceProperties>(XR_TYPE_INSTANCE_PROPERTIES);
        check(instance_, xrGetInstanceProperties(instance_, &properties), "xrGetInstanceProperties");
        runtimeName_ = properties.runtimeName;
        auto systemInfo = typed<XrSystemGetInfo>(XR_TYPE_SYSTEM_GET_INFO);
        systemInfo.formFactor = XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY;
        check(instance_, xrGetSystem(instance_, &systemInfo, &system_), "xrGetSystem (is the headset connected?)");
        auto systemProperties = typed<XrSystemProperties>(XR_TYPE_SYSTEM_PROPERTIES);
        check(instance_, xrGetSystemProperties(instance_, system_, &systemProperties), "xrGetSystemProperties");
        systemName_ = systemProperties.systemName;

        std::uint32_t viewCount = 0;
        check(instance_, xrEnumerateViewConfigurationViews(instance_, system_, XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO, 0, &viewCount, nullptr),
              "xrEnumerateViewConfigurationViews");
        if (viewCount != 2) throw SystemError("OpenXR: the stereo view configuration has " + std::to_string(viewCount) + " views, not 2");
        std::vector<XrViewConfigurationView> views(viewCount, typed<XrViewConfigurationView>(XR_TYPE_VIEW_CONFIGURATION_VIEW));
        check(instance_,
              xrEnumerateViewConfigurationViews(instance_, system_, XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO, viewCount, &viewCount, views.data()),
              "xrEnumerateViewConfigurationViews");
        for (std::size_t i = 0; i < 2; ++i)
            recommended_[i] = {static_cast<int>(views[i].recommendedImageRectWidth), static_cast<int>(views[i].recommendedImageRectHeight)};

        // The binding's GL version requirement must be asked before the session (XR_KHR_opengl_enable).
        PFN_xrGetOpenGLGraphicsRequirementsKHR getRequirements = nullptr;
        check(instance_,
              xrGetInstanceProcAddr(instance_, "xrGetOpenGLGraphicsRequirementsKHR", reinterpret_cast<PFN_xrVoidFunction*>(&getRequirements)),
              "xrGetInstanceProcAddr(xrGetOpenGLGraphicsRequirementsKHR)");
        auto requirements = typed<XrGraphicsRequirementsOpenGLKHR>(XR_TYPE_GRAPHICS_REQUIREMENTS_OPENGL_KHR);
        check(instance_, getRequirements(instance_, system_, &requirements), "xrGetOpenGLGraphicsRequirementsKHR");
        if (XR_MAKE_VERSION(4, 5, 0) < requirements.minApiVersionSupported)
            throw SystemError("the OpenXR runtime needs OpenGL " + std::to_string(XR_VERSION_MAJOR(requirements.minApiVersionSupported)) + "." +
                              std::to_string(XR_VERSION_MINOR(requirements.minApiVersionSupported)) + "; curette's context is 4.5");

        XrGraphicsBindingOpenGLXlibKHR glx{};
        XrGraphicsBindingEGLMNDX egl{};
        auto sessionInfo = typed<XrSessionCreateInfo>(XR_TYPE_SESSION_CREATE_INFO);
        if (glBinding == GlBinding::Egl) {
            egl = currentEglBinding();
            sessionInfo.next = &egl;
        } else {
            glx = currentGlxBinding();
            sessionInfo.next = &glx;
        }
        sessionInfo.systemId = system_;
        check(instance_, xrCreateSession(instance_, &sessionInfo, &session_), "xrCreateSession");

        std::uint32_t spaceCount = 0;
        check(instance_, xrEnumerateReferenceSpaces(session_, 0, &spaceCount, nullptr), "xrEnumerateReferenceSpaces");
        std::vector<XrReferenceSpaceType> spaces(spaceCount);
        check(instance_, xrEnumerateReferenceSpaces(session_, spaceCount, &spaceCount, spaces.data()), "xrEnumerateReferenceSpaces");
        bool stage = std::find(spaces.begin(), spaces.end(), XR_REFERENCE_SPACE_TYPE_STAGE) != spaces.end();
        roomSpace_ = stage ? RoomSpace::Stage : RoomSpace::Local;
        auto spaceInfo = typed<XrReferenceSpaceCreateInfo>(XR_TYPE_REFERENCE_SPACE_CREATE_INFO);
        spaceInfo.referenceSpaceType = stage ? XR_REFERENCE_SPACE_TYPE_STAGE : XR_REFERENCE_SPACE_TYPE_LOCAL;
        spaceInfo.poseInReferenceSpace.orientation.w = 1.0f;
        check(instance_, xrCreateReferenceSpace(session_, &spaceInfo, &space_), "xrCreateReferenceSpace");
        spaceInfo.referenceSpaceType = XR_REFERENCE_SPACE_TYPE_VIEW;   // the head, for sessions to record
        check(instance_, xrCreateReferenceSpace(session_, &spaceInfo, &viewSpace_), "xrCreateReferenceSpace(VIEW)");

        std::uint32_t formatCount = 0;
        check(instance_, xrEnumerateSwapchainFormats(session_, 0, &formatCount, nullptr), "xrEnumerateSwapchainFormats");
        std::vector<std::int64_t> formats(formatCount);
        check(instance_, xrEnumerateSwapchainFormats(session_, formatCount, &formatCount, formats.data()), "xrEnumerateSwapchainFormats");
        for (std::int64_t wanted : preferredSwapchainFormats())
            if (!format_ && std::find(formats.begin(), formats.end(), wanted) != formats.end()) format_ = wanted;
        if (!format_) throw SystemError("the OpenXR runtime offers neither GL_SRGB8_ALPHA8 nor GL_RGBA8 swapchains");
        for (std::size_t eye = 0; eye < 2; ++eye) swapchains_[eye] = std::make_unique<EyeSwapchain>(instance_, session_, format_, recommended_[eye]);
    } catch (...) {
        for (auto& s : swapchains_) s.reset();
        if (viewSpace_ != XR_NULL_HANDLE) xrDestroySpace(viewSpace_);
        if (space_ != XR_NULL_HANDLE) xrDestroySpace(space_);
        if (session_ != XR_NULL_HANDLE) xrDestroySession(session_);
        xrDestroyInstance(instance_);
        throw;
    }
}

Session::~Session() {
    for (auto& s : swapchains_) s.reset();
    if (viewSpace_ != XR_NULL_HANDLE) xrDestroySpace(viewSpace_);
    if (space_ != XR_NULL_HANDLE) xrDestroySpace(space_);
    if (session_ != XR_NULL_HANDLE) xrDestroySession(session_);
    if (instance_ != XR_NULL_HANDLE) xrDestroyInstance(instance_);
}

bool Session::pollEvents() {
    for (;;) {
        auto event = typed<XrEventDataBuffer>(XR_TYPE_EVENT_DATA_BUFFER);
        XrResult result = check(instance_, xrPollEvent(instance_, &event), "xrPollEvent");
        if (result == XR_EVENT_UNAVAILABLE) return true;
        if (event.type == XR_TYPE_EVENT_DATA_INSTANCE_LOSS_PENDING) {
            log::warn("OpenXR: the runtime is going away (instance loss pending)");
            return false;
        }
        if (event.type != XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED) continue;
        const auto& changed = reinterpret_cast<const XrEventDataSessionStateChanged&>(event);
        state_ = changed.state;
        if (onState_) onState_(state_);
        switch (state_) {
            case XR_SESSION_STATE_READY: {
                auto begin = typed<XrSessionBeginInfo>(XR_TYPE_SESSION_BEGIN_INFO);
                begin.primaryViewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
                check(instance_, xrBeginSession(session_, &begin), "xrBeginSession");
                running_ = true;
                break;
            }
            case XR_SESSION_STATE_STOPPING:
                check(instance_, xrEndSession(session_), "xrEndSession");
                running_ = false;
                break;
            case XR_SESSION_STATE_EXITING:
            case XR_SESSION_STATE_LOSS_PENDING: return false;
            default: break;
        }
    }
}

void Session::requestExit() {
    if (exitRequested_ || !running_) return;
    exitRequested_ = true;
    check(instance_, xrRequestExitSession(session_), "xrRequestExitSession");
}

Session::Frame Session::beginFrame() {
    Frame frame;
    auto waitInfo = typed<XrFrameWaitInfo>(XR_TYPE_FRAME_WAIT_INFO);
    auto frameState = typed<XrFrameState>(XR_TYPE_FRAME_STATE);
    check(instance_, xrWaitFrame(session_, &waitInfo, &frameState), "xrWaitFrame");
    auto beginInfo = typed<XrFrameBeginInfo>(XR_TYPE_FRAME_BEGIN_INFO);
    check(instance_, xrBeginFrame(session_, &beginInfo), "xrBeginFrame");
    frameBegun_ = true;
    submitted_ = {false, false};
    displayTime_ = frameState.predictedDisplayTime;
    frame.displayTime = frameState.predictedDisplayTime;
    frame.shouldRender = frameState.shouldRender == XR_TRUE;
    auto head = typed<XrSpaceLocation>(XR_TYPE_SPACE_LOCATION);
    check(instance_, xrLocateSpace(viewSpace_, space_, frameState.predictedDisplayTime, &head), "xrLocateSpace(VIEW)");
    const XrSpaceLocationFlags located = XR_SPACE_LOCATION_POSITION_VALID_BIT | XR_SPACE_LOCATION_ORIENTATION_VALID_BIT;
    if ((head.locationFlags & located) == located) frame.head = roomPose(head.pose);
    if (!frame.shouldRender) return frame;

    auto locate = typed<XrViewLocateInfo>(XR_TYPE_VIEW_LOCATE_INFO);
    locate.viewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
    locate.displayTime = frameState.predictedDisplayTime;
    locate.space = space_;
    auto viewState = typed<XrViewState>(XR_TYPE_VIEW_STATE);
    std::array<XrView, 2> views{};
    for (XrView& v : views) v.type = XR_TYPE_VIEW;
    std::uint32_t count = 0;
    check(instance_, xrLocateViews(session_, &locate, &viewState, 2, &count, views.data()), "xrLocateViews");
    const XrViewStateFlags valid = XR_VIEW_STATE_ORIENTATION_VALID_BIT | XR_VIEW_STATE_POSITION_VALID_BIT;
    frame.viewsValid = count == 2 && (viewState.viewStateFlags & valid) == valid;
    for (std::size_t eye = 0; eye < 2; ++eye) {
        const XrView& v = views[eye];
        TrackedView& t = frame.views[eye];
        t = roomPose(v.pose);
        t.fov = {v.fov.angleLeft, v.fov.angleRight, v.fov.angleUp, v.fov.angleDown};
    }
    return frame;
}

void Session::submitEye(int eye, const std::vector<std::uint8_t>& rgba8, glm::ivec2 size, const FieldOfView& fov, const TrackedView& view) {
    const auto e = static_cast<std::size_t>(eye);
    swapchains_[e]->fill(rgba8, size);
    XrCompositionLayerProjectionView& p = projectionViews_[e];
    p = typed<XrCompositionLayerProjectionView>(XR_TYPE_COMPOSITION_LAYER_PROJECTION_VIEW);
    p.pose.position = {static_cast<float>(view.positionM.x), static_cast<float>(view.positionM.y), static_cast<float>(view.positionM.z)};
    p.pose.orientation = {static_cast<float>(view.orientation.x), static_cast<float>(view.orientation.y), static_cast<float>(view.orientation.z),
                          static_cast<float>(view.orientation.w)};
    p.fov = {static_cast<float>(fov.angleLeft), static_cast<float>(fov.angleRight), static_cast<float>(fov.angleUp), static_cast<float>(fov.angleDown)};
    p.subImage.swapchain = swapchains_[e]->handle();
    p.subImage.imageRect = {{0, 0}, {size.x, size.y}};
    p.subImage.imageArrayIndex = 0;
    submitted_[e] = true;
}

void Session::endFrame() {
    if (!frameBegun_) return;
    frameBegun_ = false;
    auto layer = typed<XrCompositionLayerProjection>(XR_TYPE_COMPOSITION_LAYER_PROJECTION);
    layer.space = space_;
    layer.viewCount = 2;
    layer.views = projectionViews_.data();
    const XrCompositionLayerBaseHeader* layers[] = {reinterpret_cast<const XrCompositionLayerBaseHeader*>(&layer)};
    auto end = typed<XrFrameEndInfo>(XR_TYPE_FRAME_END_INFO);
    end.displayTime = displayTime_;
    end.environmentBlendMode = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
    end.layerCount = submitted_[0] && submitted_[1] ? 1 : 0;
    end.layers = end.layerCount ? layers : nullptr;
    check(instance_, xrEndFrame(session_, &end), "xrEndFrame");
}

}  // namespace curette::xr
