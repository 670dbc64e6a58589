#pragma once
// A tracked controller (an OpenXR hand, xr/controller_actions.h) as an action source, beside the SpaceMouse
// and the gamepad: while its squeeze is held the hand holds its clip mesh, which follows the grip rigidly
// (each frame's motion of the grip, a GripMesh turning about the grip), its thumbstick scales it, its trigger
// drills with it and its erase button erases with it (HoldDrill: session/drilling.h, the gamepad's rule); a
// flick of the thumbstick left undoes (a stroke or a setting edit), right redoes; its button cycles the shading. A hand moving
// the volume (session/xr_hands.h) does not move its mesh: the mesh stays on the anatomy. It sees world poses
// only: the caller places the room in the scene (render/model/tracked_view.h).

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
    bool erase = false;                             // the erase button is held
    bool cycleShading = false;                      // the button went down this frame
    double thumbstickY = 0.0;                       // -1..1: up grows the held mesh, down shrinks it
    double thumbstickX = 0.0;                       // -1..1: a flick left undoes, right redoes
    bool movingVolume = false;                      // this hand carries the volume this frame
    double dtSeconds = 0.0;                         // since the last sample
};

// Hysteresis of an analog control (the squeeze grabs, the trigger drills, the stick flicks): pressed from
// kGrabAt, released below kReleaseBelow, so a finger resting near one value does not grab and drop the mesh
// (or open and close a drill stroke, each an undo step) frame after frame.
inline constexpr double kGrabAt = 0.7;
inline constexpr double kReleaseBelow = 0.3;
bool analogHeld(bool wasHeld, double value);
// The thumbstick scales a held mesh by up to this factor a second (full deflection), past a dead zone that
// keeps a resting stick's drift from scaling it.
inline constexpr double kScalePerSecond = 2.0;
inline constexpr double kThumbstickDeadZone = 0.15;

class TrackedHand {
public:
    // `flicks`: the thumbstick's sideways flicks undo and redo (sessions before version 7 recorded no intent for them).
    explicit TrackedHand(int mesh, bool flicks = true) : mesh_(mesh), flicks_(flicks) {}
    // The actions of one frame. The first tracked frame of a grab moves nothing (it is the grab's start); a
    // frame without tracking drops the mesh where it is. The trigger and the erase button drill only with a
    // mesh in hand; a flick acts once, when the stick passes kGrabAt sideways (more sideways than up or down).
    std::vector<Action> step(const HandSample& sample);
    bool holding() const { return holding_; }
    bool drilling() const { return drilling_; }
    int mesh() const { return mesh_; }

private:
    int mesh_;
    bool flicks_;
    bool holding_ = false, drilling_ = false;
    int flick_ = 0;   // -1 left, +1 right, 0 centred
    HandSample last_;
};

}  // namespace curette::input
