#pragma once
// The controllers of a head-mounted display session as action sources: each frame's two recorded hand states
// (SessionXrHand: room-space grip and action states) -> the hands' actions (input/tracked_hand.h), the left
// hand holding mesh 0, the right mesh 1, and the volume's place in the room. `view --xr` runs it on the states
// it syncs, `replay --from-reports` on the recorded ones, so both derive the same actions and the same place
// from the same states.
//
// Moving the volume (session version 7): while a hand holds its volume button the whole scene follows that
// grip rigidly in the room (RoomAnchor::carried): the volume, its meshes and tracts keep their world (RAS)
// poses, so the carve and the ambient occlusion do not change; only the eyes see it from elsewhere. The
// first hand to press carries it (the left when both press at once) until it lets go; the first frame of a
// grab moves nothing.
//
// Scaling it (session version 8): while both hands hold their volume buttons, the volume follows both
// (RoomAnchor::heldByTwo): the ratio of the hands' distances scales it about their midpoint, the line between
// them turns it, the midpoint carries it, as in any VR viewer. The first frame both hold moves nothing; when
// one lets go, the other carries it alone from its next frame (a new grab).

#include "input/actions.h"
#include "input/tracked_hand.h"
#include "render/model/tracked_view.h"
#include "session/session.h"

#include <array>
#include <optional>
#include <vector>

namespace curette {

// A hand's state as its TrackedHand sees it: the grip in world (RAS) mm through the room anchor.
input::HandSample handSample(const SessionXrHand& hand, const RoomAnchor& anchor, double dtSeconds);

// The volume's place a recorded frame says (`table` with the recorded centre and turn; before version 7 the
// table's own), for a replay that follows the recording.
RoomAnchor recordedAnchor(const RoomAnchor& table, const SessionXrFrame& frame);

class XrHands {
public:
    // `table`: the volume's place at the start; `sessionVersion`: the recording's (flicks undo and redo from 7).
    explicit XrHands(const RoomAnchor& table, int sessionVersion = kSessionVersion);
    // Both hands' actions for one frame, `dtSeconds` after the one before (0 at the first); moves the volume first.
    std::vector<input::Action> step(const std::array<SessionXrHand, 2>& hands, double dtSeconds);
    const input::TrackedHand& hand(int i) const { return hands_[static_cast<std::size_t>(i)]; }
    const RoomAnchor& anchor() const { return anchor_; }
    std::optional<int> volumeHand() const { return volumeHand_; }

private:
    std::array<input::TrackedHand, 2> hands_;
    RoomAnchor anchor_;
    bool twoHands_;                   // the session's version scales with two hands
    std::optional<int> volumeHand_;   // the hand carrying the volume alone
    TrackedView volumeGrip_;          // its grip at the last frame
    bool heldByTwo_ = false;          // both hands held the volume at the last frame
    std::array<glm::dvec3, 2> twoGrips_{};   // their grips then (room positions)
};

}  // namespace curette
