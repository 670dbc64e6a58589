#pragma once
// The viewer's settings panels (Dear ImGui): the transfer function over the volume's histogram (and its
// gradient opacity over the volume's gradient magnitudes), shading and
// its settings, clip meshes, tubes and lights. A widget never changes the scene: it produces a SettingEdit
// (scene/setting_edit.h) whose value is the scene file's JSON of its key, and the frame loop hands the frame's
// edits to the session step, which applies them as it applies device actions (and a recording records them).
// The mesh panel's choice of which device holds which mesh is a hold request (input/pipeline.h) instead: it
// is input, not a setting, and goes to the input pipeline's next step (and is recorded with that frame).
// Call draw() inside a window (the side bar's Settings tab) between ImGui::NewFrame() and ImGui::Render(); it issues no GL call (the GL backend stays in
// tools/commands/view.cpp).

#include "session/interaction.h"
#include "session/loaded_scene.h"
#include "scene/setting_edit.h"
#include "input/pipeline.h"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace curette {

class ViewPanels {
public:
    // `presetDirectory`: where the TF presets are (assets/tf).
    ViewPanels(const LoadedScene& loaded, std::filesystem::path presetDirectory);

    // Draws the panels for `state` seen through `camera` (an added mesh goes to its target), with `input`'s
    // bindings and the meshes they hold, and returns the edits the user made. Messages (a file written, a
    // file refused) go to takeMessages(), the meshes chosen for a binding to takeHoldRequests() (for the
    // input pipeline's next step).
    std::vector<SettingEdit> draw(const InteractionState& state, const OrbitCamera& camera, const input::InputPipeline& input);
    std::vector<std::string> takeMessages() { return std::move(messages_); }
    std::vector<input::HoldRequest> takeHoldRequests() { return std::move(holdRequests_); }

    // Where the TF editor's opacity canvas was drawn last (screen pixels) and the value range it spans: a
    // point (value, alpha) is at (x + w (value - lo) / (hi - lo), y + h (1 - alpha)).
    struct Canvas {
        float x = 0, y = 0, w = 0, h = 0;
        double lo = 0, hi = 1;
    };
    const Canvas& transferFunctionCanvas() const { return canvas_; }
    // The gradient-opacity canvas below the colour bar (drawn while the TF has gradient opacity): a point
    // (|gradient|, factor) as above, over [0, the volume's largest gradient magnitude].
    const Canvas& gradientOpacityCanvas() const { return gradientCanvas_; }
    // The TF presets found (file names), for the combo.
    const std::vector<std::filesystem::path>& presets() const { return presets_; }

private:
    void transferFunctionPanel(const InteractionState& state, std::vector<SettingEdit>& edits);
    void shadingPanel(const InteractionState& state, std::vector<SettingEdit>& edits);
    void meshPanel(const InteractionState& state, const OrbitCamera& camera, const input::InputPipeline& input, std::vector<SettingEdit>& edits);
    void tubePanel(const InteractionState& state, std::vector<SettingEdit>& edits);
    void lightPanel(const InteractionState& state, std::vector<SettingEdit>& edits);
    void scenePanel(const InteractionState& state, const OrbitCamera& camera);

    const LoadedScene& loaded_;
    std::vector<std::filesystem::path> presets_;
    std::vector<double> histogram_;        // log(1 + count) per bin, over [valueMin_, valueMax_]
    double valueMin_ = 0, valueMax_ = 1;
    double maxGradient_ = 0;               // the volume's largest gradient magnitude (value units per mm)
    int draggedOpacity_ = -1, draggedGradient_ = -1, draggedColor_ = -1, selectedColor_ = -1;
    int addShape_ = 0;
    float addSizeMm_ = 30.0f;
    char tfPath_[512] = "transfer-function.json";
    char scenePath_[512] = "curette-scene.json";
    std::vector<std::string> messages_;
    std::vector<input::HoldRequest> holdRequests_;
    Canvas canvas_, gradientCanvas_;
};

// The shipped presets, assets/tf of the source tree the binary was built from.
std::filesystem::path shippedPresetDirectory();

// A primitive mesh description of `shape` (sphere, box, cylinder, cone, capsule, torus) whose main size is
// `sizeMm` (what primitiveSizeName says: a diameter, an edge, a length), as mesh/mesh_description.h reads it.
nlohmann::json primitiveMeshJson(const std::string& shape, double sizeMm);
const char* primitiveSizeName(const std::string& shape);
extern const char* const kPrimitiveShapes[6];

}  // namespace curette
