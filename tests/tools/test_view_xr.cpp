// `curette view --xr` without a headset: the real binary under Xvfb, the real Khronos loader, the Khronos core
// validation layer, and curette's test runtime (tests/xr_runtime) playing a scripted head, found only through
// XR_RUNTIME_JSON. The session walks through its states to EXITING, the layer reports nothing, and every eye
// image the runtime read back from the swapchains is, pixel for pixel, what `render --xr-views --stereo
// side-by-side` renders headless from the views the runtime located for that frame.
#include "session/session.h"
#include "tests/tools/run_curette.h"
#include "tests/tools/tool_test_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <sstream>

namespace curette {
namespace {

using curette::testing::readPng;

std::filesystem::path scratch(const std::string& name) { return curette::testing::freshScratchFolder("curette-xr-test", name); }

struct ShellRun {
    int exitCode = -1;
    std::string output;
};

ShellRun runShell(const std::string& command) {
    ShellRun run;
    FILE* pipe = popen((command + " 2>&1").c_str(), "r");
    char buffer[4096];
    while (std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) run.output.append(buffer, n);
    int status = pclose(pipe);
    run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return run;
}

// Three frames of a head 0.25 m in front of the ball on its table (its centre at 0.932 m, 0.5 m in front of the
// stage origin), looking down at it, moving and tilting; asymmetric fields of view, mirrored between the eyes.
nlohmann::json poseScript() {
    nlohmann::json frames = nlohmann::json::array();
    const double pitch = -0.35;   // looking down
    struct Head {
        double x, roll;
    };
    for (Head h : {Head{0.0, 0.0}, Head{0.03, 0.0}, Head{0.0, 0.25}}) {
        glm::dquat q = glm::angleAxis(pitch, glm::dvec3(1, 0, 0)) * glm::angleAxis(h.roll, glm::dvec3(0, 0, 1));
        frames.push_back({{"head", {{"position", {h.x, 1.03, -0.25}}, {"orientation", {q.x, q.y, q.z, q.w}}}}});
    }
    return {{"recommended_size", {40, 36}},
            {"ipd_m", 0.064},
            {"fov_rad", {{"left", {-0.30, 0.22, 0.28, -0.30}}, {"right", {-0.22, 0.30, 0.28, -0.30}}}},
            {"frames", frames}};
}

// How `view --xr` meets the test runtime: under Xvfb with the core validation layer (a GLX binding), or
// headless (no X server: an EGL binding, which the runtime offers only with `offerEgl`; the layer is left out,
// see HeadlessThroughEglWhereTheRuntimeOffersIt).
struct XrLaunch {
    bool headless = false;
    bool offerEgl = false;
    bool record = false;   // --record dir/session.jsonl (XrRun::session)
};

// `view --xr` of `scene` (with `arguments`; exact quality unless they say otherwise, so every submitted eye is
// the exact frame of its views) against the test runtime playing `script` (written to dir/script.json): the
// run, the runtime's folder (eyes, runtime.log), the layer's report file (none headless) and the recorded session.
struct XrRun {
    ShellRun shell;
    std::filesystem::path eyes, validation, session;
};
XrRun runViewXr(const std::filesystem::path& dir, const nlohmann::json& script, const std::filesystem::path& scene, const std::string& arguments = "",
                XrLaunch launch = {}) {
    auto scriptPath = dir / "script.json";
    std::ofstream(scriptPath) << script.dump(2);
    XrRun run{{}, dir / "eyes", dir / "validation.txt", launch.record ? dir / "session.jsonl" : std::filesystem::path()};
    std::string runtime = "env" + std::string(launch.headless ? " -u DISPLAY" : "") + " XR_RUNTIME_JSON=" + CURETTE_XR_TEST_RUNTIME_JSON +
                          " CURETTE_XR_TEST_SCRIPT=" + scriptPath.string() + " CURETTE_XR_TEST_OUT=" + run.eyes.string() +
                          (launch.offerEgl ? " CURETTE_XR_TEST_EGL=1" : "");
    if (!launch.headless)
        runtime = "xvfb-run -a -s '-screen 0 640x480x24' " + runtime + " XR_ENABLE_API_LAYERS=XR_APILAYER_LUNARG_core_validation" +
                  " XR_CORE_VALIDATION_EXPORT_TYPE=text XR_CORE_VALIDATION_FILE_NAME=" + run.validation.string() + " XR_LOADER_DEBUG=info";
    const std::string quality = arguments.find("--quality") == std::string::npos ? " --quality exact" : "";
    const std::string record = launch.record ? " --record " + run.session.string() : "";
    run.shell = runShell(runtime + " " + CURETTE_BINARY + " view --xr" + (launch.headless ? " --headless" : "") + " --scene " + scene.string() + quality +
                         record + arguments);
    return run;
}

// The validation layer's report names no rule.
void expectValidationSilent(const std::filesystem::path& validation) {
    std::string report = curette::testing::readTextFile(validation);
    EXPECT_EQ(report.find("VUID"), std::string::npos) << report;
    EXPECT_EQ(report.find("[VALID_"), std::string::npos) << report;
}

std::vector<std::string> lines(const std::string& text, const std::string& prefix) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
        if (line.rfind(prefix, 0) == 0) out.push_back(line.substr(prefix.size()));
    return out;
}

TEST(ViewXr, TheSessionRunsToExitUnderValidationAndSubmitsTheHeadlessStereoImages) {
    if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0) GTEST_SKIP() << "xvfb-run is not installed (package xvfb)";
    auto dir = scratch("session");
    auto scene = curette::testing::writeNoisyBallScene(dir, nlohmann::json::parse(R"({"shading": "cao", "clip_meshes": [
        {"name": "sphere", "mesh": {"shape": "sphere", "radius_mm": 12}, "position_mm": [32, 44, 40]}]})"));
    XrRun xr = runViewXr(dir, poseScript(), scene);
    const ShellRun& run = xr.shell;
    const std::filesystem::path& out = xr.eyes;
    ASSERT_EQ(run.exitCode, 0) << run.output;

    // The loader enabled the validation layer, and the layer found nothing to say.
    EXPECT_NE(run.output.find("XR_APILAYER_LUNARG_core_validation"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("Core Validation output type: text"), std::string::npos) << run.output;
    expectValidationSilent(xr.validation);

    // The state machine, as curette saw it and as the runtime drove it (OpenXR 9.3).
    const std::vector<std::string> walk{"IDLE", "READY", "SYNCHRONIZED", "VISIBLE", "FOCUSED", "VISIBLE", "SYNCHRONIZED", "STOPPING", "IDLE", "EXITING"};
    EXPECT_EQ(lines(run.output, "xr session state "), walk) << run.output;
    std::string log = curette::testing::readTextFile(out / "runtime.log");
    EXPECT_EQ(lines(log, "state "), walk) << log;
    EXPECT_EQ(log.find("error"), std::string::npos) << log;
    EXPECT_NE(run.output.find("xr session over: 3 frames rendered"), std::string::npos) << run.output;

    std::vector<std::uint8_t> first;
    for (int frame = 0; frame < 3; ++frame) {
        char stem[32];
        std::snprintf(stem, sizeof stem, "frame_%06d", frame);
        curette::testing::Png left = readPng(out / (std::string(stem) + "_left.png"));
        curette::testing::Png right = readPng(out / (std::string(stem) + "_right.png"));
        ASSERT_FALSE(left.rgba.empty()) << stem;
        ASSERT_FALSE(right.rgba.empty()) << stem;
        // The pitch that fits the field of view into 40 x 36 is the height's (0.597 / 36): 32 x 36 pixels, each
        // edge moved inwards to a whole pixel (render/model/tracked_view.h).
        EXPECT_EQ(left.width, 31);
        EXPECT_EQ(left.height, 35);
        EXPECT_EQ(right.width, 31);
        EXPECT_EQ(right.height, 35);
        auto rendered = dir / (std::string(stem) + "_render.png");
        curette::testing::Invocation r = curette::testing::runCurette("render --scene " + scene.string() + " --xr-views " +
                                                                      (out / (std::string(stem) + "_views.json")).string() +
                                                                      " --stereo side-by-side --out " + rendered.string());
        ASSERT_EQ(r.exitCode, 0) << r.output;
        curette::testing::Png pair = readPng(rendered);
        ASSERT_EQ(pair.width, left.width + right.width);
        ASSERT_EQ(pair.height, left.height);
        std::vector<std::uint8_t> joined;
        for (int y = 0; y < left.height; ++y) {
            auto row = [&](const curette::testing::Png& p) { return p.rgba.begin() + static_cast<std::ptrdiff_t>(y) * p.width * 4; };
            joined.insert(joined.end(), row(left), row(left) + left.width * 4);
            joined.insert(joined.end(), row(right), row(right) + right.width * 4);
        }
        EXPECT_TRUE(joined == pair.rgba) << stem << ": the submitted eyes differ from render --xr-views";
        // The ball is in view: the eye is not one colour.
        EXPECT_NE(std::count(left.rgba.begin(), left.rgba.end(), left.rgba[0]), static_cast<std::ptrdiff_t>(left.rgba.size())) << stem;
        if (frame == 0) first = left.rgba;
        else EXPECT_NE(left.rgba, first) << stem << ": the head moved, the image did not";
    }
}

// Two scripted controllers (Valve Index profile) under validation: the right hand grabs tool 1 with its squeeze
// and carries it 5 cm to the user's right (the patient's left, -R), then lets go and moves on; the left hand
// holds nothing, so tool 0 stays.
TEST(ViewXr, AScriptedControllerCarriesItsToolThroughTheSessionStep) {
    if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0) GTEST_SKIP() << "xvfb-run is not installed (package xvfb)";
    auto dir = scratch("controllers");
    auto scene = curette::testing::writeNoisyBallScene(dir, nlohmann::json::parse(R"({"shading": "phong", "clip_meshes": [
        {"name": "sphere", "mesh": {"shape": "sphere", "radius_mm": 8}, "position_mm": [30, 30, 44]},
        {"name": "box", "mesh": {"shape": "box", "size_mm": [10, 10, 24]}, "position_mm": [22, 40, 24]}]})"));
    nlohmann::json script = poseScript();
    script["interaction_profile"] = "/interaction_profiles/valve/index_controller";
    const double squeeze[] = {0.0, 1.0, 1.0, 0.0, 0.0};
    const double x[] = {0.10, 0.10, 0.15, 0.20, 0.20};
    nlohmann::json frames = nlohmann::json::array();
    for (int i = 0; i < 5; ++i) {
        nlohmann::json f = script["frames"][0];
        f["right"] = {{"grip", {{"position", {x[i], 1.0, -0.4}}, {"orientation", {0, 0, 0, 1}}}}, {"squeeze", squeeze[i]}};
        f["left"] = {{"grip", {{"position", {-0.1 - 0.02 * i, 1.0, -0.4}}, {"orientation", {0, 0, 0, 1}}}}, {"squeeze", 0.0}};
        frames.push_back(f);
    }
    script["frames"] = frames;
    XrRun xr = runViewXr(dir, script, scene);
    const ShellRun& run = xr.shell;
    const std::filesystem::path& out = xr.eyes;
    ASSERT_EQ(run.exitCode, 0) << run.output;
    expectValidationSilent(xr.validation);
    std::string log = curette::testing::readTextFile(out / "runtime.log");
    EXPECT_NE(log.find("bindings suggested for /interaction_profiles/valve/index_controller: 14"), std::string::npos) << log;
    EXPECT_NE(run.output.find("xr session over: 5 frames rendered"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("xr tool 0 \"sphere\" left at 30.000, 30.000, 44.000 mm"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("xr tool 1 \"box\" left at -28.000, 40.000, 24.000 mm"), std::string::npos) << run.output;
}

// Left and right eyes of a captured frame as one side-by-side image (rows of the left, then the right).
std::vector<std::uint8_t> sideBySide(const curette::testing::Png& left, const curette::testing::Png& right) {
    std::vector<std::uint8_t> joined;
    for (int y = 0; y < left.height; ++y) {
        auto row = [&](const curette::testing::Png& p) { return p.rgba.begin() + static_cast<std::ptrdiff_t>(y) * p.width * 4; };
        joined.insert(joined.end(), row(left), row(left) + left.width * 4);
        joined.insert(joined.end(), row(right), row(right) + right.width * 4);
    }
    return joined;
}

std::string lineStartingWith(const std::string& text, const std::string& prefix) {
    std::vector<std::string> found = lines(text, prefix);
    return found.empty() ? std::string() : prefix + found.back();
}

// A scripted two-controller session (Oculus Touch) recorded with --record under validation: both hands grab
// their tools; the left carries and turns tool 0 and grows it with its thumbstick; the right carries tool 1
// into the ball with its trigger held, drilling. Replayed headless, every frame's two eyes side by side are
// the images the runtime read back from the swapchains, CAO == LAO holds on each, the poses and the drilling
// re-derived from the recorded hands are the recorded ones bit for bit, and the removal is the live one.
TEST(ViewXr, ARecordedTwoControllerSessionReplaysBitForBit) {
    if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0) GTEST_SKIP() << "xvfb-run is not installed (package xvfb)";
    auto dir = scratch("record");
    auto scene = curette::testing::writeNoisyBallScene(dir, nlohmann::json::parse(R"({"shading": "cao", "clip_meshes": [
        {"name": "sphere", "mesh": {"shape": "sphere", "radius_mm": 8}, "position_mm": [30, 30, 44]},
        {"name": "burr", "mesh": {"shape": "sphere", "radius_mm": 5}, "position_mm": [24, 34, 30]}]})"));
    nlohmann::json script = poseScript();
    script["interaction_profile"] = "/interaction_profiles/oculus/touch_controller";
    const int n = 5;
    const double squeeze[n] = {0.0, 1.0, 1.0, 1.0, 0.0};
    const double trigger[n] = {0.0, 0.0, 1.0, 0.8, 0.0};
    const double stick[n] = {0.0, 0.0, 1.0, 1.0, 0.0};
    nlohmann::json frames = nlohmann::json::array();
    for (int i = 0; i < n; ++i) {
        nlohmann::json f = script["frames"][static_cast<std::size_t>(i % 3)];
        const double step = std::min(i, 3);
        glm::dquat turn = glm::angleAxis(0.05 * step, glm::normalize(glm::dvec3(0.3, 1.0, 0.2)));
        f["left"] = {{"grip", {{"position", {-0.1, 1.0 + 0.004 * step, -0.4}}, {"orientation", {turn.x, turn.y, turn.z, turn.w}}}},
                     {"squeeze", squeeze[i]},
                     {"thumbstick", {0.0, stick[i]}}};
        f["right"] = {{"grip", {{"position", {0.1 - 0.006 * step, 1.0, -0.4}}, {"orientation", {0, 0, 0, 1}}}},
                      {"squeeze", squeeze[i]},
                      {"trigger", trigger[i]}};
        frames.push_back(f);
    }
    script["frames"] = frames;
    XrRun xr = runViewXr(dir, script, scene, "", XrLaunch{.record = true});
    const std::filesystem::path& session = xr.session;
    const ShellRun& live = xr.shell;
    const std::filesystem::path& out = xr.eyes;
    ASSERT_EQ(live.exitCode, 0) << live.output;
    expectValidationSilent(xr.validation);
    std::string log = curette::testing::readTextFile(out / "runtime.log");
    // The trigger is bound in every profile that has one: not the simple controller (its one button grabs). Per
    // hand: grip, squeeze, shading, stick, trigger, volume and erase; the Vive has one trackpad click for volume
    // and erase (split by where it is pressed).
    EXPECT_NE(log.find("bindings suggested for /interaction_profiles/oculus/touch_controller: 14"), std::string::npos) << log;
    EXPECT_NE(log.find("bindings suggested for /interaction_profiles/htc/vive_controller: 12"), std::string::npos) << log;
    EXPECT_NE(log.find("bindings suggested for /interaction_profiles/khr/simple_controller: 6"), std::string::npos) << log;
    EXPECT_NE(live.output.find("xr session over: 5 frames rendered"), std::string::npos) << live.output;
    const std::string drilled = lineStartingWith(live.output, "drilled ");
    ASSERT_FALSE(drilled.empty()) << "the trigger drilled nothing:\n" << live.output;

    // The file: the room and eye sizes, and per frame the head as the runtime placed it, both views and both hands.
    std::ifstream in(session);
    std::string headerLine;
    std::getline(in, headerLine);
    nlohmann::ordered_json header = nlohmann::ordered_json::parse(headerLine);
    EXPECT_EQ(header["version"], kSessionVersion);
    EXPECT_EQ(header["xr"]["space"], "stage");
    EXPECT_EQ(header["xr"]["recommended_size"], nlohmann::ordered_json::parse("[[40, 36], [40, 36]]"));
    std::vector<nlohmann::ordered_json> recorded;   // ordered: dumped again, a line reads as in the file
    for (std::string line; std::getline(in, line);) recorded.push_back(nlohmann::ordered_json::parse(line));
    ASSERT_EQ(recorded.size(), static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
        const nlohmann::ordered_json& x = recorded[static_cast<std::size_t>(i)]["xr"];
        ASSERT_TRUE(x.contains("views")) << i;
        ASSERT_TRUE(x.contains("head")) << i;
        ASSERT_TRUE(x["hands"][1].contains("position_m")) << i << ": the right hand tracked";
        EXPECT_EQ(x["head"]["position_m"][1].get<double>(), static_cast<double>(1.03f)) << i;
        EXPECT_EQ(x["hands"][1]["position_m"][0].get<double>(), static_cast<double>(static_cast<float>(0.1 - 0.006 * std::min(i, 3)))) << i;
        EXPECT_EQ(x["hands"][1]["trigger"].get<double>(), static_cast<double>(static_cast<float>(trigger[i]))) << i;
        EXPECT_EQ(recorded[static_cast<std::size_t>(i)].contains("drill"), i == 2 || i == 3) << i;
    }

    // Replayed headless: the eyes side by side are the submitted ones; CAO == LAO on every frame.
    auto replayed = dir / "replay";
    curette::testing::Invocation replay = curette::testing::runCurette("replay " + session.string() + " --check --out " + replayed.string());
    ASSERT_EQ(replay.exitCode, 0) << replay.output;
    EXPECT_NE(replay.output.find("CAO == LAO on 5 of 5 checked frames"), std::string::npos) << replay.output;
    EXPECT_EQ(lineStartingWith(replay.output, "drilled "), drilled) << replay.output;
    for (int frame = 0; frame < n; ++frame) {
        char stem[32];
        std::snprintf(stem, sizeof stem, "frame_%06d", frame);
        curette::testing::Png left = readPng(out / (std::string(stem) + "_left.png"));
        curette::testing::Png right = readPng(out / (std::string(stem) + "_right.png"));
        curette::testing::Png pair = readPng(replayed / (std::string(stem) + ".png"));
        ASSERT_EQ(pair.width, left.width + right.width) << stem;
        ASSERT_EQ(pair.height, left.height) << stem;
        EXPECT_TRUE(sideBySide(left, right) == pair.rgba) << stem << ": the replayed eyes differ from the submitted ones";
    }

    // Re-derived from the recorded hands: the same poses and drilling, bit for bit, and the same removal.
    curette::testing::Invocation derived = curette::testing::runCurette("replay " + session.string() + " --from-reports --no-render");
    ASSERT_EQ(derived.exitCode, 0) << derived.output;
    EXPECT_NE(derived.output.find("poses and drilling from reports: identical to the recorded ones"), std::string::npos) << derived.output;
    EXPECT_EQ(lineStartingWith(derived.output, "drilled "), drilled) << derived.output;

    // A hand recorded elsewhere than it was, or a trigger not pulled, re-derives to other poses or drilling.
    std::string text = curette::testing::readTextFile(session);
    const std::string frame2 = recorded[2].dump();
    struct Tamper {
        const char* what;
        std::function<void(nlohmann::ordered_json&)> change;
    };
    const Tamper tampers[] = {
        {"the right grip 1 mm off", [](nlohmann::ordered_json& f) { f["xr"]["hands"][1]["position_m"][0] = f["xr"]["hands"][1]["position_m"][0].get<double>() + 0.001; }},
        {"the trigger released", [](nlohmann::ordered_json& f) { f["xr"]["hands"][1]["trigger"] = 0.0; }},
        {"the thumbstick at rest", [](nlohmann::ordered_json& f) { f["xr"]["hands"][0]["thumbstick"] = {0.0, 0.0}; }},
    };
    for (const Tamper& t : tampers) {
        nlohmann::ordered_json changed = recorded[2];
        t.change(changed);
        std::string tampered = text;
        tampered.replace(tampered.find(frame2), frame2.size(), changed.dump());
        auto path = dir / "tampered.jsonl";
        std::ofstream(path) << tampered;
        curette::testing::Invocation r = curette::testing::runCurette("replay " + path.string() + " --from-reports --no-render");
        EXPECT_EQ(r.exitCode, 1) << t.what << ": " << r.output;
        EXPECT_NE(r.output.find("DIFFERENT"), std::string::npos) << t.what << ": " << r.output;
    }
}

// A recorded session's header and frames, as written.
struct RecordedSession {
    nlohmann::ordered_json header;
    std::vector<nlohmann::ordered_json> frames;
    std::vector<std::string> lines;   // the file's lines, header first
};
RecordedSession readRecorded(const std::filesystem::path& path) {
    RecordedSession r;
    std::ifstream in(path);
    for (std::string line; std::getline(in, line);) r.lines.push_back(line);
    if (r.lines.empty()) return r;
    r.header = nlohmann::ordered_json::parse(r.lines[0]);
    for (std::size_t i = 1; i < r.lines.size(); ++i) r.frames.push_back(nlohmann::ordered_json::parse(r.lines[i]));
    return r;
}

// `replay --from-reports --no-render` of the session's first `frames` frames (written to `path`).
curette::testing::Invocation replayPrefix(const RecordedSession& session, std::size_t frames, const std::filesystem::path& path) {
    std::ofstream out(path);
    for (std::size_t i = 0; i <= frames && i < session.lines.size(); ++i) out << session.lines[i] << "\n";
    out.close();
    return curette::testing::runCurette("replay " + path.string() + " --from-reports --no-render");
}

// Moving the whole volume by hand (session/xr_hands.h), Oculus Touch under validation: the left hand, its grip
// on the volume's centre, holds its volume button (Y), carries the scene 3.125 cm right and 6.25 cm towards the
// user and turns it half round about the vertical, and lets go; then the right hand, turned the same way, carries
// its burr through the ball, drilling, at the room positions that are the same places on the anatomy (so its
// motion in the room is mirrored). Against the same carve with the volume left on its table: the same removal
// and the same tool pose, bit for bit (every position is dyadic and the turn is exact, so the room-to-world sums
// are exact); the frames that moved the volume ran the ray cast alone (no CAO step: nothing moved in world
// space); every submitted eye pair is `render --xr-views --stereo` of its views with the recorded volume place;
// `replay --check` and `replay --from-reports` reproduce it bit for bit.
TEST(ViewXr, AVolumeMovedByHandCarriesTheSceneAndTheCarveIsUnchanged) {
    if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0) GTEST_SKIP() << "xvfb-run is not installed (package xvfb)";
    const nlohmann::json sceneChanges = nlohmann::json::parse(R"({"shading": "cao", "clip_meshes": [
        {"name": "sphere", "mesh": {"shape": "sphere", "radius_mm": 8}, "position_mm": [30, 30, 44]},
        {"name": "burr", "mesh": {"shape": "sphere", "radius_mm": 5}, "position_mm": [24, 34, 30]}]})");
    // The volume's centre on its table in the stage (x, z; render/model/tracked_view.h), the grip there, and
    // where the grip leaves it: t further, turned half round about the vertical.
    const glm::dvec3 table(0.0, 0.75, -0.5), t(0.03125, 0.0, 0.0625);   // z: kTableDistanceM; y: any height within 2x of the centre's (exact differences)
    const nlohmann::json identity = {0, 0, 0, 1}, halfTurn = {0, 1, 0, 0};   // [x, y, z, w]
    const int n = 7;
    auto script = [&](bool moved) {
        nlohmann::json s = poseScript();
        s["interaction_profile"] = "/interaction_profiles/oculus/touch_controller";
        nlohmann::json frames = nlohmann::json::array();
        for (int i = 0; i < n; ++i) {
            nlohmann::json f = s["frames"][0];
            const bool carried = moved && i >= 1;
            const glm::dvec3 left = table + (carried ? t : glm::dvec3(0.0));
            f["left"] = {{"grip", {{"position", {left.x, left.y, left.z}}, {"orientation", carried ? halfTurn : identity}}}, {"b", moved && i <= 2}};
            const int k = std::clamp(i - 3, 0, 2);   // the burr's step: grabbed at frame 3, drilling at 4 and 5
            glm::dvec3 right(0.09375 - k / 256.0, 1.0, -0.40625);
            // The same place on the anatomy once the volume turned half round about its centre and moved by t.
            if (moved) right = glm::dvec3(table.x + t.x - (right.x - table.x), right.y, table.z + t.z - (right.z - table.z));
            f["right"] = {{"grip", {{"position", {right.x, right.y, right.z}}, {"orientation", moved ? halfTurn : identity}}},
                          {"squeeze", i >= 3 && i <= 5 ? 1.0 : 0.0},
                          {"trigger", i == 4 || i == 5 ? 1.0 : 0.0}};
            frames.push_back(f);
        }
        s["frames"] = frames;
        return s;
    };
    auto dir = scratch("move-volume");
    auto scene = curette::testing::writeNoisyBallScene(dir, sceneChanges);
    XrRun xr = runViewXr(dir, script(true), scene, "", XrLaunch{.record = true});
    const std::filesystem::path& session = xr.session;
    const ShellRun& live = xr.shell;
    ASSERT_EQ(live.exitCode, 0) << live.output;
    expectValidationSilent(xr.validation);
    EXPECT_NE(live.output.find("xr session over: 7 frames rendered"), std::string::npos) << live.output;
    const std::string digest = curette::testing::removalDigest(live.output);
    ASSERT_FALSE(digest.empty()) << "the burr drilled nothing:\n" << live.output;

    // The same carve, the volume left on its table.
    auto stillDir = scratch("still-volume");
    auto stillScene = curette::testing::writeNoisyBallScene(stillDir, sceneChanges);
    XrRun still = runViewXr(stillDir, script(false), stillScene);
    ASSERT_EQ(still.shell.exitCode, 0) << still.shell.output;
    expectValidationSilent(still.validation);
    EXPECT_EQ(curette::testing::removalDigest(still.shell.output), digest) << "moving the volume changed the carve";
    EXPECT_EQ(lineStartingWith(live.output, "xr tool 1 "), lineStartingWith(still.shell.output, "xr tool 1 "));
    EXPECT_EQ(lineStartingWith(still.shell.output, "xr volume left at "), "xr volume left at 0.0000, 0.9320, -0.5000 m in the room, turned by [1.0000, 0.0000, 0.0000, 0.0000]");
    EXPECT_EQ(lineStartingWith(live.output, "xr volume left at "), "xr volume left at 0.0312, 0.9320, -0.4375 m in the room, turned by [0.0000, 0.0000, 1.0000, 0.0000]");

    // Frames 1 and 2 moved the volume alone: the ray cast, no CAO step (the data-space V_AO is unchanged).
    std::vector<std::string> passes = lines(live.output, "xr frame ");
    ASSERT_EQ(passes.size(), static_cast<std::size_t>(n)) << live.output;
    EXPECT_NE(passes[0].find("IV voxel clipping"), std::string::npos) << passes[0];
    EXPECT_EQ(passes[1], "1 passes: VI ray casting");
    EXPECT_EQ(passes[2], "2 passes: VI ray casting");
    EXPECT_NE(passes[4].find("V LAO recompute"), std::string::npos) << passes[4] << ": the drilling frame recomputes";

    // The recorded volume place: on the table, then moved by exactly t; each eye pair is render --xr-views of
    // its views with that place.
    RecordedSession recorded = readRecorded(session);
    ASSERT_EQ(recorded.frames.size(), static_cast<std::size_t>(n));
    const nlohmann::ordered_json& onTable = recorded.frames[0]["xr"]["anchor"];
    for (int i = 0; i < n; ++i) {
        const nlohmann::ordered_json& anchor = recorded.frames[static_cast<std::size_t>(i)]["xr"]["anchor"];
        const glm::dvec3 moved = i >= 1 ? t : glm::dvec3(0.0);
        for (glm::length_t a = 0; a < 3; ++a)
            EXPECT_EQ(anchor["volume_centre_m"][static_cast<std::size_t>(a)].get<double>(),
                      onTable["volume_centre_m"][static_cast<std::size_t>(a)].get<double>() + moved[a])
                << i;
        EXPECT_EQ(anchor["volume_turn"], nlohmann::ordered_json::parse(i >= 1 ? "[0.0, 0.0, 1.0, 0.0]" : "[1.0, 0.0, 0.0, 0.0]")) << i;
        char stem[32];
        std::snprintf(stem, sizeof stem, "frame_%06d", i);
        nlohmann::json views = nlohmann::json::parse(curette::testing::readTextFile(xr.eyes / (std::string(stem) + "_views.json")));
        const nlohmann::ordered_json& q = anchor["volume_turn"];   // [w, x, y, z] in a session, [x, y, z, w] in a views file
        views["volume"] = {{"centre_m", anchor["volume_centre_m"]}, {"turn", {q[1], q[2], q[3], q[0]}}};
        auto viewsPath = dir / (std::string(stem) + "_placed_views.json");
        std::ofstream(viewsPath) << views.dump(2);
        auto rendered = dir / (std::string(stem) + "_render.png");
        curette::testing::Invocation r = curette::testing::runCurette("render --scene " + scene.string() + " --xr-views " + viewsPath.string() +
                                                                      " --stereo side-by-side --out " + rendered.string());
        ASSERT_EQ(r.exitCode, 0) << r.output;
        curette::testing::Png left = readPng(xr.eyes / (std::string(stem) + "_left.png"));
        curette::testing::Png right = readPng(xr.eyes / (std::string(stem) + "_right.png"));
        curette::testing::Png pair = readPng(rendered);
        ASSERT_EQ(pair.width, left.width + right.width) << stem;
        EXPECT_TRUE(sideBySide(left, right) == pair.rgba) << stem << ": the submitted eyes differ from render --xr-views at the volume's place";
        if (i == 1) {
            curette::testing::Png before = readPng(xr.eyes / "frame_000000_left.png");
            EXPECT_NE(before.rgba, left.rgba) << "the volume moved, the eye did not see it";
        }
    }

    // Replayed headless (the recorded places) and re-derived from the hands (the places too), bit for bit.
    auto replayed = dir / "replay";
    curette::testing::Invocation replay = curette::testing::runCurette("replay " + session.string() + " --check --out " + replayed.string());
    ASSERT_EQ(replay.exitCode, 0) << replay.output;
    EXPECT_NE(replay.output.find("CAO == LAO on 7 of 7 checked frames"), std::string::npos) << replay.output;
    EXPECT_EQ(curette::testing::removalDigest(replay.output), digest) << replay.output;
    for (int i = 0; i < n; ++i) {
        char stem[32];
        std::snprintf(stem, sizeof stem, "frame_%06d", i);
        curette::testing::Png left = readPng(xr.eyes / (std::string(stem) + "_left.png"));
        curette::testing::Png right = readPng(xr.eyes / (std::string(stem) + "_right.png"));
        curette::testing::Png pair = readPng(replayed / (std::string(stem) + ".png"));
        ASSERT_EQ(pair.width, left.width + right.width) << stem;
        EXPECT_TRUE(sideBySide(left, right) == pair.rgba) << stem << ": the replayed eyes differ from the submitted ones";
    }
    curette::testing::Invocation derived = curette::testing::runCurette("replay " + session.string() + " --from-reports --no-render");
    ASSERT_EQ(derived.exitCode, 0) << derived.output;
    EXPECT_NE(derived.output.find("poses and drilling from reports: identical to the recorded ones"), std::string::npos) << derived.output;
    EXPECT_EQ(curette::testing::removalDigest(derived.output), digest) << derived.output;
    // The volume button up at the frame that carried it re-derives to another place.
    nlohmann::ordered_json changed = recorded.frames[1];
    changed["xr"]["hands"][0]["volume"] = false;
    std::string tampered = curette::testing::readTextFile(session);
    tampered.replace(tampered.find(recorded.lines[2]), recorded.lines[2].size(), changed.dump());
    auto tamperedPath = dir / "tampered.jsonl";
    std::ofstream(tamperedPath) << tampered;
    curette::testing::Invocation r = curette::testing::runCurette("replay " + tamperedPath.string() + " --from-reports --no-render");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("DIFFERENT"), std::string::npos) << r.output;
}

// Erase, undo and redo on the controllers of `profile` under validation: the right hand's burr drills a stroke
// with the trigger, erases part of it back with the erase control (`eraseStickY`: where the thumb is on the stick
// or trackpad as it clicks), then a flick left undoes the erase and a flick right redoes it. The session records
// each as the action layer applied it (drill, erase, undo, redo), and the removal after each step, re-derived
// from the recorded hands, is what it should be: the erase changes it, the undo brings back the drilled one, the
// redo the erased one.
void eraseUndoAndRedo(const std::string& name, const std::string& profile, double eraseStickY) {
    auto dir = scratch(name);
    auto scene = curette::testing::writeNoisyBallScene(dir, nlohmann::json::parse(R"({"shading": "phong", "clip_meshes": [
        {"name": "sphere", "mesh": {"shape": "sphere", "radius_mm": 8}, "position_mm": [30, 30, 44]},
        {"name": "burr", "mesh": {"shape": "sphere", "radius_mm": 5}, "position_mm": [24, 34, 30]}]})"));
    nlohmann::json script = poseScript();
    script["interaction_profile"] = profile;
    struct Step {
        int at;   // the burr's place: 0, 1, 2 steps of 4 mm
        double squeeze, trigger;
        bool erase;
        double stickX;
    };
    const Step steps[] = {
        {0, 0, 0, false, 0},  {0, 1, 0, false, 0}, {1, 1, 1, false, 0}, {2, 1, 1, false, 0},   // grab, drill 0 -> 2
        {2, 1, 0, false, 0},  {1, 1, 0, true, 0},  {1, 1, 0, false, 0},                         // erase 2 -> 1
        {1, 1, 0, false, -1}, {1, 1, 0, false, 0}, {1, 1, 0, false, 1},  {1, 1, 0, false, 0},   // undo, redo
    };
    const int n = static_cast<int>(std::size(steps));
    nlohmann::json frames = nlohmann::json::array();
    for (const Step& st : steps) {
        nlohmann::json f = script["frames"][0];
        f["right"] = {{"grip", {{"position", {0.09375 - st.at / 256.0, 1.0, -0.40625}}, {"orientation", {0, 0, 0, 1}}}},
                      {"squeeze", st.squeeze},
                      {"trigger", st.trigger},
                      {"thumbstick_click", st.erase},
                      {"thumbstick", {st.stickX, st.erase ? eraseStickY : 0.0}}};
        frames.push_back(f);
    }
    script["frames"] = frames;
    XrRun xr = runViewXr(dir, script, scene, "", XrLaunch{.record = true});
    const std::filesystem::path& session = xr.session;
    ASSERT_EQ(xr.shell.exitCode, 0) << xr.shell.output;
    expectValidationSilent(xr.validation);
    std::string log = curette::testing::readTextFile(xr.eyes / "runtime.log");
    EXPECT_NE(log.find("bindings suggested for /interaction_profiles/valve/index_controller: 14"), std::string::npos) << log;
    EXPECT_NE(log.find("bindings suggested for /interaction_profiles/htc/vive_controller: 12"), std::string::npos) << log;
    EXPECT_NE(log.find("bindings suggested for /interaction_profiles/khr/simple_controller: 6"), std::string::npos) << log;
    const std::string finalDigest = curette::testing::removalDigest(xr.shell.output);
    ASSERT_FALSE(finalDigest.empty()) << xr.shell.output;

    // What the action layer applied, frame by frame.
    RecordedSession recorded = readRecorded(session);
    ASSERT_EQ(recorded.frames.size(), static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
        const nlohmann::ordered_json& f = recorded.frames[static_cast<std::size_t>(i)];
        nlohmann::ordered_json drill = f.contains("drill") ? f["drill"] : nlohmann::ordered_json::array();
        nlohmann::ordered_json history = f.contains("drill_history") ? f["drill_history"] : nlohmann::ordered_json::array();
        const char* expectedDrill = i == 2 || i == 3 ? R"([{"mesh": 1, "erase": false}])" : i == 5 ? R"([{"mesh": 1, "erase": true}])" : "[]";
        const char* expectedHistory = i == 7 ? R"(["undo"])" : i == 9 ? R"(["redo"])" : "[]";
        EXPECT_EQ(drill, nlohmann::ordered_json::parse(expectedDrill)) << "frame " << i;
        EXPECT_EQ(history, nlohmann::ordered_json::parse(expectedHistory)) << "frame " << i;
        EXPECT_EQ(f["xr"]["hands"][1]["erase"].get<bool>(), i == 5) << "frame " << i;
        EXPECT_FALSE(f["xr"]["hands"][1]["volume"].get<bool>()) << "frame " << i;
    }

    // The removal after each step, re-derived from the recorded hands.
    auto digestAfter = [&](std::size_t count) {
        curette::testing::Invocation r = replayPrefix(recorded, count, dir / ("prefix-" + std::to_string(count) + ".jsonl"));
        EXPECT_EQ(r.exitCode, 0) << r.output;
        EXPECT_NE(r.output.find("identical to the recorded ones"), std::string::npos) << r.output;
        return curette::testing::removalDigest(r.output);
    };
    const std::string drilled = digestAfter(5), erased = digestAfter(7), undone = digestAfter(8), redone = digestAfter(static_cast<std::size_t>(n));
    ASSERT_FALSE(drilled.empty());
    EXPECT_NE(erased, drilled) << "the erase button restored nothing";
    EXPECT_EQ(undone, drilled) << "the flick left did not undo the erase";
    EXPECT_EQ(redone, erased) << "the flick right did not redo the erase";
    EXPECT_EQ(finalDigest, erased);
}

TEST(ViewXr, TheControllersEraseUndoAndRedoThroughTheActionLayer) {
    if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0) GTEST_SKIP() << "xvfb-run is not installed (package xvfb)";
    eraseUndoAndRedo("erase-undo", "/interaction_profiles/valve/index_controller", 0.0);   // the thumbstick's click
}

// The Vive has no spare button: its trackpad clicked in the lower third erases (xr/controller_actions.h).
TEST(ViewXr, TheViveErasesWithItsTrackpadClickedLow) {
    if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0) GTEST_SKIP() << "xvfb-run is not installed (package xvfb)";
    eraseUndoAndRedo("erase-vive", "/interaction_profiles/htc/vive_controller", -0.8);
}

// Elsewhere on the Vive's trackpad the click carries the volume, and the stick reads zero while it is clicked.
TEST(ViewXr, TheViveTrackpadClickedHighCarriesTheVolume) {
    if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0) GTEST_SKIP() << "xvfb-run is not installed (package xvfb)";
    auto dir = scratch("vive-volume");
    auto scene = curette::testing::writeNoisyBallScene(dir, nlohmann::json::parse(R"({"shading": "phong"})"));
    nlohmann::json script = poseScript();
    script["interaction_profile"] = "/interaction_profiles/htc/vive_controller";
    const double stickY[] = {0.0, 0.6, 0.1, -0.2};
    const bool click[] = {false, true, true, true};
    nlohmann::json frames = nlohmann::json::array();
    for (int i = 0; i < 4; ++i) {
        nlohmann::json f = script["frames"][0];
        f["right"] = {{"grip", {{"position", {0.1, 1.0, -0.4}}, {"orientation", {0, 0, 0, 1}}}},
                      {"thumbstick_click", click[i]},
                      {"thumbstick", {0.0, stickY[i]}}};
        frames.push_back(f);
    }
    script["frames"] = frames;
    XrRun xr = runViewXr(dir, script, scene, "", XrLaunch{.record = true});
    const std::filesystem::path& session = xr.session;
    ASSERT_EQ(xr.shell.exitCode, 0) << xr.shell.output;
    expectValidationSilent(xr.validation);
    RecordedSession recorded = readRecorded(session);
    ASSERT_EQ(recorded.frames.size(), 4u);
    for (std::size_t i = 0; i < 4; ++i) {
        const nlohmann::ordered_json& hand = recorded.frames[i]["xr"]["hands"][1];
        EXPECT_EQ(hand["volume"].get<bool>(), click[i]) << "frame " << i;
        EXPECT_FALSE(hand["erase"].get<bool>()) << "frame " << i;
        EXPECT_EQ(hand["thumbstick"][1].get<double>(), click[i] ? 0.0 : static_cast<double>(static_cast<float>(stickY[i]))) << "frame " << i;
    }
}

// Previews in the headset (--quality adaptive, viewer/xr_frame_loop.h), Index under validation: the right hand
// grabs its tool and carries it over the top of the ball, cutting it, for six frames, then holds still while the head sways by a
// millimetre (below the head's stillness bound). While the tool moves every frame submits a preview of both eyes
// (smaller than the exact eye: the projection view's imageRect, which the runtime reads back), the tool seen
// moving from one to the next; once still the exact frame follows, in slices, the held eyes submitted meanwhile
// (a frame every xrWaitFrame); the last submitted eyes are the exact frame of the views they were rendered from
// (`render --xr-views` of --save-views), whole size, in spite of the sway. The recording re-derives bit for bit.
TEST(ViewXr, PreviewsWhileATakenToolMovesThenTheExactFrameOnceStill) {
    if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0) GTEST_SKIP() << "xvfb-run is not installed (package xvfb)";
    auto dir = scratch("previews");
    auto scene = curette::testing::writeNoisyBallScene(dir, nlohmann::json::parse(R"({"shading": "cao", "clip_meshes": [
        {"name": "sphere", "mesh": {"shape": "sphere", "radius_mm": 8}, "position_mm": [30, 30, 44]},
        {"name": "burr", "mesh": {"shape": "sphere", "radius_mm": 9}, "position_mm": [20, 32, 58]}]})"));
    nlohmann::json script = poseScript();
    script["interaction_profile"] = "/interaction_profiles/valve/index_controller";
    const int moving = 6, still = 180;   // the still frames: the settle time (9 frames at 90 Hz) and the slices, with room for a loaded machine
    nlohmann::json frames = nlohmann::json::array();
    for (int i = 0; i < 2 + moving + still; ++i) {
        nlohmann::json f = script["frames"][0];
        const int at = std::clamp(i - 1, 0, moving);
        if (i >= 2 + moving) f["head"]["position"][1] = 1.03 + (i % 2 ? 0.001 : -0.001);   // sway, 2 mm in all
        f["right"] = {{"grip", {{"position", {0.1 - 0.004 * at, 1.0, -0.4}}, {"orientation", {0, 0, 0, 1}}}}, {"squeeze", i >= 1 ? 1.0 : 0.0}};
        frames.push_back(f);
    }
    script["frames"] = frames;
    auto views = dir / "held-views.json";
    XrRun xr = runViewXr(dir, script, scene, " --quality adaptive --save-views " + views.string(), XrLaunch{.record = true});
    const std::filesystem::path& session = xr.session;
    ASSERT_EQ(xr.shell.exitCode, 0) << xr.shell.output;
    expectValidationSilent(xr.validation);
    EXPECT_NE(xr.shell.output.find("xr quality: adaptive"), std::string::npos) << xr.shell.output;
    EXPECT_FALSE(lineStartingWith(xr.shell.output, "xr left eye: ").empty()) << xr.shell.output;

    auto eye = [&](int frame, const char* side) {
        char name[48];
        std::snprintf(name, sizeof name, "frame_%06d_%s.png", frame, side);
        return readPng(xr.eyes / name);
    };
    // Every frame was submitted (a layer at every xrEndFrame), so the runtime wrote every one.
    for (int i = 0; i < 2 + moving + still; ++i) ASSERT_FALSE(eye(i, "left").rgba.empty()) << "frame " << i;
    // The exact eye is 31 x 35 (TheSessionRuns...); each moving frame's eyes are a preview, smaller, and the
    // tool moved between them.
    std::vector<std::uint8_t> before;
    for (int i = 2; i < 2 + moving; ++i) {
        curette::testing::Png left = eye(i, "left"), right = eye(i, "right");
        EXPECT_LT(left.width, 31) << "frame " << i << ": the tool moved, but the eye submitted is not a preview";
        EXPECT_LT(right.width, 31) << "frame " << i;
        EXPECT_LT(left.height, 35) << "frame " << i;
        if (!before.empty() && before.size() == left.rgba.size()) {
            EXPECT_NE(left.rgba, before) << "frame " << i << ": the preview did not follow the tool";
        }
        before = left.rgba;
    }
    // The last submitted eyes: exact, whole size, `render --xr-views` of the views they were rendered from.
    const int last = 1 + moving + still;
    curette::testing::Png left = eye(last, "left"), right = eye(last, "right");
    ASSERT_EQ(left.width, 31);
    ASSERT_EQ(left.height, 35);
    // The scene with the burr where the hand left it (the recorded pose, 17 digits: the same double).
    RecordedSession recorded = readRecorded(session);
    ASSERT_FALSE(recorded.frames.empty());
    nlohmann::json moved = nlohmann::json::parse(curette::testing::readTextFile(scene));
    moved["clip_meshes"][1]["position_mm"] = recorded.frames.back()["meshes"][1]["position_mm"];
    ASSERT_NE(moved["clip_meshes"][1]["position_mm"][0].get<double>(), 20.0) << "the hand did not carry the burr";
    auto movedScene = dir / "moved.json";
    std::ofstream(movedScene) << moved.dump(2);
    auto rendered = dir / "exact.png";
    curette::testing::Invocation r = curette::testing::runCurette("render --scene " + movedScene.string() + " --xr-views " + views.string() +
                                                                  " --stereo side-by-side --out " + rendered.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    curette::testing::Png pair = readPng(rendered);
    ASSERT_EQ(pair.width, left.width + right.width);
    EXPECT_TRUE(sideBySide(left, right) == pair.rgba) << "the last submitted eyes are not the exact frame";
    // Held eyes went out while the exact frame was sliced, or once it was done.
    EXPECT_NE(xr.shell.output.find("xr held eyes submitted again on "), std::string::npos) << xr.shell.output;

    // What the session recorded re-derives bit for bit (previews record nothing of their own).
    curette::testing::Invocation derived = curette::testing::runCurette("replay " + session.string() + " --from-reports --no-render");
    ASSERT_EQ(derived.exitCode, 0) << derived.output;
    EXPECT_NE(derived.output.find("identical to the recorded ones"), std::string::npos) << derived.output;
}

// Two hands scale the volume (session version 8, RoomAnchor::heldByTwo), Index under validation: both hands hold
// their volume buttons (B) 0.25 m apart, draw apart to 0.375 m about a fixed midpoint, and let go. The recorded
// anchor's scale is the ratio of the hands' distances, 1.5 (every position is dyadic: exact), the midpoint's
// place on the anatomy stays, and the volume's centre moved away from it by that ratio; `replay --from-reports`
// re-derives the anchor bit for bit and `replay --check` renders every frame with the recorded scale (its eyes
// the submitted ones, CAO == LAO).
TEST(ViewXr, TwoHandsScaleTheVolumeAboutTheirMidpoint) {
    if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0) GTEST_SKIP() << "xvfb-run is not installed (package xvfb)";
    auto dir = scratch("two-hands");
    auto scene = curette::testing::writeNoisyBallScene(dir, nlohmann::json::parse(R"({"shading": "cao", "clip_meshes": [
        {"name": "sphere", "mesh": {"shape": "sphere", "radius_mm": 8}, "position_mm": [30, 30, 44]}]})"));
    nlohmann::json script = poseScript();
    script["interaction_profile"] = "/interaction_profiles/valve/index_controller";
    const double half[] = {0.125, 0.125, 0.15625, 0.1875, 0.1875};
    const bool held[] = {false, true, true, true, false};
    const int n = 5;
    nlohmann::json frames = nlohmann::json::array();
    for (int i = 0; i < n; ++i) {
        nlohmann::json f = script["frames"][0];
        f["left"] = {{"grip", {{"position", {-half[i], 1.0, -0.5}}, {"orientation", {0, 0, 0, 1}}}}, {"b", held[i]}};
        f["right"] = {{"grip", {{"position", {half[i], 1.0, -0.5}}, {"orientation", {0, 0, 0, 1}}}}, {"b", held[i]}};
        frames.push_back(f);
    }
    script["frames"] = frames;
    XrRun xr = runViewXr(dir, script, scene, "", XrLaunch{.record = true});
    const std::filesystem::path& session = xr.session;
    ASSERT_EQ(xr.shell.exitCode, 0) << xr.shell.output;
    expectValidationSilent(xr.validation);
    RecordedSession recorded = readRecorded(session);
    ASSERT_EQ(recorded.frames.size(), static_cast<std::size_t>(n));
    EXPECT_EQ(recorded.header["version"], 8);
    const double expectedScale[] = {1.0, 1.0, 1.25, 1.5, 1.5};
    const nlohmann::ordered_json& table = recorded.frames[0]["xr"]["anchor"];
    for (int i = 0; i < n; ++i) {
        const nlohmann::ordered_json& a = recorded.frames[static_cast<std::size_t>(i)]["xr"]["anchor"];
        EXPECT_EQ(a["volume_scale"].get<double>(), expectedScale[i]) << "frame " << i;
        // The hands' midpoint (0, 1, -0.5) is fixed: the centre's offset from it grows by the scale.
        for (int k = 0; k < 3; ++k) {
            const double mid = k == 1 ? 1.0 : k == 2 ? -0.5 : 0.0;
            EXPECT_NEAR(a["volume_centre_m"][k].get<double>() - mid, expectedScale[i] * (table["volume_centre_m"][k].get<double>() - mid), 1e-12)
                << "frame " << i << " axis " << k;
        }
        EXPECT_EQ(a["volume_turn"], table["volume_turn"]) << "frame " << i << ": hands drawn apart on one line turn nothing";
    }
    EXPECT_NE(xr.shell.output.find(", scaled by 1.5000"), std::string::npos) << xr.shell.output;

    curette::testing::Invocation derived = curette::testing::runCurette("replay " + session.string() + " --from-reports --no-render");
    ASSERT_EQ(derived.exitCode, 0) << derived.output;
    EXPECT_NE(derived.output.find("identical to the recorded ones"), std::string::npos) << derived.output;
    auto replayed = dir / "replay";
    curette::testing::Invocation replay = curette::testing::runCurette("replay " + session.string() + " --check --out " + replayed.string());
    ASSERT_EQ(replay.exitCode, 0) << replay.output;
    EXPECT_NE(replay.output.find("CAO == LAO on 5 of 5 checked frames"), std::string::npos) << replay.output;
    std::vector<std::uint8_t> first;
    for (int frame = 0; frame < n; ++frame) {
        char stem[32];
        std::snprintf(stem, sizeof stem, "frame_%06d", frame);
        curette::testing::Png left = readPng(xr.eyes / (std::string(stem) + "_left.png"));
        curette::testing::Png right = readPng(xr.eyes / (std::string(stem) + "_right.png"));
        curette::testing::Png pair = readPng(replayed / (std::string(stem) + ".png"));
        ASSERT_EQ(pair.width, left.width + right.width) << stem;
        EXPECT_TRUE(sideBySide(left, right) == pair.rgba) << stem << ": the replayed eyes differ from the submitted ones";
        if (frame == 0) first = left.rgba;
        if (frame == n - 1) {
            EXPECT_NE(left.rgba, first) << "the volume grew, the eye did not change";
        }
    }
}

// Headless through XR_MNDX_egl_enable: with the test runtime offering the extension (its EGL mode, as Monado
// does), `view --xr --headless` binds a headless EGL context (no X server: no xvfb-run), the runtime sees an EGL
// binding, and every submitted eye pair is `render --xr-views --stereo` of its views. Without the extension
// offered, --headless refuses and names it. The core validation layer is left out here: Debian's build
// (openxr-layer-corevalidation 1.0.20) is compiled without XR_USE_PLATFORM_EGL, knows no
// XrGraphicsBindingEGLMNDX and fails xrCreateSession on it ("VUID-XrSessionCreateInfo-next-next").
TEST(ViewXr, HeadlessThroughEglWhereTheRuntimeOffersIt) {
    auto dir = scratch("egl");
    auto scene = curette::testing::writeNoisyBallScene(dir, nlohmann::json::parse(R"({"shading": "cao", "clip_meshes": [
        {"name": "sphere", "mesh": {"shape": "sphere", "radius_mm": 12}, "position_mm": [32, 44, 40]}]})"));
    XrRun xr = runViewXr(dir, poseScript(), scene, "", XrLaunch{true, true});
    const ShellRun& run = xr.shell;
    const std::filesystem::path& out = xr.eyes;
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_NE(run.output.find("xr session over: 3 frames rendered"), std::string::npos) << run.output;
    std::string log = curette::testing::readTextFile(out / "runtime.log");
    EXPECT_NE(log.find("session binding: EGL"), std::string::npos) << log;
    EXPECT_EQ(log.find("error"), std::string::npos) << log;
    for (int frame = 0; frame < 3; ++frame) {
        char stem[32];
        std::snprintf(stem, sizeof stem, "frame_%06d", frame);
        auto rendered = dir / (std::string(stem) + "_render.png");
        curette::testing::Invocation r = curette::testing::runCurette("render --scene " + scene.string() + " --xr-views " +
                                                                      (out / (std::string(stem) + "_views.json")).string() +
                                                                      " --stereo side-by-side --out " + rendered.string());
        ASSERT_EQ(r.exitCode, 0) << r.output;
        curette::testing::Png left = readPng(out / (std::string(stem) + "_left.png"));
        curette::testing::Png right = readPng(out / (std::string(stem) + "_right.png"));
        curette::testing::Png pair = readPng(rendered);
        ASSERT_EQ(pair.width, left.width + right.width) << stem;
        EXPECT_TRUE(sideBySide(left, right) == pair.rgba) << stem << ": the submitted eyes differ from render --xr-views";
        EXPECT_NE(std::count(left.rgba.begin(), left.rgba.end(), left.rgba[0]), static_cast<std::ptrdiff_t>(left.rgba.size())) << stem;
    }
    ShellRun refused = runViewXr(dir, poseScript(), scene, "", XrLaunch{true, false}).shell;
    EXPECT_NE(refused.exitCode, 0) << refused.output;
    EXPECT_NE(refused.output.find("XR_MNDX_egl_enable"), std::string::npos) << refused.output;
}

// Without XR_RUNTIME_JSON naming it, the test runtime is not what `view --xr` finds: it is registered nowhere
// (no active_runtime.json points at it), so the loader reports whatever the machine has, or no runtime.
TEST(ViewXr, TheTestRuntimeIsNotFoundByDefault) {
    if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0) GTEST_SKIP() << "xvfb-run is not installed (package xvfb)";
    auto dir = scratch("default");
    auto scene = curette::testing::writeNoisyBallScene(dir, nlohmann::json::object());
    ShellRun run = runShell("xvfb-run -a -s '-screen 0 640x480x24' env -u XR_RUNTIME_JSON CURETTE_XR_TEST_SCRIPT=/nonexistent XR_LOADER_DEBUG=info " +
                       std::string(CURETTE_BINARY) + " view --xr --scene " + scene.string());
    EXPECT_EQ(run.output.find("curette_xr_test_runtime"), std::string::npos) << run.output;
    EXPECT_EQ(run.output.find("curette XR test runtime"), std::string::npos) << run.output;
    EXPECT_EQ(run.output.find("scripted, no headset"), std::string::npos) << run.output;
}

}  // namespace
}  // namespace curette
