// curette bench xr: a head-mounted display session's frame time. Against the active OpenXR runtime, or with
// --test-runtime curette's scripted one (tests/xr_runtime; XR_RUNTIME_JSON is set to the built manifest, so a
// test tool runs only when asked; each run is a new OpenXR instance playing the script again): a head looking down at the volume on its table while both hands hold the
// scene's tools and move them every frame (and, with --drill, the right trigger drills), at the runtime's
// recommended eye size. Each run starts a fresh renderer (so its first frame runs step I) and goes through
// tools/xr_loop.h as `view --xr` does. Per run: the first frame and its step I; then per frame the time of each
// eye (render, read back, submit; the left eye updates V_AO, CAO steps II-V, once for both eyes), the CAO
// update's GPU time and the ray cast's; and next to them, from the run's recording followed again in the same
// renderer, whether CAO == LAO (V_AO and both eyes, bit for bit) on every frame. A second table gives the
// median and the range over the runs.
#include "tools/bench/bench_xr.h"

#include "base/atomic_file.h"
#include "base/error.h"
#include "render/renderer.h"
#include "render/stereo_render.h"
#include "session/interaction.h"
#include "session/loaded_scene.h"
#include "session/session.h"
#include "session/session_step.h"
#include "tools/bench/report.h"
#include "session/xr_hands.h"
#include "tools/xr_loop.h"

#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <unistd.h>

namespace curette::bench {

namespace {

// The test runtime's pose script: `frames` frames of a head 0.45 m from the table looking down at it and
// swaying, both hands squeezing from the first frame and moving 1 mm a frame (90 mm/s at 90 Hz), turning
// 0.5 degrees a frame; with `drill` the right trigger is held.
nlohmann::json benchScript(int frames, glm::ivec2 size, bool drill) {
    nlohmann::json list = nlohmann::json::array();
    const double pitch = -0.48;
    for (int i = 0; i < frames; ++i) {
        glm::dquat head = glm::angleAxis(pitch, glm::dvec3(1, 0, 0));
        const double a = 0.05 * i;
        glm::dquat turn = glm::angleAxis(glm::radians(0.5) * i, glm::normalize(glm::dvec3(0.2, 1.0, 0.3)));
        auto hand = [&](double side, double trigger) {
            nlohmann::json h = {{"grip",
                                 {{"position", {side * (0.08 + 0.01 * std::cos(a)), 1.0 + 0.01 * std::sin(a), -0.42 + 0.001 * i * side}},
                                  {"orientation", {turn.x, turn.y, turn.z, turn.w}}}},
                                {"squeeze", 1.0},
                                {"trigger", trigger}};
            return h;
        };
        list.push_back({{"head", {{"position", {0.0005 * i, 1.2, -0.05}}, {"orientation", {head.x, head.y, head.z, head.w}}}},
                        {"left", hand(-1.0, 0.0)},
                        {"right", hand(1.0, drill ? 1.0 : 0.0)}});
    }
    return {{"recommended_size", {size.x, size.y}},
            {"ipd_m", 0.064},
            {"fov_rad", {{"left", {-0.85, 0.75, 0.80, -0.85}}, {"right", {-0.75, 0.85, 0.80, -0.85}}}},
            {"interaction_profile", "/interaction_profiles/valve/index_controller"},
            {"frames", list}};
}

// CAO's update of a frame (steps II-V; the left eye's, which both eyes read).
double caoMs(const FrameTimings& t) { return t.ms(Pass::ClipMaps) + t.ms(Pass::VoxelClipping) + t.ms(Pass::LaoRecompute); }

struct RunFigures {
    glm::ivec2 eye{0};
    int frames = 0;
    double firstFrameMs = 0, stepIMs = 0;
    double leftMs = 0, rightMs = 0, caoMs = 0, rayCastMs = 0;   // medians over the frames after the first
    int checked = 0, equal = 0;
};

}  // namespace

int benchXr(const CommandLine& cl) {
    const std::filesystem::path scenePath = cl.valueOr("scene", "assets/scenes/head-carved.json");
    const bool testRuntime = cl.flag("test-runtime");
    if (cl.value("size") && !testRuntime) throw InputError("<command line>", "--size", "together with --test-runtime (a headset recommends its own size)");
    const glm::ivec2 size = CommandLine::parseSize("size", cl.valueOr("size", "160x144"));
    const int frames = CommandLine::parseInt("frames", cl.valueOr("frames", "6"), 2, 100000);
    const int runs = CommandLine::parseInt("runs", cl.valueOr("runs", "3"), 1, 1000);
    const bool drill = cl.flag("drill");
    const std::string jsonPath = cl.valueOr("json", "bench-xr.json");

    const std::filesystem::path work = std::filesystem::temp_directory_path() / ("curette-bench-xr-" + std::to_string(getpid()));
    std::filesystem::create_directories(work);
    if (testRuntime) {
        const std::filesystem::path manifest = CURETTE_XR_TEST_RUNTIME_JSON;
        if (!std::filesystem::exists(manifest))
            throw SystemError(manifest.string() + ": no test runtime here (build the target curette_xr_test_runtime)");
        writeFileAtomically(work / "script.json", benchScript(frames, size, drill).dump() + "\n");
        setenv("XR_RUNTIME_JSON", manifest.c_str(), 1);
        setenv("CURETTE_XR_TEST_SCRIPT", (work / "script.json").c_str(), 1);
        setenv("CURETTE_XR_TEST_OUT", (work / "runtime").c_str(), 1);
    }

    LoadedScene loaded = loadSceneWithVolume(scenePath);
    const VolumeData& v = loaded.volume;
    std::printf("curette bench xr: %s (%dx%dx%d), %s shading, %d runs of %d frames, %s\n", scenePath.c_str(), v.dims.x, v.dims.y, v.dims.z,
                shadingModeName(loaded.scene.shading), runs, frames, testRuntime ? "the test runtime (scripted)" : "the active OpenXR runtime");
    std::string runtimeName, systemName, rendererName;
    std::vector<RunFigures> figures;
    // One window for every run: closing the last would reset an X server such as xvfb-run's.
    auto window = gl::createWindowContext("curette bench xr", glm::ivec2(320, 240));
    rendererName = window->info().renderer;
    for (int run = 0; run < runs; ++run) {
        Renderer renderer(*window, loaded.volume, loaded.scene.transferFunction);
        configureRenderer(loaded, renderer);
        SessionStep step(InteractionState::fromScene(loaded.scene), initialFrame(loaded.scene, renderer.geometry()));
        step.attachRemoval(loaded.volume.dims, loaded.volume.indexToWorld);
        XrLoopOptions options;
        options.record = work / ("run-" + std::to_string(run) + ".jsonl");
        options.sceneInSession = std::filesystem::absolute(scenePath).string();
        options.printStates = false;
        if (!testRuntime) options.frameLimit = frames;
        XrLoopResult result = runXrLoop(*window, window.get(), renderer, step, loaded, options);
        runtimeName = result.runtime;
        systemName = result.system;
        if (result.rendered.size() < 2) throw SystemError("bench xr: the runtime let " + std::to_string(result.rendered.size()) + " frames render (2 or more needed)");

        RunFigures f;
        f.eye = result.recommendedSize[0];
        f.frames = static_cast<int>(result.rendered.size());
        const XrFrameTiming& first = result.rendered.front();
        f.firstFrameMs = first.eyeMs[0] + first.eyeMs[1];
        f.stepIMs = first.firstEye.ms(Pass::LaoPrecompute);
        std::vector<double> left, right, cao, cast;
        for (std::size_t i = 1; i < result.rendered.size(); ++i) {
            const XrFrameTiming& t = result.rendered[i];
            left.push_back(t.eyeMs[0]);
            right.push_back(t.eyeMs[1]);
            cao.push_back(caoMs(t.firstEye));
            cast.push_back(t.firstEye.ms(Pass::RayCast));
        }
        f.leftMs = median(left);
        f.rightMs = median(right);
        f.caoMs = median(cao);
        f.rayCastMs = median(cast);

        // CAO == LAO on every rendered frame: the recording followed again, in the same renderer, untimed.
        Session session = readSession(*options.record, false);
        SessionStep again(InteractionState::fromSessionStart(session.header, loaded.scene, scenePath.parent_path(), options.record->string()),
                          initialFrame(loaded.scene, renderer.geometry()));
        again.attachRemoval(loaded.volume.dims, loaded.volume.indexToWorld);
        for (std::size_t n = 0; n < session.frames.size(); ++n) {
            const SessionFrame& sf = session.frames[n];
            again.follow(sf, scenePath.parent_path(), options.record->string() + " line " + std::to_string(n + 2));
            if (!sf.xr || !sf.xr->views || !usesAmbientOcclusion(sf.shading)) continue;
            again.syncTo(renderer, loaded.tracts);
            std::array<TrackedEye, 2> eyes = xrEyes(again.frame(), *sf.xr->views, recordedAnchor(result.anchor, *sf.xr), result.recommendedSize);
            std::array<Image, 2> images{renderTrackedEye(renderer, eyes[0]), renderTrackedEye(renderer, eyes[1])};
            ++f.checked;
            if (xrCaoEqualsLao(renderer, eyes, images)) ++f.equal;
        }
        figures.push_back(f);
        std::printf("run %d: %d frames, eyes %dx%d, first frame %.0f ms, then %.1f + %.1f ms a frame, CAO == LAO on %d of %d\n", run + 1, f.frames,
                    f.eye.x, f.eye.y, f.firstFrameMs, f.leftMs, f.rightMs, f.equal, f.checked);
        std::fflush(stdout);
    }
    std::error_code ec;
    std::filesystem::remove_all(work, ec);

    auto check = [](const RunFigures& f) { return f.checked ? std::to_string(f.equal) + " of " + std::to_string(f.checked) : std::string("-"); };
    Table perRun("A: per run (eye times are wall ms: render, read back, submit; medians over the frames after the first; CAO and ray cast: GPU ms)",
                 {"run", "eye size", "frames", "first frame ms", "step I ms", "left eye ms", "right eye ms", "CAO II-V ms/frame", "ray cast ms (left)",
                  "CAO == LAO frames"});
    for (std::size_t r = 0; r < figures.size(); ++r) {
        const RunFigures& f = figures[r];
        perRun.add({static_cast<int>(r + 1), std::to_string(f.eye.x) + "x" + std::to_string(f.eye.y), f.frames, f.firstFrameMs, f.stepIMs, f.leftMs,
                    f.rightMs, f.caoMs, f.rayCastMs, check(f)});
    }
    perRun.print();
    Table overRuns("B: over the runs (median, smallest, largest)", {"figure", "median", "min", "max", "CAO == LAO frames (all runs)"});
    int checked = 0, equal = 0;
    for (const RunFigures& f : figures) checked += f.checked, equal += f.equal;
    const std::string allChecked = checked ? std::to_string(equal) + " of " + std::to_string(checked) : std::string("-");
    auto row = [&](const char* name, double RunFigures::*field) {
        std::vector<double> values;
        for (const RunFigures& f : figures) values.push_back(f.*field);
        overRuns.add({name, median(values), *std::min_element(values.begin(), values.end()), *std::max_element(values.begin(), values.end()), allChecked});
    };
    row("left eye ms", &RunFigures::leftMs);
    row("right eye ms", &RunFigures::rightMs);
    row("CAO II-V ms/frame (shared)", &RunFigures::caoMs);
    row("ray cast ms (left eye)", &RunFigures::rayCastMs);
    row("first frame ms (both eyes)", &RunFigures::firstFrameMs);
    row("step I ms", &RunFigures::stepIMs);
    overRuns.print();
    std::printf("runtime: %s; system: %s; renderer: %s\n", runtimeName.c_str(), systemName.c_str(), rendererName.c_str());
    writeJson(jsonPath, {{"bench", "xr"},
                         {"scene", scenePath.string()},
                         {"volume", loaded.scene.volumePath.string()},
                         {"runtime", runtimeName},
                         {"system", systemName},
                         {"test_runtime", testRuntime},
                         {"drill", drill},
                         {"runs", runs},
                         {"frames", frames},
                         {"renderer", rendererName},
                         {"tables", {perRun.toJson(), overRuns.toJson()}}});
    return equal == checked ? 0 : 1;
}

}  // namespace curette::bench
