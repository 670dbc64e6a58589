#pragma once
// A tracked controller (an OpenXR hand, xr/controller_actions.h) as an action source, beside the SpaceMouse
// and the gamepad: while its squeeze is held the hand holds its clip mesh, which follows the grip rigidly
// (each frame's motion of the grip, a GripMesh turning about the grip), its thumbstick scales it and its
// trigger drills with it (HoldDrill: session/drilling.h); its button cycles the shading. It sees
// world poses only: the caller places the room in the scene (render/model/tracked_view.h).

#include "input/actions.h"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <vector>

namespace curette::input {

struct HandSample {
    bool tracked = false;
    glm::dvec3 gripMm{0.0};                         // the grip, world (RAS) mm
    glm::dquat gripOrientation{1.0, 0.0, 0.0, 0.0}; // world
    double squeeze = 0.0;                           // 0..1
    double trigger = 0.0;                           // 0..1
    bool cycleShading = false;                      // the button went down this frame
    double thumbstickY = 0.0;                       // -1..1: up grows the held mesh, down shrinks it
    double dtSeconds = 0.0;                         // since the last sample
};

// Hysteresis of an analog control (the squeeze grabs, the trigger drills): pressed from kGrabAt, released
// below kReleaseBelow, so a finger resting near one value does not grab and drop the mesh (or open and close
// a drill stroke, each an undo step) frame after frame.
inline constexpr double kGrabAt = 0.7;
inline constexpr double kReleaseBelow = 0.3;
bool analogHeld(bool wasHeld, double value);
// The thumbstick scales a held mesh by up to this factor a second (full deflection), past a dead zone that
// keeps a resting stick's drift from scaling it.
inline constexpr double kScalePerSecond = 2.0;
inline constexpr double kThumbstickDeadZone = 0.15;

class TrackedHand {
public:
    explicit TrackedHand(int mesh) : mesh_(mesh) {}
    // The actions of one frame. The first tracked frame of a grab moves nothing (it is the grab's start); a
    // frame without tracking drops the mesh where it is. The trigger drills only with a mesh in hand.
    std::vector<Action> step(const HandSample& sample);
    bool holding() const { return holding_; }
    bool drilling() const { return drilling_; }
    int mesh() const { return mesh_; }

private:
    int mesh_;
    bool holding_ = false, drilling_ = false;
    HandSample last_;
};

}  // namespace curette::input
