#pragma once
// Keyboard and mouse, the fallback with the same actions as the devices: the viewer (tools/commands/view.cpp)
// fills a plain state from GLFW each frame (and records it), and this turns it into actions for the selected
// mesh. Fixed keys:
// W/S forward/back, A/D left/right, Q/E down/up (camera frame); Up/Down pitch, Left/Right yaw,
// PageUp/PageDown roll; right-drag moves in the view plane; Tab next mesh; R reset; Insert add; Delete
// remove; 1-6 solid/phong/lao/cao/dos/ismos; C cycle shading; F9 recording; P or F12 screenshot; Shift fine steps.
// Drilling (session/drilling.h) with the selected mesh: B held drills, N held erases (B wins when both are);
// Ctrl+Z undoes the last stroke or setting edit, Ctrl+Shift+Z or Ctrl+Y redoes it (on press; the viewer sets Undo / Redo for them).
// Lights: J/L turn the selected light left/right (yaw about the camera's up axis), I/K raise/lower it, O selects
// the next light, at the keyboard's degrees per second; a Shift + left drag turns it by kLightDegPerPixel
// (right: towards the right of the screen, up: up).

#include "input/actions.h"

#include <cstdint>

namespace curette::input {

enum class Key : int {
    W, A, S, D, Q, E, Up, Down, Left, Right, PageUp, PageDown, Tab, R, Insert, Delete, Digit1, Digit2, Digit3, Digit4,
    Digit5, C, F9, P, F12,
    Digit6,   // after the others: recorded sessions store keys as bits, and old ones keep their meaning
    I, J, K, L, O,   // lights (session version 2)
    Fine,            // Shift held: mesh motion from keys and devices at kFineStepFactor of its speed
    Drill, Erase, Undo, Redo,   // drilling (session version 6): B, N, Ctrl+Z, Ctrl+Shift+Z / Ctrl+Y
    Count
};

struct KeyboardMouseState {
    std::uint64_t keys = 0;          // bit per Key
    glm::dvec2 rightDragPixels{0.0}; // mouse motion this frame while the right button is held
    glm::dvec2 lightDragPixels{0.0}; // mouse motion this frame while Shift + the left button are held
    bool down(Key k) const { return (keys >> static_cast<int>(k)) & 1u; }
    void press(Key k) { keys |= keyBit(k); }
    static std::uint64_t keyBit(Key k) { return std::uint64_t{1} << static_cast<int>(k); }
    bool operator==(const KeyboardMouseState&) const = default;
};

static_assert(static_cast<int>(Key::Count) <= 64, "keys are recorded as the bits of one 64-bit word");

// Fine steps (Shift held) scale every mesh motion of the frame, from the keys and from the devices, so a mesh
// can be placed to a fraction of a millimetre (input/pipeline.cpp).
inline constexpr double kFineStepFactor = 0.1;

// A Shift + left drag turns the selected light by this much per framebuffer pixel.
inline constexpr double kLightDegPerPixel = 0.25;

struct KeyboardMapperState {
    std::uint64_t previousKeys = 0;
    int selectedMesh = 0;
    bool operator==(const KeyboardMapperState&) const = default;
};

class KeyboardMapper {
public:
    KeyboardMapper(double translationMmPerSecond = 40.0, double rotationDegPerSecond = 60.0)
        : translationSpeed_(translationMmPerSecond), rotationSpeed_(rotationDegPerSecond) {}
    std::vector<Action> update(const KeyboardMouseState& state, double dt, int meshCount);
    int selectedMesh() const { return selected_; }
    void select(int mesh) { selected_ = mesh; }   // as Tab would (clamped to the meshes at the next update)
    KeyboardMapperState state() const { return {previous_, selected_}; }
    void restore(const KeyboardMapperState& state) { previous_ = state.previousKeys, selected_ = state.selectedMesh; }

private:
    double translationSpeed_, rotationSpeed_;
    std::uint64_t previous_ = 0;
    int selected_ = 0;
};

}  // namespace curette::input
