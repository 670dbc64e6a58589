// `curette render --show-meshes`: the clip meshes drawn over the image (render/clip_mesh_overlay.h). The PNG
// differs from the plain render only on the mesh's projected disc (the pixel rays that meet the sphere, plus a
// pixel); without the flag it is the renderer's own image, whatever the scene's display settings; the scene's
// "show": true does what the flag does; stereo is refused.
#include "tests/tools/run_curette.h"
#include "tests/tools/tool_test_support.h"

#include "render/reference/camera_ray.h"
#include "render/renderer.h"
#include "session/loaded_scene.h"

#include <gtest/gtest.h>

namespace curette {
namespace {

using testing::Png;
using testing::readPng;
using testing::runCurette;

const glm::dvec3 kSphereCentre(38.0, 26.0, 40.0);
constexpr double kSphereRadiusMm = 8.0;

std::filesystem::path writeScene(const std::filesystem::path& dir, const nlohmann::json& display = nullptr) {
    nlohmann::json changes = nlohmann::json::parse(R"({"shading": "phong", "image": {"width": 160, "height": 128},
        "clip_meshes": [{"name": "sphere", "mesh": {"shape": "sphere", "radius_mm": 8}, "position_mm": [38, 26, 40]}]})");
    if (!display.is_null()) changes["clip_mesh_display"] = display;
    return testing::writeNoisyBallScene(dir, changes);
}

Png renderPng(const std::filesystem::path& scene, const std::string& options, const std::string& name) {
    std::filesystem::path out = scene.parent_path() / name;
    testing::Invocation r = runCurette("render --scene " + scene.string() + " --out " + out.string() + " " + options);
    EXPECT_EQ(r.exitCode, 0) << r.output;
    return readPng(out);
}

bool samePixel(const Png& a, const Png& b, int x, int y) {
    std::size_t i = (static_cast<std::size_t>(y) * a.width + x) * 4;
    return std::equal(a.rgba.begin() + i, a.rgba.begin() + i + 4, b.rgba.begin() + i);
}

TEST(ShowMeshes, TheOverlayChangesOnlyTheMeshsDiscAndTheFlagOffIsTheRenderersImage) {
    auto dir = testing::freshScratchFolder("curette-show-meshes", "disc");
    std::filesystem::path scene = writeScene(dir);
    Png plain = renderPng(scene, "", "plain.png");
    Png shown = renderPng(scene, "--show-meshes", "shown.png");
    ASSERT_EQ(plain.width, 160);
    ASSERT_EQ(shown.width, plain.width);
    ASSERT_EQ(shown.height, plain.height);

    // The scene in-process, as `render` loads it.
    LoadedScene loaded = loadSceneWithVolume(scene);
    auto context = gl::createHeadlessContext();
    Renderer renderer(*context, loaded.volume, loaded.scene.transferFunction);
    configureRenderer(loaded, renderer);
    FrameDescription frame = initialFrame(loaded.scene, renderer.geometry());

    // The disc: pixels whose ray (the ray caster's, reference::cameraRay) passes within the radius plus a pixel.
    const double pixelMm = glm::length(kSphereCentre - frame.camera.position()) / frame.camera.pixelsPerMmAtUnitDepth(frame.size.y);
    int changed = 0, changedOff = 0, discPixels = 0;
    for (int y = 0; y < plain.height; ++y)
        for (int x = 0; x < plain.width; ++x) {
            reference::CameraRay ray = reference::cameraRay(frame, {x, y});
            glm::dvec3 toCentre = kSphereCentre - ray.origin;
            double d = glm::length(toCentre - glm::dot(toCentre, ray.direction) * ray.direction);
            discPixels += d < kSphereRadiusMm;
            if (!samePixel(plain, shown, x, y)) {
                ++changed;
                changedOff += d > kSphereRadiusMm + pixelMm;
            }
        }
    EXPECT_GT(discPixels, 100) << "the sphere is in view at a size worth comparing";
    EXPECT_GT(changed, discPixels * 9 / 10) << "the overlay covers the disc";
    EXPECT_EQ(changedOff, 0) << "a pixel more than one pixel off the disc changed";

    // Without the flag: the renderer's own image, bit for bit.
    renderer.render(frame);
    EXPECT_EQ(toRgba8(renderer.readImage(), glm::vec4(loaded.scene.background)), plain.rgba);
}

TEST(ShowMeshes, TheScenesDisplaySettingsDoNothingUnlessShownAndShowDoesWhatTheFlagDoes) {
    auto folder = [](const std::string& name) { return testing::freshScratchFolder("curette-show-meshes", name); };
    Png plain = renderPng(writeScene(folder("plain")), "", "plain.png");
    Png hidden = renderPng(writeScene(folder("hidden"), {{"show", false}, {"opacity", 0.9}}), "", "hidden.png");
    EXPECT_EQ(hidden.rgba, plain.rgba) << "\"show\": false with other opacities changes nothing";
    Png flag = renderPng(writeScene(folder("flag")), "--show-meshes", "flag.png");
    Png key = renderPng(writeScene(folder("key"), {{"show", true}}), "", "key.png");
    EXPECT_EQ(key.rgba, flag.rgba) << "\"show\": true draws what --show-meshes draws";
    EXPECT_NE(key.rgba, plain.rgba);
    Png opaque = renderPng(writeScene(folder("opaque"), {{"opacity", 0.6}}), "--show-meshes", "opaque.png");
    EXPECT_NE(opaque.rgba, flag.rgba) << "the scene's opacity is the overlay's";
}

TEST(ShowMeshes, StereoIsRefused) {
    auto dir = testing::freshScratchFolder("curette-show-meshes", "stereo");
    std::filesystem::path scene = writeScene(dir);
    testing::Invocation r = runCurette("render --scene " + scene.string() + " --out " + (dir / "s.png").string() + " --stereo anaglyph --show-meshes");
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.output.find("--show-meshes"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "s.png"));
}

}  // namespace
}  // namespace curette
