// The ray caster's phong placement (render/model/phong_shading_placement.h) on the shipped scenes' real data:
// Colin27 with the head TF, where a ray ends a short way into the skin, shades between rounds; with the glass
// TF of the tract scenes, where a ray crosses the whole head, in the loop (docs/measurements.md has both timed).
#include "session/loaded_scene.h"
#include "gl/context.h"
#include "render/renderer.h"

#include <gtest/gtest.h>

namespace curette {
namespace {

PhongShading placementOf(const char* sceneName) {
    static std::unique_ptr<gl::Context> context = gl::createHeadlessContext();
    context->makeCurrent();
    LoadedScene loaded = loadSceneWithVolume(std::filesystem::path(CURETTE_SOURCE_DIR) / "assets" / "scenes" / sceneName);
    Renderer renderer(*context, loaded.volume, loaded.scene.transferFunction);
    configureRenderer(loaded, renderer);
    return renderer.phongShading(initialFrame(loaded.scene, renderer.geometry()));
}

TEST(ShippedPhongShading, TheHeadShadesBetweenRoundsAndTheGlassHeadInTheLoop) {
    EXPECT_EQ(PhongShading::BetweenRounds, placementOf("head.json"));
    EXPECT_EQ(PhongShading::BetweenRounds, placementOf("head-carved.json"));
    EXPECT_EQ(PhongShading::InLoop, placementOf("plan-arcuate.json"));
    EXPECT_EQ(PhongShading::InLoop, placementOf("fibers.json"));
}

}  // namespace
}  // namespace curette
