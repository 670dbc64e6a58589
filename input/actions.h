#pragma once
// What input asks of the scene. Input never touches the scene (DESIGN.md): it emits these, and the app
// applies them (app/interaction.h). Camera-frame motion stays camera-frame here, because input never reads
// render state; the app turns it into world motion with the frame's camera.

#include <glm/glm.hpp>

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
struct DragMesh {                  // a mouse drag in the view plane, in pixels (+x right, +y down)
    int mesh = 0;
    glm::dvec2 pixels{0.0};
};
struct SelectMesh {                // a binding now holds another mesh
    int binding = 0;
    int mesh = 0;
};
struct SetShading {
    std::string mode;              // "solid", "phong", "lao", "cao", "dos"
};
struct CycleShading {};
struct ResetPose {
    int mesh = 0;
};
struct AddMesh {};
struct RemoveMesh {
    int mesh = 0;
};
struct ToggleRecording {};
struct Screenshot {};

using Action = std::variant<MoveMesh, DragMesh, SelectMesh, SetShading, CycleShading, ResetPose, AddMesh, RemoveMesh,
                            ToggleRecording, Screenshot>;

}  // namespace curette::input
