// The scene's ISMOS keys: "ismos": {...} and each light's "disk_radius" and "spot" (render/model/frame.h).
#include "scene/scene.h"
#include "base/error.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace curette {
namespace {

const std::filesystem::path kScenes = std::filesystem::path(CURETTE_SOURCE_DIR) / "assets" / "scenes";
const std::string kVolume = R"("volume": {"path": "/usr/share/mricron/templates/ch2.nii.gz"}, "transfer_function": "../tf/mri_t1.json")";

TEST(SceneIsmos, KeysReachTheFrame) {
    Scene s = parseScene("{" + kVolume + R"(, "shading": "ismos",
        "lights": [{"direction": [1, 0, 1]}, {"direction": [0, 1, 1], "disk_radius": 0.05, "spot": {"angle_deg": 12, "target": [1, 2, 3]}}],
        "ismos": {"occlusion": "full", "opacity": "fit", "layers": 2, "blend_layers": false, "light_samples": 8, "test_points": 24,
                  "hemisphere_radius": 3, "disk_radius": 0.1, "ambient": 0.2, "opacity_threshold": 0.4, "depth_bias": 0.02,
                  "falloff": true, "light_positions": "sphere", "base": "solid"}})",
                         kScenes / "test.json");
    EXPECT_EQ(s.shading, ShadingMode::Ismos);
    const IsmosSettings& i = s.ismos;
    EXPECT_FALSE(i.partial);
    EXPECT_TRUE(i.fit);
    EXPECT_EQ(i.layers, 2);
    EXPECT_FALSE(i.blendLayers);
    EXPECT_EQ(i.lightSamples, 8);
    EXPECT_EQ(i.testPoints, 24);
    EXPECT_DOUBLE_EQ(i.hemisphereRadius, 3);
    EXPECT_DOUBLE_EQ(i.diskRadius, 0.1);
    EXPECT_DOUBLE_EQ(i.ambient, 0.2);
    EXPECT_DOUBLE_EQ(i.opacityThreshold, 0.4);
    EXPECT_DOUBLE_EQ(i.depthBias, 0.02);
    EXPECT_TRUE(i.falloff);
    EXPECT_TRUE(i.sphere);
    EXPECT_EQ(i.base, ShadingMode::Solid);
    ASSERT_EQ(i.lightShapes.size(), 2u);
    EXPECT_LT(i.lightShapes[0].diskRadius, 0);   // the default
    EXPECT_EQ(i.lightShapes[0].spotAngleDeg, 0);
    EXPECT_DOUBLE_EQ(i.lightShapes[1].diskRadius, 0.05);
    EXPECT_DOUBLE_EQ(i.lightShapes[1].spotAngleDeg, 12);
    EXPECT_EQ(i.lightShapes[1].spotTarget, glm::dvec3(1, 2, 3));
    VolumeGeometry g{glm::ivec3(8), glm::dmat4(1.0)};
    EXPECT_EQ(initialFrame(s, g).ismos, s.ismos);
}

TEST(SceneIsmos, BadValuesNameTheirKey) {
    auto fieldOf = [](const std::string& extra) {
        try {
            parseScene("{" + kVolume + ", " + extra + "}", kScenes / "test.json");
        } catch (const InputError& e) {
            return e.field();
        }
        return std::string("no error");
    };
    EXPECT_EQ(fieldOf(R"("ismos": {"layers": 5})"), "ismos.layers");
    EXPECT_EQ(fieldOf(R"("ismos": {"occlusion": "some"})"), "ismos.occlusion");
    EXPECT_EQ(fieldOf(R"("ismos": {"lights": 2})"), "ismos.lights");
    EXPECT_EQ(fieldOf(R"("lights": [{"direction": [0, 0, 1], "spot": {"angle": 3}}])"), "lights[0].spot.angle_deg");
}

}  // namespace
}  // namespace curette
