// Setting edits (scene/setting_edit.h): an edit's value is read by the scene reader's function for its key, so
// a scene edited key by key is the scene that has those keys; edits round-trip through a session (version 3)
// and a malformed one is an InputError naming the line and the key; a session of version 2 has none.
#include "session/interaction.h"
#include "io/transfer_function_file.h"
#include "session/plan_scene.h"
#include "session/session.h"
#include "scene/setting_edit.h"
#include "base/error.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace curette {
namespace {

const char* kVolume = R"("volume": {"path": "ball.raw", "format": "raw", "raw": {"dims": [4, 4, 4], "type": "uint8"}})";

Scene sceneWith(const std::string& keys) {
    return parseScene(std::string("{") + kVolume + R"(, "transfer_function": {"color": [[0, 0, 0, 0], [255, 1, 1, 1]], "opacity": [[0, 0], [255, 1]]})" +
                          (keys.empty() ? "" : ", " + keys) + "}",
                      "scene.json");
}

// The state after these edits equals the state of a scene that has the edited values as its keys.
TEST(SettingEdit, AnEditedSceneEqualsTheSceneWithThoseKeys) {
    const std::string tf = R"({"name": "t", "color": [[0, 0.5, 0, 0], [90, 1, 0.2, 1], [255, 1, 1, 1]], "opacity": [[0, 0], [40, 0.3], [255, 0.9]],
                               "material": {"ambient": 0.1, "diffuse": 0.7, "specular": 0.5, "specular_power": 12}})";
    const std::string ao = R"({"rays": "14", "samples": 9, "step_mm": 0.75, "ambient_scale": 1.5, "weights": "sky"})";
    const std::string rc = R"({"step_mm": 0.3, "jitter_seed": 4, "cut_faces": {"enabled": false}})";
    const std::string dos = R"({"cone_angle_deg": 35, "grid": 5})";
    const std::string ismos = R"({"light_samples": 8, "occlusion": "full", "layers": 2})";
    const std::string light1 = R"({"direction": [0, 1, 0.5], "color": [1, 0.5, 0.25], "intensity": 2, "space": "world", "disk_radius": 0.1})";
    const std::string lights0 = R"([{"direction": [1, 0, 0], "disk_radius": 0.3}, {"direction": [0, 0, 1], "disk_radius": 0.4}])";
    Scene plain = sceneWith(R"("lights": )" + lights0);
    Scene keyed = sceneWith(R"("lights": [{"direction": [1, 0, 0], "disk_radius": 0.3}, )" + light1 + R"(], "transfer_function": )" + tf +
                            R"(, "ambient_occlusion": )" + ao + R"(, "raycast": )" + rc + R"(, "dos": )" + dos + R"(, "ismos": )" + ismos +
                            R"(, "shading": "dos")");
    InteractionState edited = InteractionState::fromScene(plain);
    auto json = [](const std::string& t) { return nlohmann::json::parse(t); };
    // ismos before the light: the ISMOS edit keeps the lights' own keys (light 0's disk), the light edit sets
    // its own.
    edited.applyEdits({{Setting::TransferFunction, -1, json(tf)}, {Setting::AmbientOcclusion, -1, json(ao)}, {Setting::Raycast, -1, json(rc)},
                       {Setting::Dos, -1, json(dos)}, {Setting::Ismos, -1, json(ismos)}, {Setting::Light, 1, json(light1)},
                       {Setting::Shading, -1, "dos"}},
                      "<test>");
    InteractionState expected = InteractionState::fromScene(keyed);
    EXPECT_EQ(io::writeTransferFunctionJson(edited.transferFunction), io::writeTransferFunctionJson(expected.transferFunction));
    EXPECT_TRUE(edited.lao == expected.lao);
    EXPECT_EQ(edited.raycast, expected.raycast);
    EXPECT_EQ(edited.dos, expected.dos);
    EXPECT_EQ(edited.ismos, expected.ismos) << "the ISMOS settings and every light's disk and spot";
    EXPECT_EQ(edited.lights, expected.lights);
    EXPECT_EQ(edited.shading, expected.shading);
    EXPECT_EQ(edited.transferFunctionVersion, 1u);
    EXPECT_EQ(edited.appliedEdits.size(), 7u);
    // What a session header carries (one edit per edited key) rebuilds the same state.
    InteractionState again = InteractionState::fromScene(plain);
    again.applyEdits(edited.settingEdits(), "<header>");
    EXPECT_TRUE(again.lao == expected.lao);
    EXPECT_EQ(again.ismos, expected.ismos);
    EXPECT_EQ(again.lights, expected.lights);
}

// The TF editor's gradient-opacity curve is part of the TF edit: written back by the scene writer, the
// scene reads back to the same transfer function, every point bit for bit; turned off (no points), the
// written scene has none either.
TEST(SettingEdit, AnEditedGradientOpacityRoundTripsThroughTheSceneWriter) {
    Scene scene = sceneWith("");
    InteractionState state = InteractionState::fromScene(scene);
    nlohmann::json tf = state.keyJson(scene, "transfer_function");
    tf["gradient_opacity"] = {{0, 0.1}, {12.345678901234567, 0.75}, {40, 1}};
    state.applyEdits({{Setting::TransferFunction, -1, tf}}, "<panel>");
    ASSERT_EQ(state.transferFunction.gradientOpacity.size(), 3u);
    EXPECT_TRUE(state.transferFunction.hasGradientOpacity());
    auto readBack = [&](const InteractionState& s) {
        return InteractionState::fromScene(parseScene(planSceneJson(scene, scene.json.dump(), s), "written.json")).transferFunction;
    };
    TransferFunction written = readBack(state);
    ASSERT_EQ(written.gradientOpacity.size(), 3u);
    for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_EQ(written.gradientOpacity[i].value, state.transferFunction.gradientOpacity[i].value) << i;
        EXPECT_EQ(written.gradientOpacity[i].y, state.transferFunction.gradientOpacity[i].y) << i;
    }
    EXPECT_EQ(io::writeTransferFunctionJson(written), io::writeTransferFunctionJson(state.transferFunction));
    tf.erase("gradient_opacity");   // the checkbox off
    state.applyEdits({{Setting::TransferFunction, -1, tf}}, "<panel>");
    EXPECT_TRUE(readBack(state).gradientOpacity.empty());
}

// Mesh edits: add (given the next id, or the recorded one), shape, scale, clips_tubes, remove.
TEST(SettingEdit, MeshEditsAddShapeScaleAndRemove) {
    Scene scene = sceneWith(R"("clip_meshes": [{"name": "s", "mesh": {"shape": "sphere", "radius_mm": 5}}])");
    InteractionState s = InteractionState::fromScene(scene);
    s.applyEdits({{Setting::MeshAdd, -1, nlohmann::json::parse(R"({"mesh": {"shape": "box", "size_mm": [4, 4, 4]}, "position_mm": [1, 2, 3], "clips_tubes": true})")}},
                 "<test>");
    ASSERT_EQ(s.meshes.size(), 2u);
    EXPECT_EQ(s.meshes[1].id, 1);
    EXPECT_EQ(s.appliedEdits.back().target, 1) << "the applied edit carries the id it gave";
    EXPECT_EQ(s.meshes[1].pose.position, glm::dvec3(1, 2, 3));
    EXPECT_TRUE(s.meshes[1].clipsTubes);
    EXPECT_EQ(s.addedMeshIds, std::vector<int>{1});
    const clip::TriangleMesh* before = s.meshes[0].geometry.get();
    s.applyEdits({{Setting::MeshShape, 0, nlohmann::json::parse(R"({"shape": "cylinder", "radius_mm": 3, "height_mm": 9})")},
                  {Setting::MeshScale, 0, nlohmann::json::parse("[1, 2, 3]")},
                  {Setting::MeshScale, 1, 2.5},
                  {Setting::MeshClipsTubes, 0, true}},
                 "<test>");
    EXPECT_NE(s.meshes[0].geometry.get(), before);
    EXPECT_EQ(s.meshes[0].description, R"({"height_mm":9,"radius_mm":3,"shape":"cylinder"})");
    EXPECT_EQ(s.meshes[0].scale, glm::dvec3(1, 2, 3));
    EXPECT_EQ(s.meshes[1].scale, glm::dvec3(2.5));
    EXPECT_TRUE(s.meshes[0].clipsTubes);
    s.applyEdits({{Setting::MeshRemove, 0, nullptr}}, "<test>");
    ASSERT_EQ(s.meshes.size(), 1u);
    EXPECT_EQ(s.meshes[0].id, 1);
    EXPECT_EQ(s.removedMeshIds, std::vector<int>{0});
    try {
        s.applyEdits({{Setting::MeshScale, 0, 2.0}}, "session.jsonl line 9");
        FAIL() << "an edit of a removed mesh is an error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("session.jsonl"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("edits[0].mesh"), std::string::npos) << e.what();
    }
    try {
        s.applyEdits({{Setting::MeshScale, 1, -2.0}}, "<panel>");
        FAIL() << "a negative scale is the scene reader's error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("edits[0].value"), std::string::npos) << e.what();
    }
    // A pose typed in RAS mm and degrees: the same pose a scene entry with those keys gives.
    s.applyEdits({{Setting::MeshPose, 1, nlohmann::json::parse(R"({"position_mm": [4, -5, 6.5], "rotation_deg": [10, -20, 30]})")}}, "<panel>");
    EXPECT_EQ(s.meshes[0].pose.position, glm::dvec3(4, -5, 6.5));
    glm::dvec3 degrees = clip::degreesFromOrientation(s.meshes[0].pose.orientation);
    EXPECT_NEAR(degrees.x, 10, 1e-9);
    EXPECT_NEAR(degrees.y, -20, 1e-9);
    EXPECT_NEAR(degrees.z, 30, 1e-9);
    EXPECT_EQ(s.meshes[0].pose.orientation, clip::orientationFromDegrees({10, -20, 30}));
    EXPECT_THROW(s.applyEdits({{Setting::MeshPose, 1, nlohmann::json::parse(R"({"position": [1, 2, 3]})")}}, "<panel>"), InputError)
        << "an unknown key is refused";
}

SessionHeader header(int version) {
    SessionHeader h;
    h.version = version;
    h.scene = "scene.json";
    h.mappingJson = R"({"bindings": [{"device": {"family": "gamepad", "index": 0}, "mesh": 0}]})";
    h.inputState.mapper = {{0}, {-1}, {0}};
    h.meshes = {{0, "s", "", {}, {}, glm::dvec3(1), std::nullopt}};
    h.nextMeshId = 1;
    return h;
}

SessionFrame frame(std::size_t index) {
    SessionFrame f;
    f.index = index;
    f.size = {8, 8};
    f.meshes = {{0, glm::dvec3(0), glm::dquat(1, 0, 0, 0), glm::dvec3(1)}};
    return f;
}

// The viewer's "show tools" checkbox is an edit of "clip_mesh_display": the state then equals the scene with
// that key, what a session header carries rebuilds it, and the scene writer keeps it.
TEST(SettingEdit, TheClipMeshDisplayIsAnEditOfItsSceneKey) {
    Scene plain = sceneWith("");
    InteractionState state = InteractionState::fromScene(plain);
    EXPECT_FALSE(state.clipMeshDisplay.show.has_value()) << "the command's default until a scene or an edit says";
    const nlohmann::json display = nlohmann::json::parse(R"({"show": false, "opacity": 0.3})");
    state.applyEdits({{Setting::ClipMeshDisplay, -1, display}}, "<panel>");
    InteractionState expected = InteractionState::fromScene(sceneWith(R"("clip_mesh_display": {"show": false, "opacity": 0.3})"));
    EXPECT_EQ(state.clipMeshDisplay, expected.clipMeshDisplay);
    ASSERT_TRUE(state.clipMeshDisplay.show.has_value());
    EXPECT_FALSE(*state.clipMeshDisplay.show);
    InteractionState again = InteractionState::fromScene(plain);
    again.applyEdits(state.settingEdits(), "<header>");
    EXPECT_EQ(again.clipMeshDisplay, expected.clipMeshDisplay);
    Scene written = parseScene(planSceneJson(plain, plain.json.dump(), state), "written.json");
    EXPECT_EQ(written.clipMeshDisplay, expected.clipMeshDisplay);
    EXPECT_THROW(state.applyEdits({{Setting::ClipMeshDisplay, -1, nlohmann::json::parse(R"({"show": 1})")}}, "<panel>"), InputError);
}

TEST(SettingEdit, EditsRoundTripThroughASession) {
    SessionHeader h = header(kSessionVersion);
    h.edits = {{Setting::AmbientOcclusion, -1, nlohmann::json::parse(R"({"samples": 7})")}};
    h.meshes[0].clipsTubes = true;
    SessionFrame f = frame(0);
    f.edits = {{Setting::TransferFunction, -1, nlohmann::json::parse(R"({"color": [[0, 0.1, 0.2, 0.3]], "opacity": [[0, 0.123456789012345678]]})")},
               {Setting::MeshScale, 0, 1.0000000000000002},
               {Setting::Light, 0, nlohmann::json::parse(R"({"direction": [0.1, 0.2, 0.3], "color": [1, 0, 0]})")}};
    Session s = parseSession(sessionHeaderLine(h) + "\n" + sessionFrameLine(f) + "\n", "s.jsonl", false);
    ASSERT_EQ(s.frames.size(), 1u);
    EXPECT_EQ(s.header.edits, h.edits);
    EXPECT_EQ(s.header.meshes[0].clipsTubes, std::optional<bool>(true));
    EXPECT_EQ(s.frames[0].edits, f.edits) << "every value, bit for bit";
}

std::string messageOf(const std::string& text) {
    try {
        parseSession(text, "s.jsonl", false);
    } catch (const InputError& e) {
        return e.what();
    }
    return "(no error)";
}

TEST(SettingEdit, AMalformedEditNamesTheLineAndTheKey) {
    std::string head = sessionHeaderLine(header(kSessionVersion)) + "\n";
    auto withEdit = [&](const std::string& edit) {
        std::string line = sessionFrameLine(frame(0));
        line.insert(line.rfind(",\"reports\""), ",\"edits\":[" + edit + "]");
        return head + sessionFrameLine(frame(0)) + "\n" + line + "\n";
    };
    std::string m = messageOf(withEdit(R"({"setting": "ambient_occlusion", "value": {"samples": 0}})"));
    EXPECT_NE(m.find("line 3"), std::string::npos) << m;
    EXPECT_NE(m.find("edits[0].value.samples"), std::string::npos) << m;
    m = messageOf(withEdit(R"({"setting": "ambient_occlusions", "value": {}})"));
    EXPECT_NE(m.find("edits[0].setting"), std::string::npos) << m;
    EXPECT_NE(m.find("\"ambient_occlusion\""), std::string::npos) << "the list of settings: " << m;
    m = messageOf(withEdit(R"({"setting": "transfer_function", "value": {"color": [[0, 2, 0, 0]], "opacity": [[0, 1]]}})"));
    EXPECT_NE(m.find("edits[0].value.color[0]"), std::string::npos) << m;
    m = messageOf(withEdit(R"({"setting": "clip_meshes.scale", "value": 2})"));
    EXPECT_NE(m.find("edits[0].mesh"), std::string::npos) << "a mesh setting needs its mesh: " << m;
    m = messageOf(withEdit(R"({"setting": "clip_meshes.add", "mesh": 5, "value": {"mesh": {"shape": "sphere", "radius_mm": 3}}})"));
    EXPECT_NE(m.find("meshes_added"), std::string::npos) << "an added mesh is listed in meshes_added: " << m;
    m = messageOf(withEdit(R"({"setting": "lights", "light": 0, "value": {"direction": [0, 0, 0]}})"));
    EXPECT_NE(m.find("edits[0].value.direction"), std::string::npos) << m;
    m = messageOf(withEdit(R"({"setting": "shading", "value": "cao", "extra": 1})"));
    EXPECT_NE(m.find("extra"), std::string::npos) << m;

    std::string v2 = sessionHeaderLine(header(2)) + "\n";
    std::string line = sessionFrameLine(frame(0));
    line.insert(line.rfind(",\"reports\""), R"(,"edits":[{"setting": "shading", "value": "cao"}])");
    m = messageOf(v2 + line + "\n");
    EXPECT_NE(m.find("version 3"), std::string::npos) << "version 2 sessions have no edits: " << m;
    EXPECT_EQ(messageOf(v2 + sessionFrameLine(frame(0)) + "\n"), "(no error)") << "and still read";
}

}  // namespace
}  // namespace curette
