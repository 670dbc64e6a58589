// The viewer's panels (viewer/view_panels.h) driven like a user drives them, with Dear ImGui running headless
// (no window, no GL: only its frame logic): dragging an opacity point is a transfer-function edit whose value
// is the scene's TF JSON with that point moved, and applying it changes the state's TF exactly so.
#include "viewer/view_panels.h"

#include <imgui.h>

#include <gtest/gtest.h>

namespace curette {
namespace {

LoadedScene smallScene(const std::string& gradientOpacity = "") {
    LoadedScene loaded;
    loaded.scene = parseScene(R"({"volume": {"path": "x.raw", "format": "raw", "raw": {"dims": [4, 4, 4], "type": "uint8"}},
        "transfer_function": {"color": [[0, 0, 0, 0], [255, 1, 1, 1]], "opacity": [[0, 0], [100, 0.2], [255, 0.8]])" +
                                  gradientOpacity + "}}",
                              "scene.json");
    loaded.volume.dims = {4, 4, 4};
    loaded.volume.format = StorageFormat::UNorm8;
    loaded.volume.valueScale = 255.0;   // physical = stored
    loaded.volume.voxels.assign(64, 0);
    for (std::size_t i = 0; i < 64; ++i) loaded.volume.voxels[i] = static_cast<std::uint8_t>(4 * i);
    loaded.volume.maxValue = 252;
    return loaded;
}

struct Gui {
    Gui() {
        ImGui::CreateContext();
        ImGuiIO& io = ImGui::GetIO();
        io.IniFilename = nullptr;
        io.DisplaySize = ImVec2(1000, 900);
        io.DeltaTime = 1.0f / 60.0f;
        unsigned char* pixels = nullptr;
        int w = 0, h = 0;
        io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
    }
    ~Gui() { ImGui::DestroyContext(); }
    input::InputPipeline input{input::defaultMapping(), 40.0, 60.0};   // no devices: the keyboard holds a mesh
    std::vector<SettingEdit> frame(ViewPanels& panels, const InteractionState& state, ImVec2 mouse, bool down) {
        ImGuiIO& io = ImGui::GetIO();
        io.MousePos = mouse;
        io.MouseDown[0] = down;
        ImGui::NewFrame();
        ImGui::SetNextWindowPos(ImVec2(0, 0));
        ImGui::SetNextWindowSize(ImVec2(420, 900));
        ImGui::Begin("settings");   // the side bar's tab in the viewer
        std::vector<SettingEdit> edits = panels.draw(state, OrbitCamera{}, input);
        ImGui::End();
        ImGui::Render();
        return edits;
    }
};

TEST(ViewPanels, DraggingAnOpacityPointIsATransferFunctionEdit) {
    LoadedScene loaded = smallScene();
    InteractionState state = InteractionState::fromScene(loaded.scene);
    ViewPanels panels(loaded, std::filesystem::path(CURETTE_SOURCE_DIR) / "assets" / "tf");
    EXPECT_GE(panels.presets().size(), 4u) << "the shipped presets are offered";
    Gui gui;
    EXPECT_TRUE(gui.frame(panels, state, ImVec2(-1, -1), false).empty()) << "no input, no edit";
    gui.frame(panels, state, ImVec2(-1, -1), false);
    const ViewPanels::Canvas& c = panels.transferFunctionCanvas();
    ASSERT_GT(c.w, 0);
    auto at = [&](double value, double alpha) {
        return ImVec2(c.x + c.w * static_cast<float>((value - c.lo) / (c.hi - c.lo)), c.y + c.h * static_cast<float>(1.0 - alpha));
    };
    // Press on the point (100, 0.2), then drag it up and right: to (about) value 150, alpha 0.6.
    ImVec2 start = at(100, 0.2), end = at(150, 0.6);
    gui.frame(panels, state, start, false);
    EXPECT_TRUE(gui.frame(panels, state, start, true).empty()) << "pressing alone moves nothing";
    std::vector<SettingEdit> edits = gui.frame(panels, state, end, true);
    ASSERT_EQ(edits.size(), 1u);
    EXPECT_EQ(edits[0].setting, Setting::TransferFunction);
    state.applyEdits(edits, "<panel>");
    ASSERT_EQ(state.transferFunction.opacity.size(), 3u);
    EXPECT_NEAR(state.transferFunction.opacity[1].value, 150, (c.hi - c.lo) / c.w) << "within a pixel";
    EXPECT_NEAR(state.transferFunction.opacity[1].y, 0.6, 1.0 / c.h);
    EXPECT_EQ(state.transferFunction.opacity[0].value, 0) << "the other points stay";
    EXPECT_EQ(state.transferFunction.opacity[2].y, 0.8);
    EXPECT_EQ(state.transferFunctionVersion, 1u);
    // Released: no more edits.
    EXPECT_TRUE(gui.frame(panels, state, end, false).empty());
}

// The gradient-opacity canvas edits its curve with the same rules as the opacity canvas (one function): a
// drag moves the point between its neighbours and is the same transfer-function edit, the opacity curve kept.
TEST(ViewPanels, DraggingAGradientOpacityPointIsATransferFunctionEdit) {
    LoadedScene loaded = smallScene(R"(, "gradient_opacity": [[0, 0], [20, 0.5], [60, 1]])");
    InteractionState state = InteractionState::fromScene(loaded.scene);
    ViewPanels panels(loaded, std::filesystem::path(CURETTE_SOURCE_DIR) / "assets" / "tf");
    Gui gui;
    gui.frame(panels, state, ImVec2(-1, -1), false);
    gui.frame(panels, state, ImVec2(-1, -1), false);
    const ViewPanels::Canvas& c = panels.gradientOpacityCanvas();
    ASSERT_GT(c.w, 0) << "drawn while the TF has gradient opacity";
    EXPECT_EQ(c.lo, 0);
    // The volume's values are 4 x linear index: central differences of 4, 16 and 64 per mm along x, y, z.
    EXPECT_NEAR(c.hi, std::sqrt(4.0 * 4 + 16 * 16 + 64 * 64), 1e-9) << "the canvas spans the volume's gradient magnitudes";
    EXPECT_GT(c.y, panels.transferFunctionCanvas().y + panels.transferFunctionCanvas().h) << "below the opacity canvas and the colour bar";
    auto at = [&](double g, double factor) {
        return ImVec2(c.x + c.w * static_cast<float>((g - c.lo) / (c.hi - c.lo)), c.y + c.h * static_cast<float>(1.0 - factor));
    };
    // Press on (20, 0.5) and drag towards 64 (beyond the next point, at 60) and factor 0.9.
    gui.frame(panels, state, at(20, 0.5), false);
    EXPECT_TRUE(gui.frame(panels, state, at(20, 0.5), true).empty());
    std::vector<SettingEdit> edits = gui.frame(panels, state, at(64, 0.9), true);
    ASSERT_EQ(edits.size(), 1u);
    EXPECT_EQ(edits[0].setting, Setting::TransferFunction);
    state.applyEdits(edits, "<panel>");
    const auto& g = state.transferFunction.gradientOpacity;
    ASSERT_EQ(g.size(), 3u);
    EXPECT_EQ(g[1].value, 60) << "held at its right neighbour";
    EXPECT_NEAR(g[1].y, 0.9, 1.0 / c.h);
    EXPECT_EQ(g[2].value, 60);
    EXPECT_EQ(g[0].y, 0);
    ASSERT_EQ(state.transferFunction.opacity.size(), 3u);
    EXPECT_EQ(state.transferFunction.opacity[1].value, 100) << "the opacity curve is not touched";
    EXPECT_TRUE(gui.frame(panels, state, at(64, 0.9), false).empty());
}

}  // namespace
}  // namespace curette
