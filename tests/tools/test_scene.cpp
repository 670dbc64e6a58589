// Scene files: every key read strictly, errors naming the key, relative paths, clip meshes.
#include "scene/scene.h"
#include "scene/scene_keys.h"
#include "render/model/setting_limits.h"
#include "base/error.h"
#include "base/json_reader.h"
#include "tests/tools/run_curette.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace curette {
namespace {

const std::filesystem::path kScenes = std::filesystem::path(CURETTE_SOURCE_DIR) / "assets" / "scenes";

Scene parse(const std::string& text) { return parseScene(text, kScenes / "test.json"); }

void expectError(const std::string& text, const std::string& field) {
    try {
        parse(text);
        FAIL() << "expected an error naming " << field;
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), field) << e.what();
    }
}

const std::string kVolume = R"("volume": {"path": "/usr/share/mricron/templates/ch2.nii.gz"}, "transfer_function": "../tf/mri_t1.json")";

TEST(Scene, ShippedScenesParse) {
    for (const auto& entry : std::filesystem::directory_iterator(kScenes)) {
        if (entry.path().extension() != ".json") continue;
        Scene s = loadScene(entry.path());
        EXPECT_FALSE(s.transferFunction.opacity.empty()) << entry.path();
    }
    Scene carved = loadScene(kScenes / "head-carved.json");
    EXPECT_EQ(carved.shading, ShadingMode::Cao);
    ASSERT_EQ(carved.clipMeshes.size(), 2u);
    EXPECT_EQ(carved.clipMeshes[0].name, "sphere");
    EXPECT_EQ(carved.lao.directions.count, 26);
}

TEST(Scene, TubesAreBuiltOnTheCpuUnlessTheSceneAsksOtherwise) {
    EXPECT_EQ(parse("{" + kVolume + "}").tubeBuild, TubeBuild::Cpu);
    EXPECT_EQ(parse("{" + kVolume + R"(, "tube_rendering": {"build": "gpu"}})").tubeBuild, TubeBuild::Gpu);
    EXPECT_EQ(parse("{" + kVolume + R"(, "tube_rendering": {"build": "cpu"}})").tubeBuild, TubeBuild::Cpu);
    EXPECT_EQ(parse("{" + kVolume + R"(, "tube_rendering": {"build": "impostor"}})").tubeBuild, TubeBuild::Impostor);
    EXPECT_THROW(parse("{" + kVolume + R"(, "tube_rendering": {"build": "fpga"}})"), InputError);
    EXPECT_EQ(loadScene(kScenes / "tracts-100k.json").tubeBuild, TubeBuild::Impostor);
}

TEST(Scene, ClipMeshDisplayIsTheCommandsDefaultUnlessTheSceneSaysHow) {
    Scene plain = parse("{" + kVolume + "}");
    EXPECT_FALSE(plain.clipMeshDisplay.show.has_value()) << "absent: off in render and exports, on in the viewer";
    EXPECT_EQ(plain.clipMeshDisplay.display, ClipMeshDisplay{});
    Scene shown = parse("{" + kVolume + R"(, "clip_mesh_display": {"show": true, "opacity": 0.4, "outline_opacity": 0.5}})");
    ASSERT_TRUE(shown.clipMeshDisplay.show.has_value());
    EXPECT_TRUE(*shown.clipMeshDisplay.show);
    EXPECT_DOUBLE_EQ(shown.clipMeshDisplay.display.fillOpacity, 0.4);
    EXPECT_DOUBLE_EQ(shown.clipMeshDisplay.display.outlineOpacity, 0.5);
    EXPECT_FALSE(*parse("{" + kVolume + R"(, "clip_mesh_display": {"show": false}})").clipMeshDisplay.show);
    expectError("{" + kVolume + R"(, "clip_mesh_display": {"opacity": 1.5}})", "clip_mesh_display.opacity");
    expectError("{" + kVolume + R"(, "clip_mesh_display": {"show": "yes"}})", "clip_mesh_display.show");
    expectError("{" + kVolume + R"(, "clip_mesh_display": {"colour": [1, 0, 0]}})", "clip_mesh_display.colour");
}

TEST(Scene, EveryKeyIsReadAndRelativePathsFollowTheSceneFile) {
    Scene s = parse("{" + kVolume + R"(, "camera": {"target": [1,2,3], "distance_mm": 300, "azimuth_deg": 10, "elevation_deg": -20, "fov_deg": 40},
        "shading": "lao", "lights": [{"direction": [0,0,1], "color": [1,0.5,0.5], "intensity": 2, "space": "world"}],
        "image": {"width": 64, "height": 32, "background": [0,0,0,0]},
        "raycast": {"step_mm": 0.25, "early_termination": 0.95, "jitter_seed": 7, "skip_empty_space": false},
        "ambient_occlusion": {"rays": "fibonacci:64", "samples": 12, "step_mm": 0.5, "antialiasing_samples": 8, "jitter": 0,
                              "weights": "sky", "ambient_scale": 1.5, "dispatch": "full_grid"},
        "clip_meshes": [{"name": "t", "mesh": {"shape": "torus", "major_radius_mm": 20, "minor_radius_mm": 5},
                         "position_mm": [0, 0, 40], "rotation_deg": [90, 0, 0], "scale": [1, 2, 1], "clips_tubes": true}]})");
    EXPECT_EQ(s.camera.target, glm::dvec3(1, 2, 3));
    EXPECT_EQ(*s.camera.distanceMm, 300.0);
    EXPECT_EQ(s.shading, ShadingMode::Lao);
    EXPECT_EQ(s.lights[0].color, glm::dvec3(2, 1, 1));
    EXPECT_FALSE(s.lights[0].cameraSpace);
    EXPECT_EQ(s.imageSize, glm::ivec2(64, 32));
    EXPECT_EQ(s.raycast.jitterSeed, 7u);
    EXPECT_FALSE(s.raycast.skipEmptySpace);
    EXPECT_EQ(s.lao.directions.count, 64);
    EXPECT_EQ(s.lao.dispatch, LaoSettings::Dispatch::FullGrid);
    EXPECT_TRUE(s.lao.directions.skyWeighting);
    EXPECT_EQ(s.clipMeshes[0].scale, glm::dvec3(1, 2, 1));
    EXPECT_TRUE(s.clipMeshes[0].clipsTubes);
    EXPECT_EQ(s.transferFunctionSource, (kScenes / "../tf/mri_t1.json").string());
}

TEST(Scene, BadKeysTypesAndValuesNameTheKey) {
    expectError(R"({"volume": {"path": "x.nii"}})", "transfer_function");
    expectError("{" + kVolume + R"(, "shadng": "phong"})", "shadng");
    expectError("{" + kVolume + R"(, "shading": "toon"})", "shading");
    expectError("{" + kVolume + R"(, "camera": {"fov_deg": 500}})", "camera.fov_deg");
    expectError("{" + kVolume + R"(, "camera": {"target": "middle"}})", "camera.target");
    expectError("{" + kVolume + R"(, "image": {"width": -1}})", "image.width");
    expectError("{" + kVolume + R"(, "image": {"width": 1.5}})", "image.width");
    expectError("{" + kVolume + R"(, "lights": [{"direction": [0,0,0]}]})", "lights[0].direction");
    expectError("{" + kVolume + R"(, "ambient_occlusion": {"rays": "7"}})", "ambient_occlusion.rays");
    expectError("{" + kVolume + R"(, "clip_meshes": [{"mesh": {"shape": "sphere", "radius_mm": -3}}]})", "clip_meshes[0].mesh.radius_mm");
    expectError("{" + kVolume + R"(, "clip_meshes": [{"mesh": {"shape": "blob"}}]})", "clip_meshes[0].mesh.shape");
    expectError("{" + kVolume + R"(, "clip_meshes": [{"mesh": {"shape": "sphere", "radius_mm": 3}, "scale": 0}]})", "clip_meshes[0].scale");
    expectError(R"({"volume": {"path": "x.raw", "format": "raw"}, "transfer_function": "../tf/mri_t1.json"})", "volume.raw");
    expectError(R"({"volume": {"path": "x.nii"}, "transfer_function": "missing.json"})", "");
    expectError("[1, 2]", "(top level)");
    expectError("{" + kVolume + ",}", "line 1, column 106");
}

// A hostile scene nested hundreds of thousands of levels deep used to overflow the stack in the parser (and in
// the code quoting the bad value); now it is refused before parsing with the usual one-line error, and the
// binary exits 2. Ordinary nesting (a scene's deepest is four levels) still parses.
TEST(Scene, DeeplyNestedFilesAreRefusedNotACrash) {
    std::string deep = std::string(300000, '[') + std::string(300000, ']');
    expectError(deep, "line 1, column 65");
    std::string objects;
    for (int i = 0; i < 200000; ++i) objects += "{\"a\":";
    objects += "1" + std::string(200000, '}');
    expectError(objects, "line 1, column 321");
    std::string scene = "{" + kVolume + R"(, "lights": [{"direction": [0, 0, 1], "color": [1, 1, 1]}]})";
    EXPECT_NO_THROW(parse(scene));
    // Brackets inside strings are not nesting.
    EXPECT_NO_THROW(parseJson("[\"" + std::string(1000, '[') + "\"]", "test"));

    std::filesystem::path file = std::filesystem::temp_directory_path() / "curette-deep-scene.json";
    {
        std::ofstream out(file);
        out << deep;
    }
    testing::Invocation r = testing::runCurette("render --scene " + file.string() + " --out " +
                                                (std::filesystem::temp_directory_path() / "curette-deep.png").string());
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("nested at most 64 levels"), std::string::npos) << r.output;
    EXPECT_LT(r.output.size(), 400u) << "one line, not the value";
    std::filesystem::remove(file);
}

}  // namespace
}  // namespace curette

namespace curette {
namespace {

// The scene reader accepts a DOS or LAO value exactly when the pass that checks it does (one table,
// render/model/setting_limits.h): 89.99 degrees was refused by the file and accepted in code before.
TEST(Scene, DosAndLaoKeysAcceptWhatThePassesAccept) {
    auto readsDos = [](const char* key, double v) {
        nlohmann::json j = {{key, v}};
        try {
            readDos(JsonReader(j, "scene.json", "dos"));
            return true;
        } catch (const InputError&) {
            return false;
        }
    };
    auto passAccepts = [](const NumberLimit& l, double v) {
        try {
            requireWithin(l, v, "<dos settings>", "key");
            return true;
        } catch (const InputError&) {
            return false;
        }
    };
    for (double v : {-0.1, 0.0, 45.0, 89.9, 89.99, 90.0, 95.0}) EXPECT_EQ(readsDos("cone_angle_deg", v), passAccepts(limits::dosConeAngleDeg, v)) << v;
    EXPECT_TRUE(readsDos("cone_angle_deg", 89.99));
    EXPECT_FALSE(readsDos("cone_angle_deg", 90.0));
    for (int grid : {0, 1, 16, 17}) {
        nlohmann::json j = {{"grid", grid}};
        bool read = true;
        try {
            readDos(JsonReader(j, "scene.json", "dos"));
        } catch (const InputError&) {
            read = false;
        }
        EXPECT_EQ(read, limits::dosGrid.contains(grid)) << grid;
    }
    nlohmann::json lao = {{"step_mm", 0.0}};
    try {
        readLao(JsonReader(lao, "scene.json", "ambient_occlusion"));
        ADD_FAILURE() << "step_mm 0 read";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(limits::laoStepMm.expected()), std::string::npos) << e.what();
    }
    EXPECT_EQ(limits::dosConeAngleDeg.expected(), "a number in [0, 90)");
    EXPECT_EQ(limits::laoSamples.expected(), "an integer in [1, 1024]");
}

}  // namespace
}  // namespace curette
