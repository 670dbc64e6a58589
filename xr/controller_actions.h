#pragma once
// The controllers of `view --xr` as OpenXR actions (OpenXR 1.0, chapter 11): one action set with each hand's
// grip pose, squeeze, trigger, thumbstick, shading, volume and erase buttons, suggested bindings for khr/simple_controller, valve/index_controller,
// oculus/touch_controller and htc/vive_controller (the runtime picks the profile of the controllers in hand),
// and a pose space per hand. Each frame's sync gives both hands' states in the room space; input/tracked_hand.h
// turns them into actions.

#include "render/model/tracked_view.h"

#include <openxr/openxr.h>

#include <array>

namespace curette::xr {

// One hand after a sync, in the room space.
struct HandState {
    bool tracked = false;            // the grip's position and orientation are valid
    TrackedView grip;                // the grip pose (its fov unused)
    double squeeze = 0.0;            // 0..1 (a click: 0 or 1)
    double trigger = 0.0;            // 0..1 (none on the simple controller)
    bool shadingPressed = false;     // the shading button went down since the last sync
    glm::dvec2 thumbstick{0.0};      // -1..1 (a trackpad on the Vive; none on the simple controller)
    bool moveVolume = false;         // the volume button is held (none on the simple controller)
    bool erase = false;              // the erase button is held (the Vive: its trackpad clicked low; none on
                                     // the simple controller)
};

// The Vive's trackpad is its stick and its only spare click: clicked in its lower third it erases with the held
// tool, elsewhere it carries the volume (a click near the centre never erases). A click
// is a press, not a stroke of the stick, so the stick reads zero meanwhile (the lower third would otherwise
// shrink the tool as it erases).
inline constexpr double kTrackpadEraseBelow = -1.0 / 3.0;
HandState trackpadClicked(HandState hand);

class ControllerActions {
public:
    // Creates the actions, suggests the bindings, attaches the set to `session` (before its first frame).
    ControllerActions(XrInstance instance, XrSession session);
    ~ControllerActions();
    ControllerActions(const ControllerActions&) = delete;
    ControllerActions& operator=(const ControllerActions&) = delete;

    // xrSyncActions, then both hands (left, right) at `time` in `space`. Not focused: nothing held, untracked.
    std::array<HandState, 2> sync(XrTime time, XrSpace space);

private:
    XrInstance instance_;
    XrSession session_;
    XrActionSet set_ = XR_NULL_HANDLE;
    XrAction grip_ = XR_NULL_HANDLE, squeeze_ = XR_NULL_HANDLE, shading_ = XR_NULL_HANDLE, thumbstick_ = XR_NULL_HANDLE,
             trigger_ = XR_NULL_HANDLE, moveVolume_ = XR_NULL_HANDLE, erase_ = XR_NULL_HANDLE, padClick_ = XR_NULL_HANDLE;
    std::array<XrPath, 2> hands_{};
    std::array<XrSpace, 2> gripSpaces_{XR_NULL_HANDLE, XR_NULL_HANDLE};
};

}  // namespace curette::xr
