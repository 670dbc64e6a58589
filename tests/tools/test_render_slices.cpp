// `curette render --slices DIR` as a user runs it: the three slice views of a scene with a clip mesh, the
// removed region tinted where the mesh carves, the mesh's cross-section outlined, and every pixel equal to
// what the GL-free slice function (render/model/slice_view.h, which the viewer's slice panel draws) makes
// of the same inputs. And the viewer's panel: it makes its images only when their inputs change, scrolls
// and clicks move the crosshair.
#include "render/model/slice_view.h"
#include "render/renderer.h"
#include "scene/volume_statistics.h"
#include "session/carve_report.h"
#include "session/loaded_scene.h"
#include "session/scene_slices.h"
#include "tools/commands/commands.h"
#include "viewer/slice_panel.h"

#include "tests/tools/run_curette.h"
#include "tests/tools/tool_test_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <memory>

namespace curette {
namespace {

namespace fs = std::filesystem;
using testing::runCurette;

// The noisy ball (2 mm voxels, centre at 31 mm on each axis, core radius 18 mm) carved by a 14 mm sphere in
// its core.
const glm::dvec3 kMeshCentre(31.0, 33.0, 31.0);
constexpr double kMeshRadius = 14.0;

fs::path carvedBallScene(const std::string& name) {
    fs::path dir = testing::freshScratchFolder("curette-slices", name);
    nlohmann::json changes = nlohmann::json::parse(R"({"clip_meshes": [
        {"name": "sphere", "mesh": {"shape": "sphere", "radius_mm": 14}, "position_mm": [31, 33, 31]}]})");
    return testing::writeNoisyBallScene(dir, changes);
}

gl::Context& context() {
    static std::unique_ptr<gl::Context> c = gl::createHeadlessContext();
    c->makeCurrent();
    return *c;
}

glm::ivec3 rgbAt(const testing::Png& png, int x, int y) {
    std::size_t at = 4 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(png.width) + static_cast<std::size_t>(x));
    return {png.rgba[at], png.rgba[at + 1], png.rgba[at + 2]};
}

TEST(RenderSlices, WritesTheThreeViewsWithTheCarveAndTheyEqualTheSliceFunction) {
    fs::path scene = carvedBallScene("carved");
    fs::path out = scene.parent_path() / "slices";
    testing::Invocation run = runCurette("render --scene " + scene.string() + " --slices " + out.string());
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_NE(run.output.find("crosshair 31.00,33.00,31.00"), std::string::npos) << run.output;   // the mesh's centre
    EXPECT_FALSE(fs::exists(scene.parent_path() / "out.png"));

    // The same inputs in this process: the scene, its removed region as `curette report` computes it.
    LoadedScene loaded = loadSceneWithVolume(scene);
    Renderer renderer(context(), loaded.volume, loaded.scene.transferFunction);
    configureRenderer(loaded, renderer);
    InteractionState state = InteractionState::fromScene(loaded.scene);
    CarveReporter reporter(loaded, renderer.geometry(), commands::programVersion());
    reporter.compute(renderer.clipMeshes(), state);
    std::vector<std::uint8_t> removed = reporter.removedRegion();
    SliceOverlays overlays = sceneSliceOverlays(loaded, state, &removed, -1);
    GreyWindow window = defaultGreyWindow(computeStatistics(loaded.volume));

    for (SliceAxis axis : kSliceAxes) {
        testing::Png png = testing::readPng(out / (std::string(sliceAxisName(axis)) + ".png"));
        ASSERT_FALSE(png.rgba.empty()) << sliceAxisName(axis);
        SliceImage slice = renderSlice(loaded.volume, axis, kMeshCentre, window, overlays);
        ASSERT_EQ(png.width, slice.image.width);
        ASSERT_EQ(png.height, slice.image.height);
        EXPECT_EQ(png.rgba, toRgba8(slice.image, glm::vec4(0, 0, 0, 1))) << sliceAxisName(axis);

        // Read from the file alone: inside the mesh's section the pixels are tinted (grey plus 0.4 of the
        // orange: red exceeds blue by 0.4 * 0.9 of full scale), well outside it grey (r = g = b); on the
        // section's circle the mesh's colour. Pixels on the crosshair's lines and the letters are left out.
        glm::dvec2 centre = slice.plane.pixelAt(kMeshCentre);
        const double radiusPx = kMeshRadius / slice.plane.pixelMm;
        int tinted = 0, grey = 0, wrong = 0;
        const int w = png.width, h = png.height;
        auto onLetter = [&](int x, int y) {   // the 5x7 letters at the middle of each edge (slice_view.cpp)
            return (x >= w / 2 - 2 && x < w / 2 + 3 && (y < 9 || y >= h - 9)) || (y >= h / 2 - 3 && y < h / 2 + 4 && (x < 7 || x >= w - 7));
        };
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                if (x == int(std::floor(centre.x)) || y == int(std::floor(centre.y)) || onLetter(x, y)) continue;
                double r = glm::length(glm::dvec2(x + 0.5, y + 0.5) - centre);
                glm::ivec3 c = rgbAt(png, x, y);
                if (r < radiusPx - 1.5) {
                    if (std::abs(c.r - c.b - 92) <= 1) ++tinted;
                    else ++wrong;
                } else if (r > radiusPx + 1.5) {
                    if (c.r == c.g && c.g == c.b) ++grey;
                    else ++wrong;
                }
            }
        EXPECT_EQ(wrong, 0) << sliceAxisName(axis);
        EXPECT_GT(tinted, 50) << sliceAxisName(axis);
        EXPECT_GT(grey, 300) << sliceAxisName(axis);
        const std::vector<std::uint8_t> meshBytes = toRgba8(Image{1, 1, {glm::vec4(kMeshColor, 1.0f)}}, glm::vec4(0, 0, 0, 1));
        const glm::ivec3 meshRgb(meshBytes[0], meshBytes[1], meshBytes[2]);
        for (int k = 0; k < 48; ++k) {
            double angle = 2 * M_PI * (k + 0.5) / 48;
            glm::ivec2 p(glm::floor(centre + radiusPx * glm::dvec2(std::cos(angle), std::sin(angle))));
            bool near = false;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) near = near || rgbAt(png, p.x + dx, p.y + dy) == meshRgb;
            EXPECT_TRUE(near) << sliceAxisName(axis) << " angle " << angle;
        }
    }
}

TEST(RenderSlices, TheCrosshairOptionPlacesTheSlicesAndIsChecked) {
    fs::path scene = carvedBallScene("crosshair");
    fs::path out = scene.parent_path() / "slices";
    testing::Invocation run = runCurette("render --scene " + scene.string() + " --slices " + out.string() + " --crosshair 20,25.5,40");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_NE(run.output.find("crosshair 20.00,25.50,40.00"), std::string::npos) << run.output;
    for (const char* bad : {"20,25", "20,25,x", "20,25,40,1"}) {
        testing::Invocation r = runCurette("render --scene " + scene.string() + " --slices " + out.string() + " --crosshair " + bad);
        EXPECT_NE(r.exitCode, 0) << bad;
        EXPECT_NE(r.output.find("--crosshair"), std::string::npos) << r.output;
    }
    testing::Invocation alone = runCurette("render --scene " + scene.string() + " --crosshair 1,2,3 --out x.png");
    EXPECT_NE(alone.exitCode, 0);
    EXPECT_NE(alone.output.find("--slices"), std::string::npos) << alone.output;
}

TEST(RenderSlices, WithOutItAlsoRendersTheFrame) {
    fs::path scene = carvedBallScene("both");
    fs::path out = scene.parent_path() / "slices", png = scene.parent_path() / "frame.png";
    testing::Invocation run = runCurette("render --scene " + scene.string() + " --slices " + out.string() + " --out " + png.string());
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_FALSE(testing::readPng(png).rgba.empty());
    EXPECT_FALSE(testing::readPng(out / "sagittal.png").rgba.empty());
}

TEST(SlicePanel, MakesImagesOnlyWhenTheirInputsChangeAndTheMouseMovesTheCrosshair) {
    fs::path scene = carvedBallScene("panel");
    LoadedScene loaded = loadSceneWithVolume(scene);
    InteractionState state = InteractionState::fromScene(loaded.scene);
    SlicePanel panel(loaded, state);
    EXPECT_EQ(panel.crosshair(), kMeshCentre);
    EXPECT_TRUE(panel.update(state, 0));
    EXPECT_FALSE(panel.update(state, 0));
    EXPECT_EQ(panel.imageCount(), 1u);
    // The same images as render --slices makes (no removed region here: no report was taken).
    SliceImage axial = renderSlice(loaded.volume, SliceAxis::Axial, kMeshCentre, defaultGreyWindow(computeStatistics(loaded.volume)),
                                   sceneSliceOverlays(loaded, state, nullptr, 0));
    EXPECT_EQ(panel.image(SliceAxis::Axial).image.pixels, axial.image.pixels);

    state.meshes[0].pose.position.x += 1.0;   // a mesh moved
    EXPECT_TRUE(panel.update(state, 0));
    EXPECT_TRUE(panel.update(state, -1));     // the held mesh changed
    EXPECT_FALSE(panel.update(state, -1));

    panel.scroll(SliceAxis::Coronal, 2.0);    // two pixel spacings (2 mm) towards anterior
    EXPECT_EQ(panel.crosshair(), kMeshCentre + glm::dvec3(0, 4, 0));
    EXPECT_TRUE(panel.update(state, -1));
    panel.scroll(SliceAxis::Sagittal, -1.0);
    EXPECT_EQ(panel.crosshair(), kMeshCentre + glm::dvec3(-2, 4, 0));

    const SlicePlane& plane = panel.image(SliceAxis::Axial).plane;
    glm::dvec3 clicked = panel.click(SliceAxis::Axial, {3.5, 7.25});
    EXPECT_EQ(panel.crosshair(), clicked);
    EXPECT_NEAR(clicked.z, kMeshCentre.z, 1e-9);   // in the axial plane through the crosshair
    glm::dvec2 back = plane.pixelAt(clicked);
    EXPECT_NEAR(back.x, 3.5, 1e-9);
    EXPECT_NEAR(back.y, 7.25, 1e-9);
    EXPECT_TRUE(panel.update(state, -1));
    EXPECT_EQ(panel.imageCount(), 5u);
    panel.setWindow({0.0, 50.0});
    EXPECT_TRUE(panel.update(state, -1));
}

}  // namespace
}  // namespace curette
