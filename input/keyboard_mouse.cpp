#include "input/keyboard_mouse.h"

#include <algorithm>
#include <numbers>

namespace curette::input {

std::vector<Action> KeyboardMapper::update(const KeyboardMouseState& s, double dt, int meshCount) {
    std::vector<Action> actions;
    std::uint64_t pressed = s.keys & ~previous_;
    previous_ = s.keys;
    auto edge = [&](Key k) { return (pressed >> static_cast<int>(k)) & 1u; };
    auto held = [&](Key k) { return s.down(k) ? 1.0 : 0.0; };
    const char* modes[] = {"solid", "phong", "lao", "cao", "dos"};
    for (int m = 0; m < 5; ++m)
        if (edge(static_cast<Key>(static_cast<int>(Key::Digit1) + m))) actions.push_back(SetShading{modes[m]});
    if (edge(Key::Digit6)) actions.push_back(SetShading{"ismos"});
    if (edge(Key::C)) actions.push_back(CycleShading{});
    if (edge(Key::F9)) actions.push_back(ToggleRecording{});
    if (edge(Key::P) || edge(Key::F12)) actions.push_back(Screenshot{});
    if (edge(Key::Insert)) actions.push_back(AddMesh{});
    // Lights need no mesh.
    if (edge(Key::O)) actions.push_back(NextLight{});
    if (edge(Key::Undo)) actions.push_back(Undo{});
    if (edge(Key::Redo)) actions.push_back(Redo{});
    constexpr double degToRad = std::numbers::pi / 180.0;
    glm::dvec2 turn = glm::dvec2(held(Key::L) - held(Key::J), held(Key::I) - held(Key::K)) * (rotationSpeed_ * dt * degToRad);
    turn += glm::dvec2(s.lightDragPixels.x, -s.lightDragPixels.y) * (kLightDegPerPixel * degToRad);   // +y down on screen
    if (turn != glm::dvec2(0.0)) actions.push_back(MoveLight{-1, turn});
    if (meshCount == 0) return actions;
    selected_ = std::clamp(selected_, 0, meshCount - 1);
    if (edge(Key::Tab)) {
        selected_ = (selected_ + 1) % meshCount;
        actions.push_back(SelectMesh{-1, selected_});  // binding -1: the keyboard
    }
    if (edge(Key::R)) actions.push_back(ResetPose{selected_});
    if (edge(Key::Delete)) actions.push_back(RemoveMesh{selected_});
    glm::dvec3 t(held(Key::D) - held(Key::A), held(Key::E) - held(Key::Q), held(Key::W) - held(Key::S));
    glm::dvec3 r(held(Key::Up) - held(Key::Down), held(Key::Right) - held(Key::Left), held(Key::PageUp) - held(Key::PageDown));
    t *= translationSpeed_ * dt;
    r *= rotationSpeed_ * dt * std::numbers::pi / 180.0;
    if (t != glm::dvec3(0.0) || r != glm::dvec3(0.0)) actions.push_back(MoveMesh{selected_, MotionFrame::Camera, t, r});
    if (s.rightDragPixels != glm::dvec2(0.0)) actions.push_back(DragMesh{selected_, s.rightDragPixels});
    // Held, not pressed: the mesh drills every frame the key is down (a stroke lasts as long).
    if (s.down(Key::Drill) || s.down(Key::Erase)) actions.push_back(HoldDrill{selected_, !s.down(Key::Drill)});
    return actions;
}

}  // namespace curette::input
