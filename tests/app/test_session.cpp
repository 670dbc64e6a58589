// Sessions: the file format (round trip, corrupt files named by line, the lenient prefix), the recorder's
// atomic checkpoints, and record/replay through the real binary on a small CAO scene: poses re-derived from the
// raw reports equal the recorded ones, a replay is deterministic, CAO equals LAO on every frame.
#include "app/session.h"
#include "base/error.h"

#include <nlohmann/json.hpp>

#include "tests/app/run_curette.h"

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

std::filesystem::path scratch(const std::string& name) {
    auto dir = std::filesystem::temp_directory_path() / ("curette-session-" + std::to_string(::getpid())) / name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

std::string readText(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

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
    h.meshes = {{0, "sphere", "", {{1, 2, 3}, glm::dquat(1, 0, 0, 0)}, {{1, 2, 3}, glm::dquat(1, 0, 0, 0)}, glm::dvec3(1)},
                {4, "added 4", R"({"shape":"sphere","radius_mm":15})", {{0.1, 0.2, 0.3}, glm::normalize(glm::dquat(0.9, 0.1, 0.2, 0.3))},
                 {{0, 0, 0}, glm::dquat(1, 0, 0, 0)}, glm::dvec3(2, 1, 1)}};
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
        t[0] = replaced(t[0], "\"version\":1", "\"version\":7");
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
    std::vector<std::uint8_t> voxels(32 * 32 * 32);
    std::mt19937 random(5);
    std::uniform_int_distribution<int> noise(0, 20);
    for (int z = 0; z < 32; ++z)
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x) {
                double r = std::sqrt((x - 15.5) * (x - 15.5) + (y - 15.5) * (y - 15.5) + (z - 15.5) * (z - 15.5));
                int v = r < 9 ? 200 : r < 13 ? 120 : 0;
                voxels[static_cast<std::size_t>((z * 32 + y) * 32 + x)] = static_cast<std::uint8_t>(std::min(255, v + noise(random)));
            }
    std::ofstream(dir / "ball.raw", std::ios::binary).write(reinterpret_cast<const char*>(voxels.data()), static_cast<std::streamsize>(voxels.size()));
    writeText(dir / "scene.json", R"({
  "volume": {"path": "ball.raw", "format": "raw", "raw": {"dims": [32, 32, 32], "type": "uint8", "spacing": [2, 2, 2]}},
  "transfer_function": {"color": [[0, 0, 0, 0], [100, 0.8, 0.6, 0.5], [255, 1, 1, 1]], "opacity": [[0, 0], [60, 0], [100, 0.2], [255, 0.8]]},
  "camera": {"target": "center", "distance_mm": 200, "azimuth_deg": 20, "elevation_deg": 25, "fov_deg": 30},
  "shading": "cao",
  "image": {"width": 48, "height": 48},
  "ambient_occlusion": {"rays": "6", "samples": 8, "step_mm": 2.0, "antialiasing_samples": 4},
  "clip_meshes": [
    {"name": "sphere", "mesh": {"shape": "sphere", "radius_mm": 12}, "position_mm": [30, 30, 40]},
    {"name": "box", "mesh": {"shape": "box", "size_mm": [14, 14, 30]}, "position_mm": [20, 40, 20]}
  ]
})");
    return dir / "scene.json";
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
