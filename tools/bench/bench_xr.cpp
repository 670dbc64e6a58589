// curette bench xr: a head-mounted display session's frame time. Against the active OpenXR runtime, or with
// --test-runtime curette's scripted one (tests/xr_runtime; XR_RUNTIME_JSON is set to the built manifest, so a
// test tool runs only when asked; each run is a new OpenXR instance playing the script again): a head looking down at the volume on its table while both hands hold the
// scene's tools and move them every frame (and, with --drill, the right trigger drills), at the runtime's
// recommended eye size. Each run starts a fresh renderer (so its first frame runs step I) and goes through
// tools/xr_loop.h as `view --xr` does. Per run: the first frame and its step I; then per frame the time of each
// eye (render, read back, submit; the left eye updates V_AO, CAO steps II-V, once for both eyes), the CAO
// update's GPU time and the ray cast's; and next to them, from the run's recording followed again in the same
// renderer, whether CAO == LAO (V_AO and both eyes, bit for bit) on every frame. A second table gives the
// median and the range over the runs. --quality adaptive (a software renderer's default, viewer/xr_frame_loop.h):
// the moving frames are previews, then the script holds hands and head still until the exact frame (in
// slices) is submitted; per run the preview time per eye and the preview rate while moving, the exact frame's
// time per eye (its slices summed) and its CAO update, and the wait from the last motion to the exact frame
// (wall time: the test runtime's display clock advances one period a frame whatever the frame took). Step I is
// run before the session then (the exact quality's first frame times it).
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
// 0.5 degrees a frame; with `drill` the right trigger is held. Then `stillFrames` frames of the last poses held
// (the trigger released).
nlohmann::json benchScript(int frames, glm::ivec2 size, bool drill, int stillFrames = 0) {
    nlohmann::json list = nlohmann::json::array();
    const double pitch = -0.48;
    for (int n = 0; n < frames + stillFrames; ++n) {
        const int i = std::min(n, frames - 1);
        const bool drilling = drill && n < frames;
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
                        {"right", hand(1.0, drilling ? 1.0 : 0.0)}});
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
    // Adaptive quality: previews while moving (the frames after the first), the exact frame once still.
    double previewLeftMs = 0, previewRightMs = 0, previewFps = 0;
    double exactLeftMs = 0, exactRightMs = 0, exactCaoMs = 0, settleToExactS = 0;
    int exactFrames = 0;   // XR frames from the exact frame's first slice to its submission
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
    std::optional<ViewQuality> quality;
    if (auto q = cl.value("quality")) {
        quality = parseViewQuality(*q);
        if (!quality) throw InputError("<command line>", "--quality", "exact or adaptive", "\"" + *q + "\"");
    }

    const std::filesystem::path work = std::filesystem::temp_directory_path() / ("curette-bench-xr-" + std::to_string(getpid()));
    std::filesystem::create_directories(work);
    if (testRuntime) {
        const std::filesystem::path manifest = CURETTE_XR_TEST_RUNTIME_JSON;
        if (!std::filesystem::exists(manifest))
            throw SystemError(manifest.string() + ": no test runtime here (build the target curette_xr_test_runtime)");
        // Adaptive: still frames enough for the exact frame in slices (the loop ends the session once it is in).
        const bool adaptiveScript = quality.value_or(ViewQuality::Adaptive) == ViewQuality::Adaptive;
        writeFileAtomically(work / "script.json", benchScript(frames, size, drill, adaptiveScript ? 20000 : 0).dump() + "\n");
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
    const ViewQuality loopQuality = quality.value_or(testRuntime ? defaultViewQuality(window->info().softwareRenderer) : ViewQuality::Exact);
    const bool adaptive = loopQuality == ViewQuality::Adaptive;
    if (adaptive && !testRuntime) throw InputError("<command line>", "--quality", "exact without --test-runtime (a headset's poses are not scripted to hold still)");
    std::printf("quality: %s\n", viewQualityName(loopQuality));
    for (int run = 0; run < runs; ++run) {
        Renderer renderer(*window, loaded.volume, loaded.scene.transferFunction);
        configureRenderer(loaded, renderer);
        SessionStep step(InteractionState::fromScene(loaded.scene), initialFrame(loaded.scene, renderer.geometry()));
        step.attachRemoval(loaded.volume.dims, loaded.volume.indexToWorld);
        // Adaptive: step I first, outside the session (its cost is the exact quality's first frame), so the
        // previews and the exact frame are timed as a still scene's are, not behind step I's slices.
        if (adaptive)
            while (renderer.precomputePending(step.frame())) renderer.advancePrecompute(1000.0);
        XrLoopOptions options;
        options.record = work / ("run-" + std::to_string(run) + ".jsonl");
        options.sceneInSession = std::filesystem::absolute(scenePath).string();
        options.printStates = false;
        options.loop.quality = loopQuality;
        options.endAfterExact = adaptive;
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
        if (adaptive) {
            // Previews: the moving frames after the first (which runs step I's slices); their rate is one over
            // the median wall time between consecutive preview frames.
            std::vector<double> pl, pr, interval;
            double lastMotionS = 0;
            const XrFrameTiming* exact = nullptr;
            for (std::size_t i = 0; i < result.rendered.size(); ++i) {
                const XrFrameTiming& t = result.rendered[i];
                if (t.moved) lastMotionS = t.wallS, exact = nullptr;
                if (t.submittedExact && !exact) exact = &t;
                if (i == 0 || t.step != XrStep::Preview || !t.moved) continue;
                pl.push_back(t.eyeMs[0]);
                pr.push_back(t.eyeMs[1]);
                if (result.rendered[i - 1].step == XrStep::Preview) interval.push_back(t.wallS - result.rendered[i - 1].wallS);
            }
            if (!exact) throw SystemError("bench xr: the session ended before the exact frame after the motion was submitted");
            f.previewLeftMs = pl.empty() ? 0 : median(pl);
            f.previewRightMs = pr.empty() ? 0 : median(pr);
            f.previewFps = interval.empty() ? 0 : 1.0 / median(interval);
            f.exactLeftMs = exact->eyeMs[0];
            f.exactRightMs = exact->eyeMs[1];
            f.exactCaoMs = caoMs(exact->firstEye);
            f.settleToExactS = exact->wallS - lastMotionS;
            int slices = 0;
            for (const XrFrameTiming& t : result.rendered)
                if (t.step == XrStep::ExactSlice && t.wallS > lastMotionS && t.wallS <= exact->wallS) ++slices;
            f.exactFrames = slices;
        }

        // CAO == LAO on every rendered frame: the recording followed again, in the same renderer, untimed.
        Session session = readSession(*options.record, false);
        SessionStep again(InteractionState::fromSessionStart(session.header, loaded.scene, scenePath.parent_path(), options.record->string()),
                          initialFrame(loaded.scene, renderer.geometry()));
        again.attachRemoval(loaded.volume.dims, loaded.volume.indexToWorld);
        // Adaptive: the still frames after the motion hold one state; the first of them is checked.
        const std::size_t checkedFrames = adaptive ? std::min(session.frames.size(), static_cast<std::size_t>(frames) + 1) : session.frames.size();
        for (std::size_t n = 0; n < checkedFrames; ++n) {
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
        if (adaptive)
            std::printf("run %d: %d frames, eyes %dx%d, previews %.1f + %.1f ms at %.1f frames/s while moving, exact %.0f + %.0f ms in %d frames, "
                        "%.2f s from the last motion, CAO == LAO on %d of %d\n",
                        run + 1, f.frames, f.eye.x, f.eye.y, f.previewLeftMs, f.previewRightMs, f.previewFps, f.exactLeftMs, f.exactRightMs,
                        f.exactFrames, f.settleToExactS, f.equal, f.checked);
        else
            std::printf("run %d: %d frames, eyes %dx%d, first frame %.0f ms, then %.1f + %.1f ms a frame, CAO == LAO on %d of %d\n", run + 1,
                        f.frames, f.eye.x, f.eye.y, f.firstFrameMs, f.leftMs, f.rightMs, f.equal, f.checked);
        std::fflush(stdout);
    }
    std::error_code ec;
    std::filesystem::remove_all(work, ec);

    auto check = [](const RunFigures& f) { return f.checked ? std::to_string(f.equal) + " of " + std::to_string(f.checked) : std::string("-"); };
    Table perRun = adaptive
        ? Table("A: per run (previews: the moving frames after the first; eye times are wall ms: render, read back, submit, medians; exact: "
                "the slices of the frame after the motion summed per eye; CAO: GPU ms of its update; wait: wall s from the last motion to its "
                "submission)",
                {"run", "eye size", "frames", "preview left ms", "preview right ms", "previews/s moving", "exact left ms", "exact right ms",
                 "exact XR frames", "CAO II-V ms", "wait to exact s", "CAO == LAO frames"})
        : Table("A: per run (eye times are wall ms: render, read back, submit; medians over the frames after the first; CAO and ray cast: GPU ms)",
                {"run", "eye size", "frames", "first frame ms", "step I ms", "left eye ms", "right eye ms", "CAO II-V ms/frame", "ray cast ms (left)",
                 "CAO == LAO frames"});
    for (std::size_t r = 0; r < figures.size(); ++r) {
        const RunFigures& f = figures[r];
        const std::string eye = std::to_string(f.eye.x) + "x" + std::to_string(f.eye.y);
        if (adaptive)
            perRun.add({static_cast<int>(r + 1), eye, f.frames, f.previewLeftMs, f.previewRightMs, f.previewFps, f.exactLeftMs, f.exactRightMs,
                        f.exactFrames, f.exactCaoMs, f.settleToExactS, check(f)});
        else
            perRun.add({static_cast<int>(r + 1), eye, f.frames, f.firstFrameMs, f.stepIMs, f.leftMs, f.rightMs, f.caoMs, f.rayCastMs, check(f)});
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
    if (adaptive) {
        row("preview left eye ms", &RunFigures::previewLeftMs);
        row("preview right eye ms", &RunFigures::previewRightMs);
        row("previews/s while moving", &RunFigures::previewFps);
        row("exact left eye ms (slices)", &RunFigures::exactLeftMs);
        row("exact right eye ms (slices)", &RunFigures::exactRightMs);
        row("CAO II-V ms (exact frame)", &RunFigures::exactCaoMs);
        row("wait from last motion to exact s", &RunFigures::settleToExactS);
    } else {
        row("left eye ms", &RunFigures::leftMs);
        row("right eye ms", &RunFigures::rightMs);
        row("CAO II-V ms/frame (shared)", &RunFigures::caoMs);
        row("ray cast ms (left eye)", &RunFigures::rayCastMs);
        row("first frame ms (both eyes)", &RunFigures::firstFrameMs);
        row("step I ms", &RunFigures::stepIMs);
    }
    overRuns.print();
    std::printf("runtime: %s; system: %s; renderer: %s\n", runtimeName.c_str(), systemName.c_str(), rendererName.c_str());
    writeJson(jsonPath, {{"bench", "xr"},
                         {"scene", scenePath.string()},
                         {"volume", loaded.scene.volumePath.string()},
                         {"runtime", runtimeName},
                         {"system", systemName},
                         {"test_runtime", testRuntime},
                         {"drill", drill},
                         {"quality", viewQualityName(loopQuality)},
                         {"runs", runs},
                         {"frames", frames},
                         {"renderer", rendererName},
                         {"tables", {perRun.toJson(), overRuns.toJson()}}});
    return equal == checked ? 0 : 1;
}

}  // namespace curette::bench
