// Sessions: the file format (round trip, corrupt files named by line, the lenient prefix), the recorder's
// atomic checkpoints, and record/replay through the real binary on a small CAO scene: poses re-derived from the
// raw reports equal the recorded ones, a replay is deterministic, CAO equals LAO on every frame.
#include "session/live_input.h"
#include "session/loaded_scene.h"
#include "session/session.h"
#include "session/session_step.h"
#include "base/error.h"
#include "input/hid/fake_backend.h"
#include "render/renderer.h"

#include <nlohmann/json.hpp>

#include "tests/tools/run_curette.h"
#include "tests/tools/tool_test_support.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <sys/wait.h>

namespace curette {
namespace {

using curette::testing::Invocation;
Invocation run(const std::string& arguments) { return curette::testing::runCurette(arguments); }

std::filesystem::path scratch(const std::string& name) { return curette::testing::freshScratchFolder("curette-session", name); }

std::string readText(const std::filesystem::path& path) { return curette::testing::readTextFile(path); }

void writeText(const std::filesystem::path& p, const std::string& text) {
    std::ofstream out(p, std::ios::binary);
    out << text;
}

std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::stringstream s(text);
    for (std::string line; std::getline(s, line);) out.push_back(line);
    return out;
}

std::string joined(const std::vector<std::string>& ls) {
    std::string t;
    for (const std::string& l : ls) t += l + "\n";
    return t;
}

SessionHeader exampleHeader() {
    SessionHeader h;
    h.scene = "scene.json";
    h.created = "2026-11-24T00:00:00Z";
    h.devices = {{3, "dualshock4", "/dev/hidraw3", "Wireless Controller", "usb", 0x054c, 0x09cc}};
    h.mappingJson = R"({"bindings": [{"device": {"family": "gamepad", "index": 0}, "mesh": 1}]})";
    h.shading = ShadingMode::Cao;
    h.meshes = {{0, "sphere", "", {{1, 2, 3}, glm::dquat(1, 0, 0, 0)}, {{1, 2, 3}, glm::dquat(1, 0, 0, 0)}, glm::dvec3(1), std::nullopt},
                {4, "added 4", R"({"shape":"sphere","radius_mm":15})", {{0.1, 0.2, 0.3}, glm::normalize(glm::dquat(0.9, 0.1, 0.2, 0.3))},
                 {{0, 0, 0}, glm::dquat(1, 0, 0, 0)}, glm::dvec3(2, 1, 1), std::nullopt}};
    h.nextMeshId = 5;
    input::DeviceSnapshot snapshot{3, input::DeviceFamily::DualShock4, {}};
    snapshot.state.axes[0] = 0.25f;
    snapshot.state.buttons = 5;
    h.inputState.devices[3] = snapshot;
    h.inputState.mapper = {{1}, {3}, {5}};
    h.inputState.keyboard = {2, 1};
    return h;
}

SessionFrame exampleFrame(std::size_t index, std::mt19937& random) {
    std::uniform_real_distribution<double> u(-100, 100);
    SessionFrame f;
    f.index = index;
    f.time = static_cast<double>(index) / 30.0;
    f.dt = 1 / 30.0;
    f.size = {64, 48};
    f.camera.target = {u(random), u(random), u(random)};
    f.camera.azimuthDeg = u(random);
    f.shading = ShadingMode::Lao;
    glm::dquat q = glm::normalize(glm::dquat(u(random), u(random), u(random), u(random)));
    f.meshes = {{0, {u(random), u(random), u(random)}, q, glm::dvec3(1)}, {4, {u(random) / 3, 1e-17, -0.1}, q, glm::dvec3(2, 1, 1)}};
    f.keys = 1u << 7;
    f.drag = {1.5, -2};
    f.reports = {{3, f.time, {0x01, 0x80, 0x7f, 0xff, 0x00}}};
    return f;
}

TEST(Session, RoundTripKeepsEveryDoubleExactly) {
    std::mt19937 random(7);
    SessionHeader header = exampleHeader();
    std::string text = sessionHeaderLine(header) + "\n";
    std::vector<SessionFrame> frames;
    for (std::size_t i = 0; i < 20; ++i) {
        frames.push_back(exampleFrame(i, random));
        if (i == 4) frames.back().meshesAdded = {{7, "added 7", R"({"shape":"box","size_mm":[1,2,3]})"}};
        if (i == 9) frames.back().meshesRemoved = {7};
        if (i == 11) frames.back().devicesAdded = {{8, "spacemouse", "/dev/hidraw9", "SpaceNavigator", "usb", 0x046d, 0xc626}};
        if (i == 12) frames.back().reports.push_back({8, 0.4, {0x01, 0x02}});
        if (i == 13) frames.back().devicesRemoved = {8};
        text += sessionFrameLine(frames.back()) + "\n";
    }
    Session s = parseSession(text, "mem.jsonl", false);
    EXPECT_EQ(s.header.scene, "scene.json");
    EXPECT_EQ(s.header.shading, ShadingMode::Cao);
    ASSERT_EQ(s.header.meshes.size(), 2u);
    EXPECT_EQ(s.header.meshes[1].pose, header.meshes[1].pose);
    EXPECT_EQ(s.header.meshes[1].description, nlohmann::json::parse(header.meshes[1].description).dump());
    EXPECT_EQ(s.header.nextMeshId, 5);
    EXPECT_EQ(s.header.inputState.devices.at(3).state, header.inputState.devices.at(3).state);
    EXPECT_EQ(s.header.inputState.mapper, header.inputState.mapper);
    EXPECT_EQ(s.header.inputState.keyboard, header.inputState.keyboard);
    ASSERT_EQ(s.frames.size(), frames.size());
    for (std::size_t i = 0; i < frames.size(); ++i) {
        const SessionFrame &a = frames[i], &b = s.frames[i];
        EXPECT_EQ(a.camera.target, b.camera.target);
        EXPECT_EQ(a.camera.azimuthDeg, b.camera.azimuthDeg);
        ASSERT_EQ(a.meshes.size(), b.meshes.size());
        for (std::size_t m = 0; m < a.meshes.size(); ++m) {
            EXPECT_EQ(a.meshes[m].position, b.meshes[m].position) << "frame " << i;
            EXPECT_EQ(a.meshes[m].orientation, b.meshes[m].orientation) << "frame " << i;
            EXPECT_EQ(a.meshes[m].scale, b.meshes[m].scale);
        }
        EXPECT_EQ(a.keys, b.keys);
        EXPECT_EQ(a.drag, b.drag);
        ASSERT_EQ(a.reports.size(), b.reports.size());
        for (std::size_t r = 0; r < a.reports.size(); ++r) EXPECT_EQ(a.reports[r].bytes, b.reports[r].bytes);
    }
    EXPECT_EQ(s.frames[11].devicesAdded.at(0).family, "spacemouse");
    EXPECT_EQ(s.frames[13].devicesRemoved, std::vector<int>{8});
    EXPECT_TRUE(s.warning.empty());
}

// A valid three-frame session as text, for the corruption cases.
std::vector<std::string> validLines() {
    std::mt19937 random(3);
    std::vector<std::string> ls = {sessionHeaderLine(exampleHeader())};
    for (std::size_t i = 0; i < 3; ++i) ls.push_back(sessionFrameLine(exampleFrame(i, random)));
    return ls;
}

std::string replaced(std::string s, const std::string& from, const std::string& to) {
    std::size_t at = s.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) s.replace(at, from.size(), to);
    return s;
}

// Version 2 records the lights: the header's (direction, space, the selected one) and each frame's directions
// and light drag read back to the same doubles; a version 1 file (the format before lights) still loads, with
// no lights (the scene's stay), and one that has light keys is refused.
TEST(Session, LightRecordsRoundTripAndVersion1SessionsStillLoad) {
    SessionHeader header = exampleHeader();
    header.lights = std::vector<SessionLight>{{{0.1, 0.2, 0.3}, true}, {{-1.0 / 3.0, 1e-17, 0.7}, false}};
    header.selectedLight = 1;
    std::string text = sessionHeaderLine(header) + "\n";
    std::mt19937 random(9);
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<SessionFrame> frames;
    for (std::size_t i = 0; i < 5; ++i) {
        SessionFrame f = exampleFrame(i, random);
        f.lights = std::vector<glm::dvec3>{{u(random), u(random), u(random)}, {u(random), u(random), 1.0 + u(random)}};
        if (i == 2) f.lightDrag = {u(random), -3.0};
        frames.push_back(f);
        text += sessionFrameLine(f) + "\n";
    }
    Session s = parseSession(text, "lights.jsonl", false);
    EXPECT_EQ(s.header.version, kSessionVersion);
    ASSERT_TRUE(s.header.lights.has_value());
    ASSERT_EQ(s.header.lights->size(), 2u);
    EXPECT_EQ((*s.header.lights)[1].direction, (*header.lights)[1].direction);
    EXPECT_FALSE((*s.header.lights)[1].cameraSpace);
    EXPECT_EQ(s.header.selectedLight, 1);
    for (std::size_t i = 0; i < frames.size(); ++i) {
        ASSERT_TRUE(s.frames[i].lights.has_value());
        EXPECT_EQ(*s.frames[i].lights, *frames[i].lights) << "frame " << i;
        EXPECT_EQ(s.frames[i].lightDrag, frames[i].lightDrag) << "frame " << i;
    }

    // Version 1, as curette wrote it before lights.
    std::mt19937 random1(3);
    std::string v1 = replaced(sessionHeaderLine(exampleHeader()), "\"version\":" + std::to_string(kSessionVersion), "\"version\":1") + "\n" +
                     sessionFrameLine(exampleFrame(0, random1)) + "\n";
    Session old = parseSession(v1, "old.jsonl", false);
    EXPECT_EQ(old.header.version, 1);
    EXPECT_FALSE(old.header.lights.has_value());
    ASSERT_EQ(old.frames.size(), 1u);
    EXPECT_FALSE(old.frames[0].lights.has_value());
    std::string v1WithLights = replaced(text, "\"version\":" + std::to_string(kSessionVersion), "\"version\":1");
    try {
        parseSession(v1WithLights, "old.jsonl", false);
        ADD_FAILURE() << "a version 1 session with lights was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("line 1: lights"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("version 2"), std::string::npos) << e.what();
    }
}

// A bad light record is an InputError naming the file, the line and the field, and the form expected.
TEST(Session, ABadLightRecordNamesTheFileAndTheField) {
    SessionHeader header = exampleHeader();
    header.lights = std::vector<SessionLight>{{{0.1, 0.2, 0.9}, true}, {{-0.5, 0.5, 0.5}, true}};
    std::mt19937 random(4);
    std::vector<std::string> v = {sessionHeaderLine(header)};
    for (std::size_t i = 0; i < 3; ++i) {
        SessionFrame f = exampleFrame(i, random);
        f.lights = std::vector<glm::dvec3>{{0.25, 0.5, 1.0}, {-0.5, 0.5, 0.5}};
        v.push_back(sessionFrameLine(f));
    }
    struct Case {
        const char* what;
        int line;
        std::string from, to;
        std::string field, expected;
    };
    const Case cases[] = {
        {"zero direction", 2, "\"lights\":[[0.25,0.5,1.0]", "\"lights\":[[0,0,0]", "line 3: lights[0]", "non-zero length"},
        {"a direction that is not three numbers", 3, "\"lights\":[[0.25,0.5,1.0]", "\"lights\":[[0.25,\"up\",1.0]", "line 4: lights[0][1]", "a number"},
        {"one light too few", 1, "\"lights\":[[0.25,0.5,1.0],", "\"lights\":[", "line 2: lights", "an array of 2 light directions"},
        {"null (NaN as JSON writes it)", 2, "[-0.5,0.5,0.5]]", "[-0.5,null,0.5]]", "line 3: lights[1][1]", "a number"},
        {"a bad space in the header", 0, "\"space\":\"camera\"", "\"space\":\"screen\"", "line 1: lights[0].space", "camera"},
        {"a selected light that does not exist", 0, "\"selected_light\":0", "\"selected_light\":2", "line 1: selected_light", "0"},
        {"a bad light drag", 3, "\"keys\"", "\"light_drag\":[1],\"keys\"", "line 4: light_drag", "2"},
    };
    for (const Case& c : cases) {
        std::vector<std::string> t = v;
        t[static_cast<std::size_t>(c.line)] = replaced(t[static_cast<std::size_t>(c.line)], c.from, c.to);
        try {
            parseSession(joined(t), "bad.jsonl", false);
            ADD_FAILURE() << c.what << ": accepted";
        } catch (const InputError& e) {
            std::string message = e.what();
            EXPECT_NE(message.find("bad.jsonl"), std::string::npos) << c.what << ": " << message;
            EXPECT_NE(message.find(c.field), std::string::npos) << c.what << ": " << message;
            EXPECT_NE(message.find(c.expected), std::string::npos) << c.what << ": " << message;
        }
    }
}

// The mesh panel's hold requests (version 4) round-trip; a binding the header's mapping does not have, or
// holds in a version 3 session, are InputErrors naming the line and the field.
TEST(Session, HoldRequestsRoundTripAndNameABadBinding) {
    std::mt19937 random(6);
    SessionFrame f = exampleFrame(0, random);
    f.holds = {{0, 1}, {input::kKeyboardBinding, 0}};
    std::string header = sessionHeaderLine(exampleHeader()), frame = sessionFrameLine(f);
    EXPECT_NE(frame.find(R"("holds":[{"binding":0,"mesh":1},{"binding":"keyboard","mesh":0}])"), std::string::npos) << frame;
    Session s = parseSession(header + "\n" + frame + "\n", "holds.jsonl", false);
    ASSERT_EQ(s.frames.size(), 1u);
    EXPECT_EQ(s.frames[0].holds, f.holds);
    struct Case {
        const char* what;
        std::string header, frame, field, expected;
    };
    const std::string v3 = replaced(header, "\"version\":" + std::to_string(kSessionVersion), "\"version\":3");
    const Case cases[] = {
        {"a binding the mapping does not have", header, replaced(frame, R"("binding":0)", R"("binding":1)"), "line 2: holds[0].binding",
         "\"keyboard\" or the index of one of the 1 bindings of line 1's mapping"},
        {"a device name instead of the keyboard", header, replaced(frame, R"("binding":"keyboard")", R"("binding":"mouse")"), "line 2: holds[1].binding",
         "\"keyboard\""},
        {"a mesh index beyond the clip-mesh limit", header, replaced(frame, R"("mesh":1})", R"("mesh":16})"), "line 2: holds[0].mesh", "0"},
        {"holds in a version 3 session", v3, frame, "line 2: holds", "version 4"},
    };
    for (const Case& c : cases) {
        try {
            parseSession(c.header + "\n" + c.frame + "\n", "holds.jsonl", false);
            ADD_FAILURE() << c.what << ": accepted";
        } catch (const InputError& e) {
            std::string message = e.what();
            EXPECT_NE(message.find(c.field), std::string::npos) << c.what << ": " << message;
            EXPECT_NE(message.find(c.expected), std::string::npos) << c.what << ": " << message;
        }
    }
    f.holds.clear();
    EXPECT_EQ(parseSession(v3 + "\n" + sessionFrameLine(f) + "\n", "v3.jsonl", false).frames.size(), 1u) << "version 3 sessions still load";
}

// A head-mounted display session (version 6): the header's room and eye sizes and each frame's head, eyes
// (pose and asymmetric field of view) and hands read back to the same doubles; an untracked hand has no pose.
// A version 5 file still loads; "xr" in a version 5 file, a frame's "xr" without the header's, and bad views
// or hands are InputErrors naming the line, the field and the expected form.
TEST(Session, HeadMountedDisplayRecordsRoundTripAndNameABadField) {
    std::mt19937 random(9);
    std::uniform_real_distribution<double> u(-1, 1);
    SessionHeader header = exampleHeader();
    header.xr = SessionXr{RoomSpace::Local, {glm::ivec2(40, 36), glm::ivec2(41, 35)}, "curette test runtime", "scripted HMD"};
    auto pose = [&] {
        TrackedView v;
        v.positionM = {u(random), 1.0 + u(random), u(random) / 3.0};
        v.orientation = glm::normalize(glm::dquat(u(random), u(random), u(random), u(random)));
        return v;
    };
    SessionFrame f = exampleFrame(0, random);
    f.xr = SessionXrFrame{};
    f.xr->displayTimeNs = 1234567891011;
    f.xr->head = pose();
    std::array<TrackedView, 2> views{pose(), pose()};
    views[0].fov = {-0.30000001192092896, 0.2199999988079071, 0.28, -0.3};
    views[1].fov = {-0.22, 0.30000001192092896, 0.28, -1.0 / 3.0};
    f.xr->views = views;
    f.xr->hands[0] = {true, pose(), 0.75, 1.0 / 3.0, {0.1, -0.9}, true};
    f.xr->hands[1] = {false, {}, 0.0, 0.25, {0.0, 0.0}, false};
    SessionFrame unrendered = exampleFrame(1, random);
    unrendered.xr = SessionXrFrame{};
    unrendered.xr->displayTimeNs = 1234567891011 + 11111111;
    const std::string headerLine = sessionHeaderLine(header), frameLine = sessionFrameLine(f), secondLine = sessionFrameLine(unrendered);
    Session s = parseSession(headerLine + "\n" + frameLine + "\n" + secondLine + "\n", "xr.jsonl", false);
    ASSERT_TRUE(s.header.xr);
    EXPECT_EQ(s.header.xr->space, RoomSpace::Local);
    EXPECT_EQ(s.header.xr->recommendedSize, header.xr->recommendedSize);
    EXPECT_EQ(s.header.xr->runtime, "curette test runtime");
    ASSERT_EQ(s.frames.size(), 2u);
    ASSERT_TRUE(s.frames[0].xr);
    const SessionXrFrame& x = *s.frames[0].xr;
    EXPECT_EQ(x.displayTimeNs, f.xr->displayTimeNs);
    EXPECT_EQ(x.head, f.xr->head);
    EXPECT_EQ(x.views, f.xr->views);
    EXPECT_EQ(x.hands, f.xr->hands);
    EXPECT_EQ(frameLine.find("\"position_m\"", frameLine.find("\"tracked\":false")), std::string::npos) << "an untracked hand has no pose";
    ASSERT_TRUE(s.frames[1].xr);
    EXPECT_FALSE(s.frames[1].xr->head);
    EXPECT_FALSE(s.frames[1].xr->views);

    struct Case {
        const char* what;
        std::string header, frame, field, expected;
    };
    const std::string v5 = replaced(headerLine, "\"version\":" + std::to_string(kSessionVersion), "\"version\":5");
    const std::string plainHeader = sessionHeaderLine(exampleHeader());
    const Case cases[] = {
        {"xr in a version 5 session", v5, frameLine, "line 1: xr", "version 6"},
        {"a frame's xr without the header's", plainHeader, frameLine, "line 2: xr", "line 1 has no \"xr\""},
        {"one view", headerLine, replaced(frameLine, "\"views\":[{", "\"views\":[{\"x\":1},{"), "line 2: xr.views", "2"},
        {"a field of view that is not four angles", headerLine, replaced(frameLine, "\"fov_rad\":[", "\"fov_rad\":[0.1,"), "line 2: xr.views[0].fov_rad",
         "4"},
        {"a field of view with left right of right", headerLine, replaced(frameLine, "\"fov_rad\":[-0.30000001192092896", "\"fov_rad\":[0.5"),
         "line 2: xr.views[0].fov_rad", "left < right"},
        {"a squeeze beyond 1", headerLine, replaced(frameLine, "\"squeeze\":0.75", "\"squeeze\":1.5"), "line 2: xr.hands[0].squeeze", "1"},
        {"a tracked hand without its pose", headerLine, replaced(frameLine, "\"tracked\":false", "\"tracked\":true"), "line 2: xr.hands[1].position_m",
         ""},
        {"a bad room space", replaced(headerLine, "\"space\":\"local\"", "\"space\":\"room\""), frameLine, "line 1: xr.space", "stage"},
        {"an eye size that is not whole pixels", replaced(headerLine, "[41,35]", "[41.5,35]"), frameLine, "line 1: xr.recommended_size[1]", "whole pixels"},
    };
    for (const Case& c : cases) {
        try {
            parseSession(c.header + "\n" + c.frame + "\n", "xr.jsonl", false);
            ADD_FAILURE() << c.what << ": accepted";
        } catch (const InputError& e) {
            std::string message = e.what();
            EXPECT_NE(message.find("xr.jsonl"), std::string::npos) << c.what << ": " << message;
            EXPECT_NE(message.find(c.field), std::string::npos) << c.what << ": " << message;
            EXPECT_NE(message.find(c.expected), std::string::npos) << c.what << ": " << message;
        }
    }
    SessionFrame plain = exampleFrame(0, random);
    EXPECT_EQ(parseSession(replaced(plainHeader, "\"version\":" + std::to_string(kSessionVersion), "\"version\":5") + "\n" + sessionFrameLine(plain) + "\n",
                           "v5.jsonl", false)
                  .frames.size(),
              1u)
        << "version 5 sessions still load";
}

// A frame that adds or removes a light (version 4) records one direction per light after its edits; the
// next frames keep that count; a version 3 session cannot add lights.
TEST(Session, LightsAddedAndRemovedChangeTheFramesLightCount) {
    SessionHeader header = exampleHeader();
    header.lights = std::vector<SessionLight>{{{0.1, 0.2, 0.9}, true}};
    std::mt19937 random(7);
    std::vector<std::string> v = {sessionHeaderLine(header)};
    SessionFrame added = exampleFrame(0, random), same = exampleFrame(1, random), removed = exampleFrame(2, random);
    added.edits = {{Setting::LightAdd, -1, nlohmann::json::parse(R"({"direction": [0, 1, 0]})")}};
    added.lights = same.lights = std::vector<glm::dvec3>{{0.1, 0.2, 0.9}, {0, 1, 0}};
    removed.edits = {{Setting::LightRemove, 0, nullptr}};
    removed.lights = std::vector<glm::dvec3>{{0, 1, 0}};
    for (const SessionFrame& f : {added, same, removed}) v.push_back(sessionFrameLine(f));
    Session s = parseSession(joined(v), "lights.jsonl", false);
    ASSERT_EQ(s.frames.size(), 3u);
    EXPECT_EQ(s.frames[1].lights->size(), 2u);
    EXPECT_EQ(s.frames[2].edits, removed.edits);
    auto message = [](const std::string& text) {
        try {
            parseSession(text, "lights.jsonl", false);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("(no error)");
    };
    std::vector<std::string> t = v;
    t[2] = replaced(t[2], "\"lights\":[[0.1,0.2,0.9],", "\"lights\":[");   // the second frame with one light
    std::string m = message(joined(t));
    EXPECT_NE(m.find("line 3: lights"), std::string::npos) << m;
    EXPECT_NE(m.find("an array of 2 light directions"), std::string::npos) << m;
    EXPECT_NE(m.find("added and removed"), std::string::npos) << m;
    t = v;
    t[0] = replaced(t[0], "\"version\":" + std::to_string(kSessionVersion), "\"version\":3");
    m = message(joined(t));
    EXPECT_NE(m.find("line 2: edits[0].setting"), std::string::npos) << m;
    EXPECT_NE(m.find("version 4"), std::string::npos) << m;
}

TEST(Session, CorruptSessionsAreNamedByLineAndTheLenientModeKeepsThePrefix) {
    struct Case {
        const char* what;
        std::vector<std::string> text;
        std::string expected;       // in the error message
        int validFramesBefore;      // -1: the header is bad, lenient refuses too
    };
    std::vector<std::string> v = validLines();
    std::vector<Case> cases;
    {
        auto t = v;
        t[3] = t[3].substr(0, t[3].size() / 2);  // a crash mid-write (without the atomic writer)
        cases.push_back({"truncated last line", t, "line 4", 2});
    }
    {
        auto t = v;
        t[0] = replaced(t[0], "\"version\":" + std::to_string(kSessionVersion), "\"version\":" + std::to_string(kSessionVersion + 1));
        cases.push_back({"wrong version", t, "version", -1});
    }
    {
        auto t = v;
        t[2] = replaced(t[2], "\"meshes\":[{\"id\":0", "\"meshes\":[{\"id\":42");
        cases.push_back({"unknown mesh id", t, "line 3", 1});
    }
    {
        auto t = v;
        std::size_t at = t[2].find("\"position_mm\":[") + 15;
        t[2] = t[2].substr(0, at) + "NaN" + t[2].substr(t[2].find(',', at));
        cases.push_back({"NaN pose (literal)", t, "line 3", 1});
    }
    {
        auto t = v;
        std::size_t at = t[3].find("\"position_mm\":[") + 15;
        t[3] = t[3].substr(0, at) + "null" + t[3].substr(t[3].find(',', at));
        cases.push_back({"NaN pose (as JSON writes it: null)", t, "line 4", 2});
    }
    {
        auto t = v;
        std::size_t at = t[1].find("\"orientation\":[") + 15;
        t[1] = t[1].substr(0, at) + "0,0,0,0" + t[1].substr(t[1].find(']', at));
        cases.push_back({"zero quaternion", t, "non-zero length", 0});
    }
    {
        auto t = v;
        t[2] = replaced(t[2], "\"bytes\":\"01", "\"bytes\":\"0x1");
        cases.push_back({"bad hex", t, "line 3", 1});
    }
    {
        auto t = v;
        t[3] = replaced(t[3], "\"reports\":[{\"device\":3", "\"reports\":[{\"device\":99");
        cases.push_back({"report from an unknown device", t, "line 4", 2});
    }
    {
        auto t = v;
        t[0] = replaced(t[0], "curette-session", "something-else");
        cases.push_back({"not a session", t, "curette-session", -1});
    }
    {
        auto t = v;
        t[0] = replaced(t[0], "\"held_meshes\":[1]", "\"held_meshes\":[1,2]");
        cases.push_back({"input state that does not fit the mapping", t, "held_meshes", -1});
    }
    cases.push_back({"empty file", {}, "line 1", -1});

    for (const Case& c : cases) {
        std::string text = joined(c.text);
        try {
            parseSession(text, "bad.jsonl", false);
            ADD_FAILURE() << c.what << ": accepted";
        } catch (const InputError& e) {
            std::string message = e.what();
            EXPECT_NE(message.find("bad.jsonl"), std::string::npos) << c.what << ": " << message;
            EXPECT_NE(message.find(c.expected), std::string::npos) << c.what << ": " << message;
        }
        if (c.validFramesBefore < 0) {
            EXPECT_THROW(parseSession(text, "bad.jsonl", true), InputError) << c.what;
        } else {
            Session s = parseSession(text, "bad.jsonl", true);
            EXPECT_EQ(static_cast<int>(s.frames.size()), c.validFramesBefore) << c.what;
            EXPECT_FALSE(s.warning.empty()) << c.what;
        }
    }
}

TEST(Session, RecorderCheckpointsCompleteSessionsAndLeavesNoTemporaryFiles) {
    auto dir = scratch("recorder");
    auto path = dir / "s.jsonl";
    std::mt19937 random(1);
    {
        SessionRecorder recorder(path, exampleHeader(), 0.1);
        EXPECT_EQ(parseSession(readText(path), path, false).frames.size(), 0u) << "a valid, empty session at once";
        for (std::size_t i = 0; i < 10; ++i) recorder.add(exampleFrame(i, random));  // frame i at i/30 s: checkpoints at 0.1 s steps
        Session mid = parseSession(readText(path), path, false);
        EXPECT_GE(mid.frames.size(), 7u);
        EXPECT_LT(mid.frames.size(), 10u) << "the last frames are only in memory until the next checkpoint";
    }  // the destructor finishes it
    EXPECT_EQ(parseSession(readText(path), path, false).frames.size(), 10u);
    int files = 0;
    for (auto& e : std::filesystem::directory_iterator(dir)) files += e.is_regular_file() ? 1 : 0;
    EXPECT_EQ(files, 1) << "no temporary files left behind";

    EXPECT_THROW(SessionRecorder("/nonexistent-dir/s.jsonl", exampleHeader()), std::exception) << "an unwritable path fails at once";
}

// A 32^3 ball with a soft shell, as a raw file, and a CAO scene with two clip meshes around it.
std::filesystem::path writeSmallScene(const std::filesystem::path& dir) {
    return curette::testing::writeNoisyBallScene(dir, nlohmann::json::parse(R"({
  "shading": "cao", "lights": null,
  "ambient_occlusion": {"samples": 8, "step_mm": 2.0},
  "clip_meshes": [
    {"name": "sphere", "mesh": {"shape": "sphere", "radius_mm": 12}, "position_mm": [30, 30, 40]},
    {"name": "box", "mesh": {"shape": "box", "size_mm": [14, 14, 30]}, "position_mm": [20, 40, 20]}]})"));
}

TEST(Replay, FromReportsReproducesThePosesAndTamperingIsCaught) {
    auto dir = scratch("from-reports");
    auto scene = writeSmallScene(dir);
    auto session = dir / "session.jsonl";
    Invocation rec = run("record --scene " + scene.string() + " --out " + session.string() +
                         " --synthetic spacemouse,dualshock4_bt,switch_pro,xbox_bt,dualsense,spacemouse_wireless --frames 90 --unplug 20");
    ASSERT_EQ(rec.exitCode, 0) << rec.output;
    Session s = readSession(session, false);
    ASSERT_EQ(s.frames.size(), 90u);
    EXPECT_NE(s.frames.back().meshes[0].position, s.frames.front().meshes[0].position) << "the spacemouse moved mesh 0";
    EXPECT_NE(s.frames.back().meshes[1].position, s.frames.front().meshes[1].position) << "the gamepad moved mesh 1";
    bool removed = false, readded = false;
    for (const SessionFrame& f : s.frames) {
        removed |= !f.devicesRemoved.empty();
        readded |= removed && !f.devicesAdded.empty();
    }
    EXPECT_TRUE(removed && readded) << "the unplugged device was released and picked up again";

    Invocation ok = run("replay " + session.string() + " --from-reports --no-render");
    EXPECT_EQ(ok.exitCode, 0) << ok.output;
    EXPECT_NE(ok.output.find("identical to the recorded ones"), std::string::npos) << ok.output;

    // One recorded coordinate off by 1e-9 mm: the check must see it.
    std::vector<std::string> ls = lines(readText(session));
    std::string& line = ls[40];
    std::size_t at = line.find("\"position_mm\":[") + 15;
    std::size_t end = line.find(',', at);
    double x = std::stod(line.substr(at, end - at));
    char text[64];
    std::snprintf(text, sizeof text, "%.17g", x + 1e-9);
    line = line.substr(0, at) + text + line.substr(end);
    auto tampered = dir / "tampered.jsonl";
    writeText(tampered, joined(ls));
    Invocation bad = run("replay " + tampered.string() + " --from-reports --no-render");
    EXPECT_EQ(bad.exitCode, 1) << bad.output;
    EXPECT_NE(bad.output.find("line 41"), std::string::npos) << bad.output;
}

std::string column(const std::string& csv, int index) {
    std::string out;
    for (const std::string& l : lines(csv)) {
        std::stringstream s(l);
        std::string cell;
        for (int i = 0; i <= index && std::getline(s, cell, ','); ++i) {}
        out += cell + "\n";
    }
    return out;
}

TEST(Replay, CheckIsDeterministicAndCaoEqualsLaoOnEveryFrame) {
    auto dir = scratch("check");
    auto scene = writeSmallScene(dir);
    auto session = dir / "session.jsonl";
    ASSERT_EQ(run("record --scene " + scene.string() + " --out " + session.string() + " --synthetic spacemouse,dualshock4 --frames 8 --fps 4").exitCode, 0);
    Invocation first = run("replay " + session.string() + " --check --out " + (dir / "a").string());
    ASSERT_EQ(first.exitCode, 0) << first.output;
    Invocation second = run("replay " + session.string() + " --check --from-reports --out " + (dir / "b").string());
    ASSERT_EQ(second.exitCode, 0) << second.output;
    std::string a = readText(dir / "a" / "frames.csv"), b = readText(dir / "b" / "frames.csv");
    ASSERT_EQ(lines(a).size(), 9u) << a;
    EXPECT_EQ(column(a, 5), column(b, 5)) << "image hashes differ between two replays";
    EXPECT_EQ(column(a, 6), "cao_equals_lao\nyes\nyes\nyes\nyes\nyes\nyes\nyes\nyes\n");
    EXPECT_TRUE(std::filesystem::exists(dir / "a" / "frame_000007.png"));
    EXPECT_TRUE(std::filesystem::exists(dir / "a" / "frames.png")) << first.output;
    // Some voxels are recomputed once the meshes move, never all of them.
    double maxFraction = 0;
    for (const std::string& l : lines(column(a, 4)))
        if (l != "recomputed_fraction") maxFraction = std::max(maxFraction, std::stod(l));
    EXPECT_GT(maxFraction, 0.0);
    EXPECT_LT(maxFraction, 1.0);
}

TEST(Replay, CorruptFilesFailCleanlyAndLenientReplaysThePrefix) {
    auto dir = scratch("corrupt");
    auto scene = writeSmallScene(dir);
    auto session = dir / "session.jsonl";
    ASSERT_EQ(run("record --scene " + scene.string() + " --out " + session.string() + " --synthetic dualsense --frames 6").exitCode, 0);
    std::vector<std::string> ls = lines(readText(session));
    ls.back() = ls.back().substr(0, ls.back().size() / 3);
    auto truncated = dir / "truncated.jsonl";
    writeText(truncated, joined(ls));
    Invocation strict = run("replay " + truncated.string() + " --size 16x16");
    EXPECT_EQ(strict.exitCode, 2) << strict.output;
    EXPECT_NE(strict.output.find("truncated.jsonl"), std::string::npos) << strict.output;
    EXPECT_NE(strict.output.find("line 7"), std::string::npos) << strict.output;
    Invocation lenient = run("replay " + truncated.string() + " --lenient --size 16x16 --every 5");
    EXPECT_EQ(lenient.exitCode, 0) << lenient.output;
    EXPECT_NE(lenient.output.find("replayed 5 frames"), std::string::npos) << lenient.output;

    Invocation missing = run("replay " + (dir / "none.jsonl").string());
    EXPECT_EQ(missing.exitCode, 2) << missing.output;
    Invocation badOption = run("record --scene " + scene.string() + " --out " + (dir / "x.jsonl").string() + " --synthetic joystick");
    EXPECT_EQ(badOption.exitCode, 2);
    EXPECT_NE(badOption.output.find("--synthetic"), std::string::npos) << badOption.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "x.jsonl"));
}

// The small ball in ismos with two lights (one world-space), for the light sessions.
std::filesystem::path writeSmallIsmosScene(const std::filesystem::path& dir) {
    writeSmallScene(dir);
    writeText(dir / "ismos.json", R"({
  "volume": {"path": "ball.raw", "format": "raw", "raw": {"dims": [32, 32, 32], "type": "uint8", "spacing": [2, 2, 2]}},
  "transfer_function": {"color": [[0, 0, 0, 0], [100, 0.8, 0.6, 0.5], [255, 1, 1, 1]], "opacity": [[0, 0], [60, 0], [100, 0.2], [255, 0.8]]},
  "camera": {"target": "center", "distance_mm": 200, "azimuth_deg": 20, "elevation_deg": 25, "fov_deg": 30},
  "shading": "ismos",
  "lights": [{"direction": [0.7, 0.4, 0.6], "space": "camera"}, {"direction": [-0.5, 0.6, 0.3], "space": "world", "intensity": 0.6}],
  "ismos": {"light_samples": 4, "test_points": 16},
  "image": {"width": 40, "height": 40}
})");
    return dir / "ismos.json";
}

// The viewer's loop without a window: live keys (I/J/K/L held, O, a Shift + left drag) turn the lights through
// the input pipeline and the session step while a renderer draws each frame and the session is recorded. Each
// light move plans only the ISMOS passes; the recorded session replays, following the recorded lights and
// re-deriving them from the recorded keys, to the image hashes the live frames had.
TEST(Replay, ASessionThatMovesALightReplaysToTheLiveImageHashes) {
    auto dir = scratch("lights");
    auto scene = writeSmallIsmosScene(dir);
    auto session = dir / "lights.jsonl";
    std::vector<std::string> live;
    {
        LoadedScene loaded = loadSceneWithVolume(scene);
        auto context = gl::createHeadlessContext();
        Renderer renderer(*context, loaded.volume, loaded.scene.transferFunction);
        configureRenderer(loaded, renderer);
        SessionStep step(InteractionState::fromScene(loaded.scene), initialFrame(loaded.scene, renderer.geometry()));
        LiveInput input(std::make_unique<input::FakeHidBackend>(std::make_shared<input::FakeHidBackend::Ports>()), input::defaultMapping(), 40.0,
                        60.0);
        LiveRecording recording(session, "ismos.json", step.state(), input, 0.0);
        int moves = 0;
        for (int f = 0; f < 12; ++f) {
            input::KeyboardMouseState keys;
            auto hold = [&](input::Key k) { keys.keys |= 1u << static_cast<int>(k); };
            if (f >= 1 && f < 4) hold(input::Key::L);
            if (f >= 3 && f < 6) hold(input::Key::I);
            if (f == 6) hold(input::Key::O);   // the world-space light from here on
            if (f == 7 || f == 8) keys.lightDragPixels = {5.0, -3.0};
            if (f == 10) hold(input::Key::J), hold(input::Key::K);
            double now = f / 10.0, dt = f == 0 ? 0.0 : 0.1;
            InputFrame in = input.step(now, keys, dt, static_cast<int>(step.state().meshes.size()));
            StepChanges changes = step.apply(in.actions, step.frame().size.y);
            recording.addFrame(now, dt, step.frame().size, step.frame().camera, step.state(), keys, in);
            step.syncTo(renderer.clipMeshes());
            FrameDescription frame = step.frame();
            if (f > 0) {
                EXPECT_EQ(changes.lights, !renderer.showing(frame)) << "frame " << f << ": only a light move changes the frame";
            }
            renderer.render(frame);
            if (changes.lights) {
                ++moves;
                std::vector<Pass> planned;
                for (const PlannedPass& p : renderer.lastPlan().passes) planned.push_back(p.pass);
                EXPECT_EQ(planned, (std::vector<Pass>{Pass::IsmosRayCast, Pass::IsmosOcclusion})) << "frame " << f;
            }
            live.push_back(imageHash(toRgba8(renderer.readImage(), glm::vec4(loaded.scene.background))));
        }
        recording.finish();
        EXPECT_EQ(moves, 8) << "frames 1-5, 7, 8 and 10 turn a light";
        EXPECT_NE(live.front(), live.back()) << "the moves must show in the image for the comparison to mean something";
        EXPECT_NE(live[6], live[9]) << "and so must the second light's";
    }
    Session s = readSession(session, false);
    ASSERT_EQ(s.frames.size(), 12u);
    ASSERT_TRUE(s.frames.back().lights.has_value());
    EXPECT_NE((*s.frames.back().lights)[0], (*s.frames.front().lights)[0]);
    EXPECT_NE((*s.frames.back().lights)[1], (*s.frames.front().lights)[1]);
    EXPECT_EQ(s.frames[7].lightDrag, glm::dvec2(5.0, -3.0));
    std::string expected = "image_hash\n";
    for (const std::string& h : live) expected += h + "\n";
    for (const char* mode : {"", " --from-reports"}) {
        std::filesystem::path out = dir / (std::string("replay") + (*mode ? "-reports" : ""));
        Invocation r = run("replay " + session.string() + " --check --out " + out.string() + mode);
        ASSERT_EQ(r.exitCode, 0) << r.output;
        EXPECT_EQ(column(readText(out / "frames.csv"), 5), expected) << "replay" << mode << " differs from the live frames";
        if (*mode) {
            EXPECT_NE(r.output.find("identical to the recorded ones"), std::string::npos) << r.output;
        }
    }
}

// curette record --move-lights: scripted light keys and drags (no device needed) turn both lights, and the
// lights re-derived from the recorded keys equal the recorded ones bit for bit; one recorded light direction
// off in its last digit is caught.
TEST(Replay, RecordMoveLightsReDerivesTheLightsFromTheKeys) {
    auto dir = scratch("record-lights");
    auto scene = writeSmallIsmosScene(dir);
    auto session = dir / "lights.jsonl";
    Invocation rec = run("record --scene " + scene.string() + " --out " + session.string() + " --move-lights --frames 40");
    ASSERT_EQ(rec.exitCode, 0) << rec.output;
    Session s = readSession(session, false);
    ASSERT_EQ(s.frames.size(), 40u);
    ASSERT_TRUE(s.header.lights.has_value());
    EXPECT_EQ(s.header.lights->size(), 2u);
    EXPECT_NE((*s.frames.back().lights)[0], (*s.header.lights)[0].direction) << "light 0 turned";
    EXPECT_NE((*s.frames.back().lights)[1], (*s.header.lights)[1].direction) << "light 1 turned after O";
    Invocation ok = run("replay " + session.string() + " --from-reports --no-render");
    EXPECT_EQ(ok.exitCode, 0) << ok.output;
    EXPECT_NE(ok.output.find("identical to the recorded ones"), std::string::npos) << ok.output;

    std::vector<std::string> ls = lines(readText(session));
    std::string& line = ls[30];
    std::size_t at = line.find("\"lights\":[[") + 11;
    std::size_t end = line.find(',', at);
    double x = std::stod(line.substr(at, end - at));
    char text[64];
    std::snprintf(text, sizeof text, "%.17g", std::nextafter(x, 2.0));
    line = line.substr(0, at) + text + line.substr(end);
    writeText(dir / "tampered.jsonl", joined(ls));
    Invocation bad = run("replay " + (dir / "tampered.jsonl").string() + " --from-reports --no-render");
    EXPECT_EQ(bad.exitCode, 1) << bad.output;
    EXPECT_NE(bad.output.find("line 31"), std::string::npos) << bad.output;

    Invocation unplug = run("record --scene " + scene.string() + " --out " + (dir / "x.jsonl").string() + " --move-lights --unplug 3");
    EXPECT_EQ(unplug.exitCode, 2) << unplug.output;
    EXPECT_NE(unplug.output.find("--unplug"), std::string::npos) << unplug.output;
}

// curette record --press-shading MODE@FRAME: the mode's key pressed at that frame, as at the window (no device
// needed): the frames before keep the scene's shading, the frame and those after have the mode. A mode that is
// none, or no frame, is an error naming the option.
TEST(Replay, RecordPressShadingSwitchesTheModeAtItsFrame) {
    auto dir = scratch("record-shading");
    auto scene = writeSmallIsmosScene(dir);
    auto session = dir / "switch.jsonl";
    Invocation rec = run("record --scene " + scene.string() + " --out " + session.string() + " --press-shading dos@4 --frames 8");
    ASSERT_EQ(rec.exitCode, 0) << rec.output;
    Session s = readSession(session, false);
    ASSERT_EQ(s.frames.size(), 8u);
    for (std::size_t f = 0; f < s.frames.size(); ++f)
        EXPECT_EQ(s.frames[f].shading == ShadingMode::Dos, f >= 4) << "frame " << f << ": " << shadingModeName(s.frames[f].shading);
    for (const char* bad : {"dos", "fancy@3", "dos@x", "dos@150"}) {   // 150 frames by default: 0-149
        Invocation r = run("record --scene " + scene.string() + " --out " + (dir / "bad.jsonl").string() + " --press-shading " + bad);
        EXPECT_EQ(r.exitCode, 2) << bad << ": " << r.output;
        EXPECT_NE(r.output.find("press-shading"), std::string::npos) << bad << ": " << r.output;
    }
}

TEST(Replay, TheShippedDemoReproducesItsPosesFromItsReports) {
    std::string demo = std::string(CURETTE_SOURCE_DIR) + "/assets/sessions/demo.jsonl";
    Session s = readSession(demo, false);
    ASSERT_GE(s.frames.size(), 30u);
    ASSERT_EQ(s.frames.front().meshes.size(), 2u);
    // Two meshes moving at once: both change between consecutive frames somewhere in the middle.
    int bothMoving = 0;
    for (std::size_t i = 1; i < s.frames.size(); ++i)
        bothMoving += s.frames[i].meshes[0].position != s.frames[i - 1].meshes[0].position &&
                      s.frames[i].meshes[1].position != s.frames[i - 1].meshes[1].position;
    EXPECT_GT(bothMoving, static_cast<int>(s.frames.size()) / 2);
    Invocation r = run("replay " + demo + " --from-reports --no-render");
    EXPECT_EQ(r.exitCode, 0) << r.output;
}

}  // namespace
}  // namespace curette
