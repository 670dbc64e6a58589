#include "xr/controller_actions.h"

#include "xr/xr_result.h"
#include "xr/xr_session.h"
#include "xr/xr_struct.h"

#include <cstdio>
#include <string>
#include <vector>

namespace curette::xr {

namespace {

XrPath path(XrInstance instance, const std::string& text) {
    XrPath p = XR_NULL_PATH;
    check(instance, xrStringToPath(instance, text.c_str(), &p), "xrStringToPath");
    return p;
}

XrAction createAction(XrInstance instance, XrActionSet set, const char* name, const char* localized, XrActionType type,
                      const std::array<XrPath, 2>& hands) {
    auto info = typed<XrActionCreateInfo>(XR_TYPE_ACTION_CREATE_INFO);
    std::snprintf(info.actionName, sizeof info.actionName, "%s", name);
    std::snprintf(info.localizedActionName, sizeof info.localizedActionName, "%s", localized);
    info.actionType = type;
    info.countSubactionPaths = 2;
    info.subactionPaths = hands.data();
    XrAction action = XR_NULL_HANDLE;
    check(instance, xrCreateAction(set, &info, &action), "xrCreateAction");
    return action;
}

// The inputs of a profile for the actions besides the grip pose (nullptr: the profile has none to spare):
// squeeze (the simple controller's one button, select, is its squeeze), the shading button per hand, the
// thumbstick (its y scales a held tool, a flick of its x undoes or redoes), the trigger, the volume button
// per hand (held: the hand carries the volume) and the erase button (held: the tool erases). The simple
// controller has two inputs, both taken. The Vive has one click left for both, its trackpad's: `padClick`,
// split by where the thumb presses (ControllerActions::sync).
struct ProfileInputs {
    const char* profile;
    const char* squeeze;
    std::array<const char*, 2> shading;
    const char* thumbstick;
    const char* trigger;
    std::array<const char*, 2> moveVolume;
    const char* erase;
    const char* padClick = nullptr;
};
constexpr ProfileInputs kProfiles[] = {
    {"/interaction_profiles/khr/simple_controller", "/input/select/click", {"/input/menu/click", "/input/menu/click"}, nullptr, nullptr,
     {nullptr, nullptr}, nullptr},
    {"/interaction_profiles/valve/index_controller", "/input/squeeze/value", {"/input/a/click", "/input/a/click"}, "/input/thumbstick",
     "/input/trigger/value", {"/input/b/click", "/input/b/click"}, "/input/thumbstick/click"},
    {"/interaction_profiles/oculus/touch_controller", "/input/squeeze/value", {"/input/x/click", "/input/a/click"}, "/input/thumbstick",
     "/input/trigger/value", {"/input/y/click", "/input/b/click"}, "/input/thumbstick/click"},
    {"/interaction_profiles/htc/vive_controller", "/input/squeeze/click", {"/input/menu/click", "/input/menu/click"}, "/input/trackpad",
     "/input/trigger/value", {nullptr, nullptr}, nullptr, "/input/trackpad/click"},
};

}  // namespace

HandState trackpadClicked(HandState hand) {
    if (hand.thumbstick.y < kTrackpadEraseBelow) hand.erase = true;
    else hand.moveVolume = true;
    hand.thumbstick = glm::dvec2(0.0);   // a click is neither a scale nor a flick
    return hand;
}

ControllerActions::ControllerActions(XrInstance instance, XrSession session) : instance_(instance), session_(session) {
    hands_ = {path(instance, "/user/hand/left"), path(instance, "/user/hand/right")};
    auto setInfo = typed<XrActionSetCreateInfo>(XR_TYPE_ACTION_SET_CREATE_INFO);
    std::snprintf(setInfo.actionSetName, sizeof setInfo.actionSetName, "carving");
    std::snprintf(setInfo.localizedActionSetName, sizeof setInfo.localizedActionSetName, "Carving");
    check(instance, xrCreateActionSet(instance, &setInfo, &set_), "xrCreateActionSet");
    grip_ = createAction(instance, set_, "grip_pose", "Hold a tool", XR_ACTION_TYPE_POSE_INPUT, hands_);
    squeeze_ = createAction(instance, set_, "grab", "Grab the tool", XR_ACTION_TYPE_FLOAT_INPUT, hands_);
    shading_ = createAction(instance, set_, "next_shading", "Next shading mode", XR_ACTION_TYPE_BOOLEAN_INPUT, hands_);
    thumbstick_ = createAction(instance, set_, "scale", "Scale the held tool", XR_ACTION_TYPE_VECTOR2F_INPUT, hands_);
    trigger_ = createAction(instance, set_, "drill", "Drill with the held tool", XR_ACTION_TYPE_FLOAT_INPUT, hands_);
    moveVolume_ = createAction(instance, set_, "move_volume", "Move the volume", XR_ACTION_TYPE_BOOLEAN_INPUT, hands_);
    erase_ = createAction(instance, set_, "erase", "Erase with the held tool", XR_ACTION_TYPE_BOOLEAN_INPUT, hands_);
    padClick_ = createAction(instance, set_, "trackpad_click", "Erase (lower third) or move the volume", XR_ACTION_TYPE_BOOLEAN_INPUT, hands_);

    const char* sides[] = {"/user/hand/left", "/user/hand/right"};
    for (const ProfileInputs& p : kProfiles) {
        std::vector<XrActionSuggestedBinding> bindings;
        for (int h = 0; h < 2; ++h) {
            std::string side = sides[h];
            bindings.push_back({grip_, path(instance, side + "/input/grip/pose")});
            bindings.push_back({squeeze_, path(instance, side + p.squeeze)});
            bindings.push_back({shading_, path(instance, side + p.shading[static_cast<std::size_t>(h)])});
            if (p.thumbstick) bindings.push_back({thumbstick_, path(instance, side + p.thumbstick)});
            if (p.trigger) bindings.push_back({trigger_, path(instance, side + p.trigger)});
            if (const char* volume = p.moveVolume[static_cast<std::size_t>(h)]) bindings.push_back({moveVolume_, path(instance, side + volume)});
            if (p.erase) bindings.push_back({erase_, path(instance, side + p.erase)});
            if (p.padClick) bindings.push_back({padClick_, path(instance, side + p.padClick)});
        }
        auto suggested = typed<XrInteractionProfileSuggestedBinding>(XR_TYPE_INTERACTION_PROFILE_SUGGESTED_BINDING);
        suggested.interactionProfile = path(instance, p.profile);
        suggested.countSuggestedBindings = static_cast<std::uint32_t>(bindings.size());
        suggested.suggestedBindings = bindings.data();
        check(instance, xrSuggestInteractionProfileBindings(instance, &suggested), "xrSuggestInteractionProfileBindings");
    }
    for (std::size_t h = 0; h < 2; ++h) {
        auto spaceInfo = typed<XrActionSpaceCreateInfo>(XR_TYPE_ACTION_SPACE_CREATE_INFO);
        spaceInfo.action = grip_;
        spaceInfo.subactionPath = hands_[h];
        spaceInfo.poseInActionSpace.orientation.w = 1.0f;
        check(instance, xrCreateActionSpace(session, &spaceInfo, &gripSpaces_[h]), "xrCreateActionSpace");
    }
    auto attach = typed<XrSessionActionSetsAttachInfo>(XR_TYPE_SESSION_ACTION_SETS_ATTACH_INFO);
    attach.countActionSets = 1;
    attach.actionSets = &set_;
    check(instance, xrAttachSessionActionSets(session, &attach), "xrAttachSessionActionSets");
}

ControllerActions::~ControllerActions() {
    for (XrSpace s : gripSpaces_)
        if (s != XR_NULL_HANDLE) xrDestroySpace(s);
    if (set_ != XR_NULL_HANDLE) xrDestroyActionSet(set_);   // its actions with it
}

std::array<HandState, 2> ControllerActions::sync(XrTime time, XrSpace space) {
    std::array<HandState, 2> hands{};
    XrActiveActionSet active{set_, XR_NULL_PATH};
    auto syncInfo = typed<XrActionsSyncInfo>(XR_TYPE_ACTIONS_SYNC_INFO);
    syncInfo.countActiveActionSets = 1;
    syncInfo.activeActionSets = &active;
    if (check(instance_, xrSyncActions(session_, &syncInfo), "xrSyncActions") == XR_SESSION_NOT_FOCUSED) return hands;
    for (std::size_t h = 0; h < 2; ++h) {
        HandState& hand = hands[h];
        auto get = typed<XrActionStateGetInfo>(XR_TYPE_ACTION_STATE_GET_INFO);
        get.subactionPath = hands_[h];
        get.action = grip_;
        auto pose = typed<XrActionStatePose>(XR_TYPE_ACTION_STATE_POSE);
        check(instance_, xrGetActionStatePose(session_, &get, &pose), "xrGetActionStatePose");
        if (pose.isActive) {
            auto location = typed<XrSpaceLocation>(XR_TYPE_SPACE_LOCATION);
            check(instance_, xrLocateSpace(gripSpaces_[h], space, time, &location), "xrLocateSpace");
            const XrSpaceLocationFlags valid = XR_SPACE_LOCATION_POSITION_VALID_BIT | XR_SPACE_LOCATION_ORIENTATION_VALID_BIT;
            hand.tracked = (location.locationFlags & valid) == valid;
            if (hand.tracked) hand.grip = roomPose(location.pose);
        }
        get.action = squeeze_;
        auto squeeze = typed<XrActionStateFloat>(XR_TYPE_ACTION_STATE_FLOAT);
        check(instance_, xrGetActionStateFloat(session_, &get, &squeeze), "xrGetActionStateFloat");
        hand.squeeze = squeeze.isActive ? squeeze.currentState : 0.0;
        get.action = trigger_;
        auto trigger = typed<XrActionStateFloat>(XR_TYPE_ACTION_STATE_FLOAT);
        check(instance_, xrGetActionStateFloat(session_, &get, &trigger), "xrGetActionStateFloat");
        hand.trigger = trigger.isActive ? trigger.currentState : 0.0;
        get.action = shading_;
        auto button = typed<XrActionStateBoolean>(XR_TYPE_ACTION_STATE_BOOLEAN);
        check(instance_, xrGetActionStateBoolean(session_, &get, &button), "xrGetActionStateBoolean");
        hand.shadingPressed = button.isActive && button.currentState && button.changedSinceLastSync;
        get.action = thumbstick_;
        auto stick = typed<XrActionStateVector2f>(XR_TYPE_ACTION_STATE_VECTOR2F);
        check(instance_, xrGetActionStateVector2f(session_, &get, &stick), "xrGetActionStateVector2f");
        if (stick.isActive) hand.thumbstick = {stick.currentState.x, stick.currentState.y};
        get.action = moveVolume_;
        check(instance_, xrGetActionStateBoolean(session_, &get, &button), "xrGetActionStateBoolean");
        hand.moveVolume = button.isActive && button.currentState;
        get.action = erase_;
        check(instance_, xrGetActionStateBoolean(session_, &get, &button), "xrGetActionStateBoolean");
        hand.erase = button.isActive && button.currentState;
        get.action = padClick_;
        check(instance_, xrGetActionStateBoolean(session_, &get, &button), "xrGetActionStateBoolean");
        if (button.isActive && button.currentState) hand = trackpadClicked(hand);
    }
    return hands;
}

}  // namespace curette::xr
