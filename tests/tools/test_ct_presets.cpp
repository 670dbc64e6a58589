// The CT presets proven on real CT: the shipped scenes dicom-ct-bone.json and dicom-ct-soft-tissue.json render
// pydicom's CT_small.dcm (a vertebra in Hounsfield units, read through GDCM) and show what each preset is for.
#include "session/loaded_scene.h"
#include "gl/context.h"
#include "render/renderer.h"

#include <gtest/gtest.h>

namespace curette {
namespace {

std::size_t coveredPixels(const char* sceneName) {
    static std::unique_ptr<gl::Context> context = gl::createHeadlessContext();
    context->makeCurrent();
    LoadedScene loaded = loadSceneWithVolume(std::filesystem::path(CURETTE_SOURCE_DIR) / "assets" / "scenes" / sceneName);
    Renderer renderer(*context, loaded.volume, loaded.scene.transferFunction);
    configureRenderer(loaded, renderer);
    FrameDescription frame = initialFrame(loaded.scene, renderer.geometry());
    frame.size = {64, 64};
    renderer.render(frame);
    Image image = renderer.readImage();
    std::size_t covered = 0;
    for (const glm::vec4& p : image.pixels) covered += p.a > 0.1f;
    return covered;
}

TEST(CtPresets, BoneAndSoftTissueShowTheVertebraOfPydicomsCtSlice) {
    std::size_t bone = coveredPixels("dicom-ct-bone.json");
    std::size_t soft = coveredPixels("dicom-ct-soft-tissue.json");
    // The vertebra covers a few hundred of the 4096 pixels; soft tissue adds the muscle and fat around it.
    EXPECT_GT(bone, 150u);
    EXPECT_LT(bone, 2000u) << "bone only, not the whole slice";
    EXPECT_GT(soft, bone + 300u) << "soft tissue shows the tissue around the bone too";
}

}  // namespace
}  // namespace curette
