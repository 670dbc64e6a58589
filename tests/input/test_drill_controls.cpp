// Drill controls as actions (input/mapping.h, input/keyboard_mouse.h): a drill or erase control emits HoldDrill
// for the held mesh on every frame it is held, not only when pressed; a trigger axis drills past its threshold;
// undo and redo fire on press; the keyboard's B, N, Ctrl+Z and Ctrl+Shift+Z do the same; the shipped mapping
// drills with a SpaceMouse button and the gamepad's right trigger.
#include "base/error.h"
#include "input/keyboard_mouse.h"
#include "input/mapping.h"

#include <gtest/gtest.h>

namespace curette::input {
namespace {

// The frame's drill actions as text: "D0" drill mesh 0, "E1" erase mesh 1, "U" undo, "R" redo.
std::string drills(const std::vector<Action>& actions) {
    std::string s;
    for (const Action& a : actions) {
        if (auto* h = std::get_if<HoldDrill>(&a)) s += (h->erase ? "E" : "D") + std::to_string(h->mesh) + " ";
        if (std::holds_alternative<Undo>(a)) s += "U ";
        if (std::holds_alternative<Redo>(a)) s += "R ";
    }
    return s;
}

MappingConfig gamepadMapping() {
    return parseMapping(R"({"bindings": [{"device": {"family": "gamepad"}, "mesh": 1,
        "buttons": {"south": "drill", "east": "erase", "dpad_left": "undo_stroke", "dpad_right": "redo_stroke"},
        "drill": {"axis": "right_trigger", "threshold": 0.5}, "erase": {"axis": "left_trigger", "threshold": 0.8}}]})",
                        "test mapping");
}

TEST(DrillControls, ButtonsDrillWhileHeldAndUndoOnPress) {
    Mapper mapper(gamepadMapping());
    std::vector<DeviceSnapshot> devices{{1, DeviceFamily::DualSense, {}}};
    EXPECT_EQ(drills(mapper.update(devices, 0.016, 3)), "");
    devices[0].state.buttons = 1u << South;
    for (int frame = 0; frame < 3; ++frame) EXPECT_EQ(drills(mapper.update(devices, 0.016, 3)), "D1 ") << "every frame held, frame " << frame;
    devices[0].state.buttons = 1u << East;
    EXPECT_EQ(drills(mapper.update(devices, 0.016, 3)), "E1 ");
    devices[0].state.buttons = (1u << East) | (1u << South);
    EXPECT_EQ(drills(mapper.update(devices, 0.016, 3)), "D1 ") << "drill wins over erase";
    devices[0].state.buttons = 1u << DpadLeft;
    EXPECT_EQ(drills(mapper.update(devices, 0.016, 3)), "U ");
    EXPECT_EQ(drills(mapper.update(devices, 0.016, 3)), "") << "held: one undo";
    devices[0].state.buttons = 1u << DpadRight;
    EXPECT_EQ(drills(mapper.update(devices, 0.016, 3)), "R ");
    devices[0].state.buttons = 0;
    EXPECT_EQ(drills(mapper.update(devices, 0.016, 3)), "");
}

TEST(DrillControls, TriggerAxesDrillPastTheirThreshold) {
    Mapper mapper(gamepadMapping());
    std::vector<DeviceSnapshot> devices{{1, DeviceFamily::XboxBluetooth, {}}};
    devices[0].state.axes[RightTrigger] = 0.49f;
    EXPECT_EQ(drills(mapper.update(devices, 0.016, 3)), "");
    devices[0].state.axes[RightTrigger] = 0.5f;
    EXPECT_EQ(drills(mapper.update(devices, 0.016, 3)), "D1 ");
    EXPECT_EQ(drills(mapper.update(devices, 0.016, 3)), "D1 ") << "held";
    devices[0].state.axes[RightTrigger] = 0.0f;
    devices[0].state.axes[LeftTrigger] = 0.7f;
    EXPECT_EQ(drills(mapper.update(devices, 0.016, 3)), "") << "below the erase threshold";
    devices[0].state.axes[LeftTrigger] = 0.9f;
    EXPECT_EQ(drills(mapper.update(devices, 0.016, 3)), "E1 ");
    // The held mesh follows cycling: the drill is the binding's held mesh.
    mapper.hold(0, 2);
    EXPECT_EQ(drills(mapper.update(devices, 0.016, 3)), "E2 ");
}

TEST(DrillControls, AxisControlsParseAndRoundTrip) {
    MappingConfig config = gamepadMapping();
    ASSERT_TRUE(config.bindings[0].drillAxis);
    EXPECT_EQ(*config.bindings[0].drillAxis, (AxisControl{"right_trigger", 0.5}));
    EXPECT_EQ(*config.bindings[0].eraseAxis, (AxisControl{"left_trigger", 0.8}));
    MappingConfig again = parseMapping(mappingToJson(config), "again");
    EXPECT_EQ(mappingToJson(again), mappingToJson(config));
    EXPECT_EQ(*again.bindings[0].eraseAxis, *config.bindings[0].eraseAxis);
    auto expectError = [](const std::string& json, const std::string& field) {
        try {
            parseMapping(json, "m.json");
            ADD_FAILURE() << "accepted " << json;
        } catch (const InputError& e) {
            EXPECT_EQ(e.field(), field) << e.what();
        }
    };
    expectError(R"({"bindings": [{"device": {"family": "gamepad"}, "drill": {"axis": "tx"}}]})", "bindings[0].drill.axis");
    expectError(R"({"bindings": [{"device": {"family": "spacemouse"}, "drill": {"axis": "right_trigger"}}]})", "bindings[0].drill.axis");
    expectError(R"({"bindings": [{"device": {"family": "gamepad"}, "erase": {"axis": "left_trigger", "threshold": 0}}]})",
                "bindings[0].erase.threshold");
    expectError(R"({"bindings": [{"device": {"family": "gamepad"}, "drill": {"axis": "left_trigger", "speed": 1}}]})", "bindings[0].drill.speed");
}

TEST(DrillControls, TheShippedMappingDrillsWithASpaceMouseButtonAndTheRightTrigger) {
    Mapper mapper(defaultMapping());
    std::vector<DeviceSnapshot> devices{{1, DeviceFamily::SpaceMouse, {}}, {2, DeviceFamily::DualShock4, {}}};
    devices[0].state.buttons = 1u << 1;
    devices[1].state.axes[RightTrigger] = 1.0f;
    // The SpaceMouse holds mesh 0, the first gamepad mesh 1: each drills its own, and the trigger moves nothing.
    std::vector<Action> a = mapper.update(devices, 0.016, 2);
    EXPECT_EQ(drills(a), "D0 D1 ");
    for (const Action& action : a) EXPECT_FALSE(std::holds_alternative<MoveMesh>(action)) << "a trigger drills in place";
    devices[0].state.buttons = 0;
    devices[1].state.axes[RightTrigger] = 0.0f;
    devices[1].state.axes[LeftTrigger] = 1.0f;
    devices[1].state.buttons = 1u << DpadLeft;
    EXPECT_EQ(drills(mapper.update(devices, 0.016, 2)), "U E1 ");
}

TEST(DrillControls, KeyboardBDrillsNErasesCtrlZUndoes) {
    KeyboardMapper keys(40.0, 60.0);
    keys.select(1);
    KeyboardMouseState s;
    s.press(Key::Drill);
    EXPECT_EQ(drills(keys.update(s, 0.016, 2)), "D1 ");
    EXPECT_EQ(drills(keys.update(s, 0.016, 2)), "D1 ") << "held: every frame";
    s.press(Key::Erase);
    EXPECT_EQ(drills(keys.update(s, 0.016, 2)), "D1 ") << "B wins over N";
    s.keys = KeyboardMouseState::keyBit(Key::Erase);
    EXPECT_EQ(drills(keys.update(s, 0.016, 2)), "E1 ");
    s.keys = KeyboardMouseState::keyBit(Key::Undo);
    EXPECT_EQ(drills(keys.update(s, 0.016, 2)), "U ");
    EXPECT_EQ(drills(keys.update(s, 0.016, 2)), "") << "held: one undo";
    s.keys = KeyboardMouseState::keyBit(Key::Redo);
    EXPECT_EQ(drills(keys.update(s, 0.016, 0)), "R ") << "no mesh needed to redo";
    s.keys = KeyboardMouseState::keyBit(Key::Drill);
    EXPECT_EQ(drills(keys.update(s, 0.016, 0)), "") << "no mesh, nothing drills";
    EXPECT_GT(static_cast<int>(Key::Redo), 31) << "past 32 bits: the keys word is 64-bit";
}

}  // namespace
}  // namespace curette::input
