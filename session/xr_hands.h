#pragma once
// The controllers of a head-mounted display session as action sources: each frame's two recorded hand states
// (SessionXrHand: room-space grip and action states) -> the hands' actions (input/tracked_hand.h), the left
// hand holding mesh 0, the right mesh 1. `view --xr` runs it on the states it syncs, `replay --from-reports`
// on the recorded ones, so both derive the same actions from the same states.

#include "input/actions.h"
#include "input/tracked_hand.h"
#include "render/model/tracked_view.h"
#include "session/session.h"

#include <array>
#include <vector>

namespace curette {

// A hand's state as its TrackedHand sees it: the grip in world (RAS) mm through the room anchor.
input::HandSample handSample(const SessionXrHand& hand, const RoomAnchor& anchor, double dtSeconds);

class XrHands {
public:
    // Both hands' actions for one frame, `dtSeconds` after the one before (0 at the first).
    std::vector<input::Action> step(const std::array<SessionXrHand, 2>& hands, const RoomAnchor& anchor, double dtSeconds);
    const input::TrackedHand& hand(int i) const { return hands_[static_cast<std::size_t>(i)]; }

private:
    std::array<input::TrackedHand, 2> hands_{input::TrackedHand(0), input::TrackedHand(1)};
};

}  // namespace curette
