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

// The environment of a run against the test runtime with the core validation layer writing to `validation`.
std::string xrEnvironment(const std::filesystem::path& script, const std::filesystem::path& out, const std::filesystem::path& validation) {
    return "env XR_RUNTIME_JSON=" + std::string(CURETTE_XR_TEST_RUNTIME_JSON) + " CURETTE_XR_TEST_SCRIPT=" + script.string() +
           " CURETTE_XR_TEST_OUT=" + out.string() + " XR_ENABLE_API_LAYERS=XR_APILAYER_LUNARG_core_validation" +
           " XR_CORE_VALIDATION_EXPORT_TYPE=text XR_CORE_VALIDATION_FILE_NAME=" + validation.string() + " XR_LOADER_DEBUG=info";
}

// `view --xr` of `scene` (with `arguments`) under Xvfb against the test runtime playing `script` (written to
// dir/script.json), the core validation layer on: the run, the runtime's folder (eyes, runtime.log) and the
// layer's report file.
struct XrRun {
    ShellRun shell;
    std::filesystem::path eyes, validation;
};
XrRun runViewXr(const std::filesystem::path& dir, const nlohmann::json& script, const std::filesystem::path& scene, const std::string& arguments = "") {
    auto scriptPath = dir / "script.json";
    std::ofstream(scriptPath) << script.dump(2);
    XrRun run{{}, dir / "eyes", dir / "validation.txt"};
    run.shell = runShell("xvfb-run -a -s '-screen 0 640x480x24' " + xrEnvironment(scriptPath, run.eyes, run.validation) + " " + CURETTE_BINARY +
                         " view --xr --scene " + scene.string() + arguments);
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
    EXPECT_NE(log.find("bindings suggested for /interaction_profiles/valve/index_controller: 10"), std::string::npos) << log;
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
    auto session = dir / "session.jsonl";
    XrRun xr = runViewXr(dir, script, scene, " --record " + session.string());
    const ShellRun& live = xr.shell;
    const std::filesystem::path& out = xr.eyes;
    ASSERT_EQ(live.exitCode, 0) << live.output;
    expectValidationSilent(xr.validation);
    std::string log = curette::testing::readTextFile(out / "runtime.log");
    // The trigger is bound in every profile that has one: not the simple controller (its one button grabs).
    EXPECT_NE(log.find("bindings suggested for /interaction_profiles/oculus/touch_controller: 10"), std::string::npos) << log;
    EXPECT_NE(log.find("bindings suggested for /interaction_profiles/htc/vive_controller: 10"), std::string::npos) << log;
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
