// `curette view --xr` without a headset: the real binary under Xvfb, the real Khronos loader, the Khronos core
// validation layer, and curette's test runtime (tests/xr_runtime) playing a scripted head, found only through
// XR_RUNTIME_JSON. The session walks through its states to EXITING, the layer reports nothing, and every eye
// image the runtime read back from the swapchains is, pixel for pixel, what `render --xr-views --stereo
// side-by-side` renders headless from the views the runtime located for that frame.
#include "tests/tools/run_curette.h"
#include "tests/tools/tool_test_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
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
    auto script = dir / "script.json";
    std::ofstream(script) << poseScript().dump(2);
    auto out = dir / "eyes";
    auto validation = dir / "validation.txt";
    ShellRun run = runShell("xvfb-run -a -s '-screen 0 640x480x24' " + xrEnvironment(script, out, validation) + " " + CURETTE_BINARY +
                       " view --xr --scene " + scene.string());
    ASSERT_EQ(run.exitCode, 0) << run.output;

    // The loader enabled the validation layer, and the layer found nothing to say.
    EXPECT_NE(run.output.find("XR_APILAYER_LUNARG_core_validation"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("Core Validation output type: text"), std::string::npos) << run.output;
    std::string report = curette::testing::readTextFile(validation);
    EXPECT_EQ(report.find("VUID"), std::string::npos) << report;
    EXPECT_EQ(report.find("[VALID_"), std::string::npos) << report;

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
    auto scriptPath = dir / "script.json";
    std::ofstream(scriptPath) << script.dump(2);
    auto out = dir / "eyes";
    auto validation = dir / "validation.txt";
    ShellRun run = runShell("xvfb-run -a -s '-screen 0 640x480x24' " + xrEnvironment(scriptPath, out, validation) + " " + CURETTE_BINARY +
                            " view --xr --scene " + scene.string());
    ASSERT_EQ(run.exitCode, 0) << run.output;
    std::string report = curette::testing::readTextFile(validation);
    EXPECT_EQ(report.find("VUID"), std::string::npos) << report;
    EXPECT_EQ(report.find("[VALID_"), std::string::npos) << report;
    std::string log = curette::testing::readTextFile(out / "runtime.log");
    EXPECT_NE(log.find("bindings suggested for /interaction_profiles/valve/index_controller: 8"), std::string::npos) << log;
    EXPECT_NE(run.output.find("xr session over: 5 frames rendered"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("xr tool 0 \"sphere\" left at 30.000, 30.000, 44.000 mm"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("xr tool 1 \"box\" left at -28.000, 40.000, 24.000 mm"), std::string::npos) << run.output;
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
