#pragma once
// The OpenXR session of `curette view --xr` (OpenXR 1.0 through the Khronos loader): the instance with
// XR_KHR_opengl_enable, the head-mounted system, a session bound to the GL context current on this thread
// (a GLX one: the GLFW window's; or, headless, an EGL one through XR_MNDX_egl_enable where the runtime offers
// it), the room space (stage, else local), a swapchain per eye at the runtime's recommended size, and the
// frame loop. The session state machine (spec 9.3) is followed in pollEvents:
// READY begins the session, STOPPING ends it, EXITING and LOSS_PENDING end the loop.

#include "render/model/tracked_view.h"
#include "xr/eye_swapchain.h"

#include <openxr/openxr.h>

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>

namespace curette::xr {

// The name of a session state ("READY", ...).
const char* sessionStateName(XrSessionState state);

// A runtime's pose (floats) in curette's doubles, its orientation normalised; fov left zero.
TrackedView roomPose(const XrPosef& pose);

// How the session reaches the current GL context: GLX (XR_KHR_opengl_enable's Xlib binding: a window) or EGL
// (XR_MNDX_egl_enable's binding: a headless context; only where the runtime offers the extension).
enum class GlBinding { Glx, Egl };

// Whether the active runtime offers `extension`; throws SystemError when the loader finds no runtime.
bool runtimeOffers(const char* extension);

class Session {
public:
    // Throws SystemError naming the call that failed (no runtime, no HMD, no GLX or EGL context current, no
    // XR_MNDX_egl_enable for an EGL binding, ...). `onState` hears every state change, in order.
    Session(const std::string& applicationName, GlBinding binding, std::function<void(XrSessionState)> onState);
    ~Session();
    Session(const Session&) = delete;
    Session& operator=(const Session&) = delete;

    std::string runtimeName() const { return runtimeName_; }
    std::string systemName() const { return systemName_; }
    RoomSpace roomSpace() const { return roomSpace_; }
    glm::ivec2 recommendedSize(int eye) const { return recommended_[static_cast<std::size_t>(eye)]; }
    std::int64_t swapchainFormat() const { return format_; }

    // Handles the queued events; false once the session is over (exiting, lost).
    bool pollEvents();
    bool running() const { return running_; }
    XrSessionState state() const { return state_; }
    // Asks the runtime to end the session (a closed window, Ctrl-C): it walks it down to EXITING.
    void requestExit();

    struct Frame {
        XrTime displayTime = 0;
        bool shouldRender = false;
        std::optional<TrackedView> head;       // the view space, when located (fov unused)
        bool viewsValid = false;               // both eyes located (position and orientation)
        std::array<TrackedView, 2> views{};    // left, right, in the room space
    };
    // Waits for the runtime's next frame and begins it (only while running).
    Frame beginFrame();
    // Copies eye `eye`'s 8-bit image (rows top-down) into its swapchain; `fov` is what its pixels span and
    // `view` where it was rendered from.
    void submitEye(int eye, const std::vector<std::uint8_t>& rgba8, glm::ivec2 size, const FieldOfView& fov, const TrackedView& view);
    // Ends the frame begun: a projection layer when both eyes were submitted, no layer otherwise.
    void endFrame();

    XrInstance instance() const { return instance_; }
    XrSession session() const { return session_; }
    XrSpace space() const { return space_; }

private:
    std::function<void(XrSessionState)> onState_;
    XrInstance instance_ = XR_NULL_HANDLE;
    XrSystemId system_ = XR_NULL_SYSTEM_ID;
    XrSession session_ = XR_NULL_HANDLE;
    XrSpace space_ = XR_NULL_HANDLE, viewSpace_ = XR_NULL_HANDLE;
    RoomSpace roomSpace_ = RoomSpace::Stage;
    std::string runtimeName_, systemName_;
    std::array<glm::ivec2, 2> recommended_{};
    std::int64_t format_ = 0;
    std::array<std::unique_ptr<EyeSwapchain>, 2> swapchains_;
    std::array<XrCompositionLayerProjectionView, 2> projectionViews_{};
    std::array<bool, 2> submitted_{false, false};
    XrSessionState state_ = XR_SESSION_STATE_UNKNOWN;
    bool running_ = false, exitRequested_ = false, frameBegun_ = false;
    XrTime displayTime_ = 0;
};

}  // namespace curette::xr
