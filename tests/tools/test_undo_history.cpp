// One undo history for strokes and setting edits (plan/undo_history.h, session/drilling.h): Ctrl+Z undoes the
// last step of either kind, in order, giving back the exact settings and sub-voxel masks; redo gives them back
// again; a new step drops the redo steps; a removed mesh comes back with its id, shape, pose and scale; the
// memory budget counts both kinds.
#include "session/drilling.h"
#include "session/interaction.h"
#include "plan/undo_history.h"
#include "scene/setting_edit.h"
#include "io/transfer_function_file.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

namespace curette {
namespace {

Scene historyScene() {
    return parseScene(R"({"volume": {"path": "ball.raw", "format": "raw", "raw": {"dims": [4, 4, 4], "type": "uint8"}},
        "transfer_function": {"color": [[0, 0, 0, 0], [255, 1, 1, 1]], "opacity": [[0, 0], [255, 1]]},
        "lights": [{"direction": [1, 0, 0], "disk_radius": 0.3}, {"direction": [0, 0, 1]}, {"direction": [0, 1, 0], "color": [1, 0.5, 0.5]}],
        "clip_meshes": [{"name": "burr", "mesh": {"shape": "sphere", "radius_mm": 3}, "position_mm": [-4, 0, 0]},
                        {"name": "box", "mesh": {"shape": "box", "size_mm": [4, 5, 6]}, "position_mm": [5, 1, -2], "rotation_deg": [0, 0, 0], "scale": 1.5}]})",
                      "scene.json");
}

// What the test compares: every setting an edit below reaches, the meshes, and the removal's bits.
struct Snapshot {
    ShadingMode shading;
    LaoSettings lao;
    std::string tf;   // as its JSON
    std::vector<Light> lights;
    std::vector<std::tuple<int, std::string, std::string, glm::dvec3, glm::dquat, glm::dvec3, bool>> meshes;   // geometry: its source
    std::string removal;
    bool operator==(const Snapshot&) const = default;
};

// The parts that differ ("" when none), for the failure message.
std::string differences(const Snapshot& a, const Snapshot& b) {
    std::string out;
    if (a.shading != b.shading) out += " shading";
    if (!(a.lao == b.lao)) out += " lao";
    if (a.tf != b.tf) out += " tf";
    if (a.lights != b.lights) out += " lights(" + std::to_string(a.lights.size()) + " vs " + std::to_string(b.lights.size()) + ")";
    if (a.meshes != b.meshes) out += " meshes(" + std::to_string(a.meshes.size()) + " vs " + std::to_string(b.meshes.size()) + ")";
    if (a.removal != b.removal) out += " removal";
    return out;
}

Snapshot snapshot(const InteractionState& s) {
    Snapshot out{s.shading, s.lao, io::writeTransferFunctionJson(s.transferFunction), s.lights, {}, s.removal->digest()};
    // The burr's pose is left out: moving a mesh by hand or device is no undo step.
    for (const MeshState& m : s.meshes)
        out.meshes.emplace_back(m.id, m.name, m.geometry->source, m.id == 0 ? glm::dvec3(0.0) : m.pose.position,
                                m.id == 0 ? glm::dquat() : m.pose.orientation, m.scale, m.clipsTubes);
    std::sort(out.meshes.begin(), out.meshes.end(), [](const auto& a, const auto& b) { return std::get<0>(a) < std::get<0>(b); });
    return out;
}

struct HistoryRun {
    InteractionState state = InteractionState::fromScene(historyScene());
    HistoryRun() {
        glm::ivec3 dims(24);
        glm::dmat4 affine = glm::translate(glm::dmat4(1.0), glm::dvec3(-11.5));
        state.removal = std::make_shared<plan::RemovalVolume>(dims, affine);
        state.undoHistory = std::make_shared<plan::UndoHistory>();
    }
    // One frame as the session step makes it: the panels' edits, then the drilling (mesh id `drill` held, or
    // none), then the undo/redo presses.
    void frame(const std::vector<SettingEdit>& edits, int drill = -1, std::vector<HistoryCommand> history = {}) {
        std::vector<SessionMesh> before = state.sessionPoses();
        state.appliedEdits.clear();
        applyUndoableEdits(state, edits, "<test>");
        DrillInput input;
        if (drill >= 0) input.drills.push_back({drill, false});
        input.history = std::move(history);
        applyDrilling(state, before, input);
    }
    void undo() { frame({}, -1, {HistoryCommand::Undo}); }
    void redo() { frame({}, -1, {HistoryCommand::Redo}); }
};

TEST(UndoHistory, StrokesAndSettingEditsUndoAndRedoInOrder) {
    HistoryRun run;
    InteractionState& s = run.state;
    std::vector<Snapshot> states{snapshot(s)};
    auto moveBurr = [&](glm::dvec3 to) { s.meshes[0].pose.position = to; };
    // A stroke over two frames, then an AO edit (the stroke closes first), a light edit and a mesh scale in
    // one frame (one step), a second stroke, a mesh removed, a light removed (not the last), a light added,
    // a transfer function and the shading.
    run.frame({}, 0);
    moveBurr({2, 1, 0});
    run.frame({}, 0);
    nlohmann::json ao = s.keyJson("ambient_occlusion");
    ao["samples"] = 3;
    run.frame({{Setting::AmbientOcclusion, -1, ao}});
    // The stroke and the AO edit are two steps (the edit closed the stroke): after the stroke, the AO as before.
    Snapshot edited = snapshot(s), stroked = edited;
    stroked.lao = states[0].lao;
    states.push_back(stroked);
    states.push_back(edited);
    nlohmann::json light = s.keyJson("lights[1]");
    light["color"] = {0.2, 0.4, 1.0};
    run.frame({{Setting::Light, 1, light}, {Setting::MeshScale, 1, nlohmann::json::parse("[1, 2, 0.5]")}});
    states.push_back(snapshot(s));
    moveBurr({-2, -3, 4});
    run.frame({}, 0);
    run.frame({});   // the stroke ends
    states.push_back(snapshot(s));
    run.frame({{Setting::MeshRemove, 1, nullptr}});
    states.push_back(snapshot(s));
    run.frame({{Setting::LightRemove, 0, nullptr}});
    states.push_back(snapshot(s));
    run.frame({{Setting::LightAdd, -1, nlohmann::json::parse(R"({"direction": [0, -1, 0], "intensity": 0.5})")}});
    states.push_back(snapshot(s));
    run.frame({{Setting::TransferFunction, -1, nlohmann::json::parse(R"({"color": [[0, 1, 0, 0], [255, 0, 1, 1]], "opacity": [[0, 0.1], [255, 0.7]]})")},
               {Setting::Shading, -1, "cao"}});
    states.push_back(snapshot(s));
    ASSERT_EQ(s.undoHistory->undoSteps(), states.size() - 1);
    EXPECT_EQ(s.meshes.size(), 1u);
    EXPECT_EQ(s.lights.size(), 3u);

    // Undo every step, in order: the exact state before each.
    for (std::size_t i = states.size() - 1; i-- > 0;) {
        run.undo();
        EXPECT_EQ(s.appliedHistory.size(), 1u);
        EXPECT_EQ(differences(snapshot(s), states[i]), "") << "after undoing step " << i + 1;
    }
    run.undo();
    EXPECT_TRUE(s.appliedHistory.empty()) << "nothing left to undo";
    EXPECT_TRUE(s.removal->empty());
    // Redo them all: the exact states after each; an edit's redo is recorded as its history edits.
    for (std::size_t i = 1; i < states.size(); ++i) {
        run.redo();
        EXPECT_EQ(differences(snapshot(s), states[i]), "") << "after redoing step " << i;
    }
    EXPECT_EQ(s.appliedHistoryEdits.size(), 2u) << "the last step's two edits, redone";
    // Undo two, then a new edit drops what could be redone.
    run.undo();
    run.undo();
    EXPECT_EQ(s.undoHistory->redoSteps(), 2u);
    run.frame({{Setting::Shading, -1, "phong"}});
    EXPECT_EQ(s.undoHistory->redoSteps(), 0u);
    run.redo();
    EXPECT_TRUE(s.appliedHistory.empty());
    run.undo();
    EXPECT_EQ(differences(snapshot(s), states[states.size() - 3]), "");
}

// A slider dragged over consecutive frames (one edit of one setting a frame) is one step: undo gives back the
// value before the drag, redo the last; a frame without the edit (the release) ends the drag, and an edit of
// another setting is its own step.
TEST(UndoHistory, ADragIsOneStep) {
    HistoryRun run;
    InteractionState& s = run.state;
    const LaoSettings start = s.lao;
    auto samples = [&](int n) {
        nlohmann::json ao = s.keyJson("ambient_occlusion");
        ao["samples"] = n;
        return std::vector<SettingEdit>{{Setting::AmbientOcclusion, -1, ao}};
    };
    for (int n = 3; n <= 7; ++n) run.frame(samples(n));
    EXPECT_EQ(s.undoHistory->undoSteps(), 1u);
    run.frame({});   // released
    run.frame(samples(9));
    run.frame({{Setting::Shading, -1, "dos"}});
    EXPECT_EQ(s.undoHistory->undoSteps(), 3u);
    run.undo();
    run.undo();
    EXPECT_EQ(s.lao.samples, 7);
    run.undo();
    EXPECT_EQ(s.lao.samples, start.samples);
    EXPECT_TRUE(s.lao == start);
    run.redo();
    EXPECT_EQ(s.lao.samples, 7);
}

// A removed mesh comes back with its id, name, shape, pose, scale and clips_tubes; the edits undo recorded are
// session edits, read back strictly.
TEST(UndoHistory, ARemovedMeshComesBackAsItWas) {
    HistoryRun run;
    InteractionState& s = run.state;
    s.meshes[1].pose.orientation = glm::angleAxis(0.7, glm::normalize(glm::dvec3(1, -2, 0.5)));
    s.meshes[1].clipsTubes = true;
    MeshState box = s.meshes[1];
    run.frame({{Setting::MeshRemove, box.id, nullptr}});
    ASSERT_EQ(s.meshes.size(), 1u);
    run.undo();
    ASSERT_EQ(s.appliedHistoryEdits.size(), 1u);
    EXPECT_EQ(s.appliedHistoryEdits[0].setting, Setting::MeshAdd);
    ASSERT_EQ(s.meshes.size(), 2u);
    const MeshState& back = s.meshes[1];
    EXPECT_EQ(back.id, box.id);
    EXPECT_EQ(back.name, box.name);
    EXPECT_EQ(back.geometry->source, box.geometry->source);
    EXPECT_EQ(nlohmann::json::parse(back.description), historyScene().json["clip_meshes"][1]["mesh"]) << "the scene's shape";
    EXPECT_EQ(back.pose.position, box.pose.position);
    EXPECT_NEAR(std::abs(glm::dot(back.pose.orientation, box.pose.orientation)), 1.0, 1e-12) << "through rotation_deg";
    EXPECT_EQ(back.scale, box.scale);
    EXPECT_EQ(back.clipsTubes, box.clipsTubes);
    run.redo();
    EXPECT_EQ(s.meshes.size(), 1u);
}

// The budget counts strokes and edits alike: beyond it the oldest steps are forgotten, never the state.
TEST(UndoHistory, TheBudgetCountsStrokesAndEdits) {
    plan::RemovalVolume removal({8, 8, 8}, glm::dmat4(1.0));
    plan::UndoHistory history(1);
    history.beginStroke();
    removal.apply([](glm::dvec3 w) { return glm::length(w - glm::dvec3(3)) < 2; }, {{0, 0, 0}, {8, 8, 8}}, false, history.before());
    history.endStroke(removal);
    EXPECT_EQ(history.undoSteps(), 1u);
    EXPECT_GT(history.lastStrokeBytes(), sizeof(plan::BrickMasks));
    history.pushEdit(removal, nlohmann::json::array({{{"setting", "shading"}, {"value", "phong"}}}), nlohmann::json::array());
    EXPECT_EQ(history.undoSteps(), 1u) << "a budget below two steps keeps the newest";
    plan::UndoResult undone = history.undo(removal);
    EXPECT_TRUE(undone.done);
    EXPECT_TRUE(undone.edits.is_array());
    EXPECT_FALSE(removal.empty()) << "the forgotten stroke stays drilled";
    EXPECT_FALSE(history.undo(removal).done);

    plan::UndoHistory roomy;
    roomy.pushEdit(removal, nlohmann::json::array(), nlohmann::json::array());
    std::size_t oneEdit = roomy.bytes();
    EXPECT_GT(oneEdit, 0u);
    roomy.beginStroke();
    removal.apply([](glm::dvec3 w) { return w.x < 2; }, {{0, 0, 0}, {8, 8, 8}}, false, roomy.before());
    roomy.endStroke(removal);
    EXPECT_EQ(roomy.bytes(), oneEdit + roomy.lastStrokeBytes());
}

}  // namespace
}  // namespace curette
