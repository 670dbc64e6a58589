// The input pipeline as sessions use it: a pipeline restored from another's mid-run state continues exactly
// as the original (so a recording may start mid-run), and the built-in default mapping is the shipped file.
#include "base/atomic_file.h"
#include "input/devices/encoders.h"
#include "input/pipeline.h"

#include <gtest/gtest.h>

#include <random>

namespace curette::input {
namespace {

struct Frame {
    std::vector<RawReport> reports;
    KeyboardMouseState keys;
};

// Random frames for a SpaceMouse (id 1) and a DualSense (id 2): motion, button presses, keys, garbage.
std::vector<Frame> randomFrames(int count, std::uint32_t seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<float> axis(-1, 1);
    std::uniform_int_distribution<int> percent(0, 99);
    std::vector<Frame> frames(static_cast<std::size_t>(count));
    for (Frame& f : frames) {
        DeviceState mouse, pad;
        for (float& a : mouse.axes) a = axis(random);
        for (float& a : pad.axes) a = axis(random);
        pad.axes[LeftTrigger] = std::abs(pad.axes[LeftTrigger]);
        pad.axes[RightTrigger] = std::abs(pad.axes[RightTrigger]);
        if (percent(random) < 20) mouse.buttons = 1u << (percent(random) % 2);
        if (percent(random) < 20) pad.buttons = 1u << (percent(random) % ButtonCount);
        f.reports.push_back({1, 0, encodeSpaceMouseCombined(mouse)});
        if (percent(random) < 30) f.reports.push_back({1, 0, encodeSpaceMouseButtons(mouse)});
        f.reports.push_back({2, 0, encodeDualSenseUsb(pad)});
        if (percent(random) < 10) f.reports.push_back({2, 0, {0x01, 0x02, 0x03}});  // truncated: ignored
        if (percent(random) < 15) f.keys.keys = std::uint64_t{1} << (percent(random) % static_cast<int>(Key::Count));
        if (percent(random) < 10) f.keys.rightDragPixels = {axis(random) * 10, axis(random) * 10};
    }
    return frames;
}

std::string describe(const std::vector<Action>& actions) {
    std::string s;
    for (const Action& a : actions) {
        s += std::to_string(a.index()) + ":";
        if (auto* m = std::get_if<MoveMesh>(&a))
            s += std::to_string(m->mesh) + "," + std::to_string(m->translationMm.x) + "," + std::to_string(m->rotationRad.z);
        if (auto* m = std::get_if<SelectMesh>(&a)) s += std::to_string(m->binding) + "," + std::to_string(m->mesh);
        s += ";";
    }
    return s;
}

TEST(Pipeline, ARestoredPipelineContinuesExactlyAsTheOriginal) {
    std::vector<Frame> frames = randomFrames(200, 11);
    InputPipeline original(defaultMapping(), 40.0, 60.0);
    original.addDevice(1, DeviceFamily::SpaceMouse);
    original.addDevice(2, DeviceFamily::DualSense);
    std::optional<InputPipeline> restored;
    int compared = 0;
    for (std::size_t i = 0; i < frames.size(); ++i) {
        if (i == 77) {  // recording starts here
            restored.emplace(defaultMapping(), 40.0, 60.0);
            restored->restore(original.state());
        }
        std::vector<Action> a = original.step(frames[i].reports, frames[i].keys, 1 / 60.0, 3);
        if (restored) {
            std::vector<Action> b = restored->step(frames[i].reports, frames[i].keys, 1 / 60.0, 3);
            ASSERT_EQ(describe(a), describe(b)) << "frame " << i;
            ++compared;
        }
    }
    EXPECT_EQ(compared, 123);

    // Without the state, a fresh pipeline diverges (held meshes, button edges): the header needs it.
    InputPipeline fresh(defaultMapping(), 40.0, 60.0), warm(defaultMapping(), 40.0, 60.0);
    for (InputPipeline* p : {&fresh, &warm}) p->addDevice(1, DeviceFamily::SpaceMouse), p->addDevice(2, DeviceFamily::DualSense);
    std::string freshLog, warmLog;
    for (std::size_t i = 0; i < frames.size(); ++i) {
        std::string w = describe(warm.step(frames[i].reports, frames[i].keys, 1 / 60.0, 3));
        if (i >= 77) warmLog += w, freshLog += describe(fresh.step(frames[i].reports, frames[i].keys, 1 / 60.0, 3));
    }
    EXPECT_NE(freshLog, warmLog);
}

TEST(Pipeline, RestoringAStateForAnotherMappingIsRefused) {
    InputPipeline p(defaultMapping(), 40.0, 60.0);
    InputPipelineState s = p.state();
    s.mapper.heldMeshes.push_back(0);
    EXPECT_THROW(p.restore(s), std::invalid_argument);
}

// A hold request (the viewer's mesh panel) takes effect in the step that applies it: that step's motion
// already moves the newly held mesh, for a device binding and for the keyboard, and it is a SelectMesh.
TEST(Pipeline, AHoldRequestMovesTheNewMeshFromThatStepOn) {
    InputPipeline p(defaultMapping(), 40.0, 60.0);
    p.addDevice(1, DeviceFamily::SpaceMouse);   // binding 0 of the default mapping, holding mesh 0
    DeviceState pushed;
    pushed.axes[0] = 0.8f;   // tx
    KeyboardMouseState w;
    w.keys = 1u << static_cast<int>(Key::W);
    auto movedMeshes = [](const std::vector<Action>& actions) {
        std::vector<int> meshes;
        for (const Action& a : actions)
            if (auto* m = std::get_if<MoveMesh>(&a)) meshes.push_back(m->mesh);
        return meshes;
    };
    EXPECT_EQ(movedMeshes(p.step({{1, 0, encodeSpaceMouseCombined(pushed)}}, w, 0.1, 3)), (std::vector<int>{0, 0}));
    std::vector<Action> a = p.step({}, w, 0.1, 3, {{0, 2}, {kKeyboardBinding, 1}});
    ASSERT_GE(a.size(), 2u);
    EXPECT_EQ(describe({a[0], a[1]}), describe({SelectMesh{0, 2}, SelectMesh{kKeyboardBinding, 1}}));
    EXPECT_EQ(movedMeshes(a), (std::vector<int>{2, 1})) << "the SpaceMouse moves mesh 2, the keyboard mesh 1, in the same step";
    EXPECT_EQ(p.mapper().heldMesh(0), 2);
    EXPECT_EQ(p.keyboardSelection(), 1);
    EXPECT_EQ(p.state().mapper.heldMeshes[0], 2) << "a recording started now starts from it";
    // A mesh beyond the meshes there are is the last one (as the mapper clamps); a binding the mapping does
    // not have is refused.
    p.step({}, {}, 0.1, 2, {{0, 7}});
    EXPECT_EQ(p.mapper().heldMesh(0), 1);
    EXPECT_THROW(p.step({}, {}, 0.1, 2, {{9, 0}}), std::invalid_argument);
}

// Shift held (Key::Fine): the frame's mesh motion, from the keys and from a device alike, at a tenth of its speed.
TEST(Pipeline, FineStepsScaleEveryMeshMotionOfTheFrame) {
    auto motion = [](bool fine) {
        InputPipeline p(defaultMapping(), 40.0, 60.0);
        p.addDevice(1, DeviceFamily::SpaceMouse);
        DeviceState pushed;
        pushed.axes[0] = 0.8f;
        pushed.axes[4] = 0.5f;
        KeyboardMouseState keys;
        keys.keys = 1u << static_cast<int>(Key::W) | 1u << static_cast<int>(Key::Up);
        if (fine) keys.keys |= 1u << static_cast<int>(Key::Fine);
        keys.rightDragPixels = {30, -10};
        std::vector<glm::dvec3> out;
        for (const Action& a : p.step({{1, 0, encodeSpaceMouseCombined(pushed)}}, keys, 0.1, 3)) {
            if (auto* m = std::get_if<MoveMesh>(&a)) out.push_back(m->translationMm), out.push_back(m->rotationRad);
            if (auto* d = std::get_if<DragMesh>(&a)) out.push_back(glm::dvec3(d->pixels, 0));
        }
        return out;
    };
    std::vector<glm::dvec3> normal = motion(false), fine = motion(true);
    ASSERT_EQ(normal.size(), 5u) << "the SpaceMouse's move, the keys' move and the drag";
    ASSERT_EQ(fine.size(), normal.size());
    for (std::size_t i = 0; i < normal.size(); ++i) {
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(fine[i][c], kFineStepFactor * normal[i][c], 1e-12) << i;
    }
    EXPECT_NEAR(normal[2].z, 4.0, 1e-9) << "W: 40 mm/s for 0.1 s";
}

TEST(Pipeline, TheBuiltInDefaultMappingIsTheShippedFile) {
    std::vector<std::uint8_t> bytes = readFileBytes(std::string(CURETTE_SOURCE_DIR) + "/assets/input/default_mapping.json");
    MappingConfig shipped = parseMapping(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), "file");
    EXPECT_EQ(mappingToJson(defaultMapping()), mappingToJson(shipped));
}

}  // namespace
}  // namespace curette::input
