#include "input/tracked_hand.h"

#include <cmath>

namespace curette::input {

bool analogHeld(bool wasHeld, double value) { return wasHeld ? value >= kReleaseBelow : value >= kGrabAt; }

std::vector<Action> TrackedHand::step(const HandSample& sample) {
    std::vector<Action> actions;
    if (sample.cycleShading) actions.push_back(CycleShading{});
    const bool wasHolding = holding_;
    holding_ = sample.tracked && analogHeld(holding_, sample.squeeze);
    drilling_ = holding_ && analogHeld(drilling_, sample.trigger);
    // While the hand carries the volume its grip stays put on the anatomy: the mesh does not move (not even
    // by the rounding of the room-to-world map, which would recompute the ambient occlusion).
    if (holding_ && wasHolding && last_.tracked && !sample.movingVolume) {
        // The grip's motion since the last frame: turn about where the grip was, then move by its displacement.
        glm::dquat turn = glm::normalize(sample.gripOrientation * glm::conjugate(last_.gripOrientation));
        if (turn.w < 0) turn = -turn;   // the shorter way round
        double angle = 2.0 * std::atan2(glm::length(glm::dvec3(turn.x, turn.y, turn.z)), turn.w);
        glm::dvec3 axis = angle > 0 ? glm::normalize(glm::dvec3(turn.x, turn.y, turn.z)) : glm::dvec3(0.0);
        GripMesh move{mesh_, last_.gripMm, sample.gripMm - last_.gripMm, angle * axis};
        if (move.translationMm != glm::dvec3(0.0) || move.rotationRad != glm::dvec3(0.0)) actions.push_back(move);
    }
    if (holding_ && std::abs(sample.thumbstickY) > kThumbstickDeadZone && sample.dtSeconds > 0)
        actions.push_back(ScaleMesh{mesh_, std::pow(kScalePerSecond, sample.thumbstickY * sample.dtSeconds)});
    // After the motion: the drill sweeps from where the mesh was before the frame to where the hand put it.
    if (auto d = heldDrill(mesh_, drilling_, holding_ && sample.erase)) actions.push_back(*d);
    if (flicks_) {
        const double x = sample.thumbstickX;
        const int side = x < 0 ? -1 : 1;
        if (flick_ != 0 && !analogHeld(true, std::abs(x))) flick_ = 0;   // back towards the centre
        if (flick_ == 0 && analogHeld(false, std::abs(x)) && std::abs(x) > std::abs(sample.thumbstickY)) {
            flick_ = side;
            if (side < 0) actions.push_back(Undo{});
            else actions.push_back(Redo{});
        }
    }
    last_ = sample;
    return actions;
}

}  // namespace curette::input
