#pragma once
// What input asks of the scene. Input never touches the scene (input/ sees base/ only: docs/architecture.md,
// "Layers"): it emits these, and the session layer applies them (session/interaction.h). Camera-frame motion
// stays camera-frame here, because input never reads render state; the session turns it into world motion
// with the frame's camera.

#include <glm/glm.hpp>

#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace curette::input {

enum class MotionFrame { Camera, World };  // camera: (right, up, forward into the screen)

struct MoveMesh {
    int mesh = 0;
    MotionFrame frame = MotionFrame::Camera;
    glm::dvec3 translationMm{0.0};
    glm::dvec3 rotationRad{0.0};   // axis * angle, about the mesh's origin
};
// A rigid motion of a mesh in world space about a point: turned by rotationRad (axis * angle) about pivotMm,
// then moved by translationMm. A tracked hand holding the mesh (input/tracked_hand.h): the grip's motion of
// one frame, so the mesh keeps its place in the hand.
struct GripMesh {
    int mesh = 0;
    glm::dvec3 pivotMm{0.0};
    glm::dvec3 translationMm{0.0};
    glm::dvec3 rotationRad{0.0};
};
// The mesh's scale multiplied by `factor` on every axis (a held mesh scaled by a thumbstick).
struct ScaleMesh {
    int mesh = 0;
    double factor = 1.0;
};
struct DragMesh {                  // a mouse drag in the view plane, in pixels (+x right, +y down)
    int mesh = 0;
    glm::dvec2 pixels{0.0};
};
struct SelectMesh {                // a binding now holds another mesh
    int binding = 0;
    int mesh = 0;
};
struct SetShading {
    std::string mode;              // "solid", "phong", "lao", "cao", "dos", "ismos"
};
struct CycleShading {};
struct ResetPose {
    int mesh = 0;
};
struct AddMesh {};
struct RemoveMesh {
    int mesh = 0;
};
// Lights (any shading mode; ismos shadows follow them): turn the light's direction in the camera frame, yaw
// about the camera's up axis (+: towards the right of the screen) and pitch towards it (+: up), in radians.
// light -1: the selected light (NextLight selects the next one). The session applies it (turnedLight in
// session/interaction.h), with the frame's camera for world-space lights.
struct MoveLight {
    int light = -1;
    glm::dvec2 yawPitchRad{0.0};
};
struct NextLight {};
struct ToggleRecording {};
struct Screenshot {};
// Drilling (session/drilling.h): a device emits HoldDrill every frame the mesh's drill control is down (erase:
// its restore control); the session removes what the mesh sweeps that frame. On the press of Undo / Redo the
// session undoes or redoes the last step of its history: a stroke or a frame's setting edits.
struct HoldDrill {
    int mesh = 0;
    bool erase = false;
};
struct Undo {};
struct Redo {};

// A mesh's drill and erase controls (every device's, one rule): either held drills this frame, drill over erase.
inline std::optional<HoldDrill> heldDrill(int mesh, bool drill, bool erase) {
    if (!drill && !erase) return std::nullopt;
    return HoldDrill{mesh, !drill};
}

using Action = std::variant<MoveMesh, GripMesh, ScaleMesh, DragMesh, SelectMesh, SetShading, CycleShading, ResetPose, AddMesh, RemoveMesh,
                            ToggleRecording, Screenshot, MoveLight, NextLight, HoldDrill, Undo, Redo>;

}  // namespace curette::input
