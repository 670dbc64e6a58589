#include "session/xr_hands.h"

namespace curette {

input::HandSample handSample(const SessionXrHand& hand, const RoomAnchor& anchor, double dtSeconds) {
    input::HandSample s;
    s.tracked = hand.tracked;
    if (hand.tracked) {   // an untracked grip's pose is not recorded, and TrackedHand reads none
        s.gripMm = anchor.roomToWorldMm(hand.grip.positionM);
        s.gripOrientation = RoomAnchor::roomOrientationToWorld(hand.grip.orientation);
    }
    s.squeeze = hand.squeeze;
    s.trigger = hand.trigger;
    s.cycleShading = hand.shadingPressed;
    s.thumbstickY = hand.thumbstick.y;
    s.dtSeconds = dtSeconds;
    return s;
}

std::vector<input::Action> XrHands::step(const std::array<SessionXrHand, 2>& hands, const RoomAnchor& anchor, double dtSeconds) {
    std::vector<input::Action> actions;
    for (std::size_t h = 0; h < 2; ++h)
        for (input::Action& a : hands_[h].step(handSample(hands[h], anchor, dtSeconds))) actions.push_back(std::move(a));
    return actions;
}

}  // namespace curette
