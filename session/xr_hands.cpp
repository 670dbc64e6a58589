#include "session/xr_hands.h"

namespace curette {

input::HandSample handSample(const SessionXrHand& hand, const RoomAnchor& anchor, double dtSeconds) {
    input::HandSample s;
    s.tracked = hand.tracked;
    if (hand.tracked) {   // an untracked grip's pose is not recorded, and TrackedHand reads none
        s.gripMm = anchor.roomToWorldMm(hand.grip.positionM);
        s.gripOrientation = anchor.orientationToWorld(hand.grip.orientation);
    }
    s.squeeze = hand.squeeze;
    s.trigger = hand.trigger;
    s.erase = hand.erase;
    s.cycleShading = hand.shadingPressed;
    s.thumbstickY = hand.thumbstick.y;
    s.thumbstickX = hand.moveVolume ? 0.0 : hand.thumbstick.x;   // the Vive's trackpad click carries the volume: no flick then
    s.dtSeconds = dtSeconds;
    return s;
}

RoomAnchor recordedAnchor(const RoomAnchor& table, const SessionXrFrame& frame) {
    RoomAnchor a = table;
    if (frame.anchor) {
        a.volumeCentreRoomM = frame.anchor->volumeCentreRoomM;
        a.volumeTurnRoom = frame.anchor->volumeTurnRoom;
        a.volumeScale = frame.anchor->volumeScale;
    }
    return a;
}

XrHands::XrHands(const RoomAnchor& table, int sessionVersion)
    : hands_{input::TrackedHand(0, sessionVersion >= kXrVolumeVersion), input::TrackedHand(1, sessionVersion >= kXrVolumeVersion)},
      anchor_(table),
      twoHands_(sessionVersion >= kXrTwoHandVersion) {}

std::vector<input::Action> XrHands::step(const std::array<SessionXrHand, 2>& hands, double dtSeconds) {
    auto carrying = [&](int h) { return hands[static_cast<std::size_t>(h)].tracked && hands[static_cast<std::size_t>(h)].moveVolume; };
    bool carried = false;   // the anchor followed a grip this frame (not at a grab's first frame)
    bool byTwo = twoHands_ && carrying(0) && carrying(1);
    if (byTwo) {
        if (heldByTwo_) {
            anchor_ = anchor_.heldByTwo(twoGrips_[0], twoGrips_[1], hands[0].grip.positionM, hands[1].grip.positionM);
            carried = true;
        }
        twoGrips_ = {hands[0].grip.positionM, hands[1].grip.positionM};
        volumeHand_.reset();   // when one lets go, the other's carrying starts afresh
    } else if (volumeHand_ && carrying(*volumeHand_)) {
        carried = true;
        const TrackedView& grip = hands[static_cast<std::size_t>(*volumeHand_)].grip;
        anchor_ = anchor_.carried(volumeGrip_, grip);
        volumeGrip_ = grip;
    } else {
        volumeHand_.reset();
        for (int h : {0, 1})
            if (!volumeHand_ && carrying(h)) {
                volumeHand_ = h;
                volumeGrip_ = hands[static_cast<std::size_t>(h)].grip;
            }
    }
    heldByTwo_ = byTwo;
    std::vector<input::Action> actions;
    for (std::size_t h = 0; h < 2; ++h) {
        input::HandSample sample = handSample(hands[h], anchor_, dtSeconds);
        sample.movingVolume = carried && (byTwo || volumeHand_ == static_cast<int>(h));
        for (input::Action& a : hands_[h].step(sample)) actions.push_back(std::move(a));
    }
    return actions;
}

}  // namespace curette
