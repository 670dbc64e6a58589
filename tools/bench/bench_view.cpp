// curette bench view --session F: the viewer's frame loop (viewer/view_frame_loop.h) driven headless, as a user
// at the window would meet it. Two phases:
//   1. the first frame: the session's start state from a fresh renderer, with step I in slices, until the exact
//      frame is on screen (the time to the first image, step I's wall time, how long the frames during it took:
//      how responsive the window stays);
//   2. the session played back in real time: at wall time t the session's state at recorded time t (the
//      recorded frames the renderer cannot keep up with are skipped, as in a live viewer), until after the last
//      motion the exact frame is on screen (the frame intervals while in motion, and the time from the last
//      recorded motion to the exact frame).
// Both phases report the longest the window went without a presented frame (what `view` draws to the window when
// nothing else happens: a new image, a slice of step I or of the exact frame, with its progress).
// --check renders the last state once more in a fresh renderer (what `curette render` gives) and compares the
// image hashes.
#include "tools/bench/bench_view.h"

#include "tools/bench/lao_options.h"
#include "tools/bench/report.h"
#include "session/interaction.h"
#include "session/loaded_scene.h"
#include "session/removal_file.h"
#include "session/session.h"
#include "session/session_step.h"
#include "viewer/viewer_driver.h"
#include "base/error.h"
#include "render/model/lao_directions.h"
#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <thread>

namespace curette::bench {

namespace {

using Clock = std::chrono::steady_clock;

double msBetween(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double, std::milli>(b - a).count(); }

// Nearest-rank percentile (p in [0, 100]) of a list; 0 for an empty one.
double percentile(std::vector<double> values, double p) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    std::size_t rank = static_cast<std::size_t>(std::ceil(p / 100.0 * double(values.size())));
    return values[std::clamp<std::size_t>(rank, 1, values.size()) - 1];
}

// One iteration of the loop as run.
struct LoopFrame {
    double t = 0;              // s since the phase began, at the end of the iteration
    double ms = 0;             // wall time of the iteration's work (step I slices, render, finish)
    double renderMs = 0;       // of it, the render
    FrameKind kind = FrameKind::None;
    bool exactShown = false;   // the exact frame was on screen after it (an exact frame in slices: its last)
    bool presented = false;    // the window presents after it (ViewerIteration::rendered)
    glm::ivec2 size{0};
    bool inMotion = false;
    bool precomputing = false;
    double progress = 1;       // step I after the iteration
    int followed = 0;          // recorded frames applied before it
    FrameTimings passes;       // GPU time per pass of the iteration (render/model/frame_plan.h)
};

nlohmann::json toJson(const LoopFrame& f) {
    return {{"t_s", f.t}, {"ms", f.ms}, {"render_ms", f.renderMs}, {"kind", frameKindName(f.kind)}, {"exact_shown", f.exactShown}, {"presented", f.presented}, {"size", {f.size.x, f.size.y}},
            {"in_motion", f.inMotion}, {"precomputing", f.precomputing}, {"step1_progress", f.progress}, {"recorded_frames_applied", f.followed},
            {"pass_ms", [&] {
                 nlohmann::json passes = nlohmann::json::object();
                 for (const FrameTimings::Entry& e : f.passes.passes) passes[passInfo(e.pass).name] = passes.value(passInfo(e.pass).name, 0.0) + e.ms;
                 return passes;
             }()}};
}

// The 1-minute load average (/proc/loadavg), to say how shared the machine was; -1 where unknown.
double loadAverage() {
    std::ifstream in("/proc/loadavg");
    double load = -1;
    in >> load;
    return load;
}

// The frame loop's settings: the defaults of the viewer on this renderer, then the options.
FrameLoopSettings loopSettings(const CommandLine& cl, bool softwareRenderer) {
    FrameLoopSettings settings;
    settings.quality = defaultViewQuality(softwareRenderer);
    if (auto q = cl.value("quality")) {
        std::optional<ViewQuality> parsed = parseViewQuality(*q);
        if (!parsed) throw InputError("<command line>", "--quality", "exact or adaptive", "\"" + *q + "\"");
        settings.quality = *parsed;
    }
    settings.settleSeconds = CommandLine::parseDouble("settle", cl.valueOr("settle", std::to_string(settings.settleSeconds)), 0, 10);
    settings.precomputeBudgetMs =
        CommandLine::parseDouble("precompute-budget", cl.valueOr("precompute-budget", std::to_string(settings.precomputeBudgetMs)), 1, 10000);
    settings.previewTargetMs =
        CommandLine::parseDouble("preview-target", cl.valueOr("preview-target", std::to_string(settings.previewTargetMs)), 1, 10000);
    // 0: the exact frame whole, in one iteration (as before it was sliced; and as exact quality does).
    settings.exactBudgetMs = CommandLine::parseDouble("exact-budget", cl.valueOr("exact-budget", std::to_string(settings.exactBudgetMs)), 0, 100000);
    return settings;
}

// One iteration of the viewer's loop (viewer/viewer_driver.h, what the window runs between polling events and
// swapping buffers), as the bench records it.
struct Viewer {
    ViewerState state;
    Renderer& renderer;
    SessionStep& step;
    const std::vector<Tractogram>& tracts;
    glm::ivec2 size;
    glm::vec4 background;

    LoopFrame iterate(double now, bool moved, double movedAt = std::numeric_limits<double>::quiet_NaN()) {
        ViewerIteration it = stepViewer(state, renderer, step, tracts, size, now, moved, background, movedAt);
        LoopFrame out;
        out.kind = it.decision.render;
        out.size = it.decision.size;
        out.inMotion = it.decision.inMotion;
        out.precomputing = it.precomputing;
        out.exactShown = it.exactCompleted;
        out.presented = it.rendered;
        out.renderMs = it.renderMs;
        out.ms = it.ms;
        out.progress = renderer.precomputeProgress();
        out.passes = it.passes;
        // The viewer waits for events at most 1/120 s when it has nothing to draw; so does the bench.
        if (it.decision.render == FrameKind::None && it.decision.precomputeBudgetMs == 0) std::this_thread::sleep_for(std::chrono::microseconds(8333));
        return out;
    }
};

// The longest wall time (ms) in a phase without a presented frame: from the phase's start to its first, between
// two, and from its last to its end.
double longestWithoutAFrame(const std::vector<LoopFrame>& frames) {
    double longest = 0, last = 0;
    for (const LoopFrame& f : frames) {
        if (!f.presented) continue;
        longest = std::max(longest, f.t - last);
        last = f.t;
    }
    if (!frames.empty()) longest = std::max(longest, frames.back().t - last);
    return 1000 * longest;
}

// Phase 1: the first frame, step I in slices, until the exact frame is shown.
struct FirstFrame {
    std::vector<LoopFrame> frames;
    double firstImageMs = -1, step1Ms = 0, firstExactMs = 0;
    std::vector<double> step1Frames;   // the iterations' work while step I ran
};

FirstFrame runFirstFrame(Viewer& viewer) {
    FirstFrame r;
    auto phaseStart = Clock::now();
    auto sinceStart = [&] { return msBetween(phaseStart, Clock::now()) / 1000.0; };
    for (;;) {
        LoopFrame f = viewer.iterate(sinceStart(), false);
        f.t = sinceStart();
        if (f.kind != FrameKind::None && r.firstImageMs < 0) r.firstImageMs = 1000 * f.t;
        if (f.precomputing) r.step1Ms = 1000 * f.t;
        r.frames.push_back(f);
        if (f.exactShown) {
            r.firstExactMs = 1000 * f.t;
            break;
        }
    }
    for (const LoopFrame& f : r.frames)
        if (f.precomputing) r.step1Frames.push_back(f.ms);
    return r;
}

// Phase 2: the session in real time.
struct Playback {
    std::vector<LoopFrame> frames;
    double lastMotionRecorded = -1;   // recorded time (from the session's start) of the last frame that changed anything
    double lastMotionApplied = -1;    // wall time it was applied at
    double exactAfterMotion = -1;     // wall time the exact frame after it was on screen
};

Playback playInRealTime(Viewer& viewer, const Session& session, const std::filesystem::path& file, const std::filesystem::path& sceneFolder) {
    Playback r;
    std::size_t next = 0;
    double sessionStart = session.frames.front().time;
    auto phaseStart = Clock::now();
    auto sinceStart = [&] { return msBetween(phaseStart, Clock::now()) / 1000.0; };
    for (;;) {
        double t = sinceStart();
        bool moved = false;
        int followed = 0;
        while (next < session.frames.size() && session.frames[next].time - sessionStart <= t) {
            const SessionFrame& rf = session.frames[next];
            OrbitCamera cameraBefore = viewer.step.frame().camera;
            StepChanges changes = viewer.step.follow(rf, sceneFolder, file.string() + " line " + std::to_string(next + 2));
            if (changes.any() || !(viewer.step.frame().camera == cameraBefore)) {
                moved = true;
                r.lastMotionRecorded = rf.time - sessionStart;
                r.lastMotionApplied = t;
            }
            ++next, ++followed;
        }
        // The motion happened at its recorded time (the playback's clock starts with the session), not when this
        // iteration got to it.
        LoopFrame f = viewer.iterate(t, moved, r.lastMotionRecorded);
        f.t = sinceStart();
        f.followed = followed;
        r.frames.push_back(f);
        bool sessionOver = next == session.frames.size();
        if (sessionOver && f.exactShown) {
            r.exactAfterMotion = f.t;
            break;
        }
        if (sessionOver && f.kind == FrameKind::None && viewer.renderer.lastFrameExact() && !f.inMotion && !f.precomputing) {
            r.exactAfterMotion = f.t;   // the exact frame was already on screen (nothing moved at the end)
            break;
        }
    }
    return r;
}

// What the playback's iterations say about the motion and the last exact frame.
struct PlaybackSummary {
    std::vector<double> intervals, previewMs, previewScale;
    int skipped = 0, presented = 0;
    double exactRenderMs = 0, settleFrameMaxMs = 0;
    int exactSlices = 0;
    std::map<std::string, double> exactPassMs;
};

PlaybackSummary summarise(const Playback& playback, glm::ivec2 size) {
    PlaybackSummary r;
    // Frame intervals while in motion: between the ends of consecutive presented frames of the playback, both in
    // motion (what the eye sees as the frame rate); the recorded frames each presented frame skipped.
    double previousEnd = -1;
    for (const LoopFrame& f : playback.frames) {
        if (f.followed > 1) r.skipped += f.followed - 1;
        if (f.kind == FrameKind::None) continue;
        ++r.presented;
        if (f.inMotion && previousEnd >= 0) r.intervals.push_back(1000 * (f.t - previousEnd));
        if (f.kind == FrameKind::Preview && f.inMotion) {
            r.previewMs.push_back(f.renderMs);
            r.previewScale.push_back(double(f.size.x) / size.x);
        }
        previousEnd = f.inMotion ? f.t : -1;
    }
    // The last exact frame's work: the iterations that ran it (one, or its slices), and the longest of all the
    // iterations after the last motion was applied (how long the window waited at most while it settled);
    // and its work by pass (steps IV, V and VI, and the clip maps when they were not drawn by the last preview).
    for (auto f = playback.frames.rbegin(); f != playback.frames.rend() && f->kind == FrameKind::Exact; ++f) {
        r.exactRenderMs += f->renderMs, ++r.exactSlices;
        for (const FrameTimings::Entry& e : f->passes.passes) r.exactPassMs[passInfo(e.pass).name] += e.ms;
    }
    for (const LoopFrame& f : playback.frames)
        if (playback.lastMotionApplied >= 0 && f.t - f.ms / 1000.0 >= playback.lastMotionApplied)
            r.settleFrameMaxMs = std::max(r.settleFrameMaxMs, f.ms);
    return r;
}

// --check: the image hash of a fresh renderer and a fresh session step that follows every recorded frame (the
// step syncs what changed since it last synced, so the played one cannot serve a second renderer): meshes and
// setting edits.
std::string freshRenderHash(gl::Context& context, const LoadedScene& loaded, const Session& session, const std::filesystem::path& file,
                            const std::filesystem::path& sceneFolder, glm::ivec2 size, glm::vec4 background) {
    Renderer fresh(context, loaded.volume, loaded.scene.transferFunction);
    configureRenderer(loaded, fresh);
    VolumeGeometry geometry{loaded.volume.dims, loaded.volume.indexToWorld};
    SessionStep freshStep(InteractionState::fromSessionStart(session.header, loaded.scene, sceneFolder, file.string()),
                          initialFrame(loaded.scene, geometry));
    freshStep.attachRemoval(loaded.volume.dims, loaded.volume.indexToWorld, sessionStartRemoval(session, loaded).get());   // drilling too
    for (std::size_t n = 0; n < session.frames.size(); ++n)
        freshStep.follow(session.frames[n], sceneFolder, file.string() + " line " + std::to_string(n + 2));
    freshStep.syncTo(fresh, loaded.tracts);
    FrameDescription freshFrame = freshStep.frame();
    freshFrame.shading = freshStep.state().shading;
    freshFrame.size = size;
    fresh.render(freshFrame);
    return imageHash(toRgba8(fresh.readImage(), background));
}

}  // namespace

int benchView(const CommandLine& cl) {
    std::filesystem::path file = cl.required("session");
    glm::ivec2 size = CommandLine::parseSize("size", cl.valueOr("size", "1024x768"));
    std::filesystem::path jsonPath = cl.valueOr("json", "bench-view.json");
    Session session = readSession(file, false);
    if (session.frames.empty()) throw InputError(file.string(), "frames", "at least one recorded frame after the header");
    std::filesystem::path scenePath = session.header.scene;
    if (scenePath.is_relative()) scenePath = file.parent_path() / scenePath;
    LoadedScene loaded = loadSceneWithVolume(scenePath);
    // --rays K: the LAO ray count instead of the scene's (as in bench cao; the test runs with few).
    if (auto rays = cl.value("rays")) {
        std::string k = std::to_string(CommandLine::parseInt("rays", *rays, 1, 1024));
        if (!parseLaoPattern(k, loaded.scene.lao.directions)) parseLaoPattern("fibonacci:" + k, loaded.scene.lao.directions);
    }
    applyUnseenVoxelsOption(cl, loaded.scene.lao);

    auto context = gl::createHeadlessContext(gpuChoice(cl));
    FrameLoopSettings settings = loopSettings(cl, context->info().softwareRenderer);
    glm::vec4 background(loaded.scene.background);

    double loadBefore = loadAverage();
    auto setupStart = Clock::now();
    Renderer renderer(*context, loaded.volume, loaded.scene.transferFunction);
    configureRenderer(loaded, renderer);
    renderer.setRecastOnlyChangedPixels(recastOnlyChanged(cl));
    VolumeGeometry geometry{loaded.volume.dims, loaded.volume.indexToWorld};
    SessionStep step(InteractionState::fromSessionStart(session.header, loaded.scene, scenePath.parent_path(), file.string()),
                     initialFrame(loaded.scene, geometry));
    step.attachRemoval(loaded.volume.dims, loaded.volume.indexToWorld, sessionStartRemoval(session, loaded).get());
    Viewer viewer{ViewerState(settings), renderer, step, loaded.tracts, size, background};
    renderer.finish();
    renderer.collectTimings();
    double setupMs = msBetween(setupStart, Clock::now());

    std::printf("curette bench view: %s (%zu frames, %.2f s), %dx%d, quality %s, %s\n", file.c_str(), session.frames.size(),
                session.frames.back().time - session.frames.front().time, size.x, size.y, viewQualityName(settings.quality),
                context->info().renderer.c_str());
    FirstFrame firstFrame = runFirstFrame(viewer);
    const std::vector<LoopFrame>& first = firstFrame.frames;
    const double firstImageMs = firstFrame.firstImageMs, step1Ms = firstFrame.step1Ms, firstExactMs = firstFrame.firstExactMs;
    const std::vector<double>& step1Frames = firstFrame.step1Frames;

    Playback playback = playInRealTime(viewer, session, file, scenePath.parent_path());
    const std::vector<LoopFrame>& played = playback.frames;
    PlaybackSummary summary = summarise(playback, size);
    const std::vector<double>&intervals = summary.intervals, &previewMs = summary.previewMs, &previewScale = summary.previewScale;
    const int skipped = summary.skipped, presented = summary.presented, exactSlices = summary.exactSlices;
    const double exactRenderMs = summary.exactRenderMs, settleFrameMaxMs = summary.settleFrameMaxMs;
    const std::map<std::string, double>& exactPassMs = summary.exactPassMs;
    double fromRecordedMotion = playback.lastMotionRecorded >= 0 ? 1000 * (playback.exactAfterMotion - playback.lastMotionRecorded) : 0;
    double fromAppliedMotion = playback.lastMotionApplied >= 0 ? 1000 * (playback.exactAfterMotion - playback.lastMotionApplied) : 0;
    FrameDescription lastFrame = viewerFrame(viewer.state, step, size);
    bool lastIsExact = renderer.lastFrameExact() && renderer.showing(lastFrame);
    std::string hash = imageHash(toRgba8(renderer.readImage(), background));

    std::optional<std::string> freshHash;
    if (cl.flag("check")) freshHash = freshRenderHash(*context, loaded, session, file, scenePath.parent_path(), size, background);

    double loadAfter = loadAverage();
    Table table("bench view: the viewer's frame loop on " + file.filename().string() + ", " + std::to_string(size.x) + "x" +
                    std::to_string(size.y) + ", quality " + viewQualityName(settings.quality) + " (wall times on a shared machine)",
                {"measure", "value", "unit", "what it measures"});
    table.add({"load average", std::max(loadBefore, loadAfter), "", "1-minute load average at the start or end, whichever is higher (of " +
                                                                           std::to_string(std::thread::hardware_concurrency()) + " cores)"});
    table.add({"renderer set-up", setupMs, "ms", "volume upload and scene configuration (before the loop; the window is not open yet)"});
    table.add({"first image", firstImageMs, "ms", "loop start to the first presented image (a preview while step I runs)"});
    table.add({"step I", step1Ms, "ms", "loop start to V_PAO complete (step I in slices)"});
    table.add({"frames during step I", static_cast<double>(step1Frames.size()), "", "iterations that ran a slice of step I"});
    table.add({"step I frame p50", percentile(step1Frames, 50), "ms", "per iteration during step I (slices + the preview when drawn)"});
    table.add({"step I frame max", percentile(step1Frames, 100), "ms", "the longest the window waited during step I"});
    table.add({"first exact frame", firstExactMs, "ms", "loop start to the first exact frame on screen"});
    const double firstGapMs = longestWithoutAFrame(first), playbackGapMs = longestWithoutAFrame(played);
    table.add({"first frame: longest without a frame", firstGapMs, "ms", "the longest the window went without presenting, loop start to the first exact frame"});
    table.add({"motion frames", static_cast<double>(intervals.size()), "", "presented frames in motion during playback"});
    table.add({"motion frame p50", percentile(intervals, 50), "ms", "interval between presented frames while in motion"});
    table.add({"motion frame p90", percentile(intervals, 90), "ms", "(same)"});
    table.add({"motion frame p99", percentile(intervals, 99), "ms", "(same)"});
    table.add({"motion frame max", percentile(intervals, 100), "ms", "(same)"});
    table.add({"motion fps", intervals.empty() ? 0.0 : 1000.0 / percentile(intervals, 50), "1/s", "1000 / p50"});
    table.add({"preview render p50", percentile(previewMs, 50), "ms", "render + finish of a motion preview"});
    table.add({"preview scale p50", percentile(previewScale, 50), "", "preview width / exact width"});
    table.add({"recorded frames skipped", static_cast<double>(skipped), "", "recorded frames applied together with a later one"});
    table.add({"last motion -> exact", fromRecordedMotion, "ms", "recorded time of the last motion to the exact frame on screen"});
    table.add({"applied motion -> exact", fromAppliedMotion, "ms", "wall time the last motion was applied to the exact frame on screen"});
    table.add({"exact frame render", exactRenderMs, "ms", "the last exact frame's render + finish (steps IV, V, VI), over its slices"});
    for (const auto& [pass, ms] : exactPassMs) table.add({"  " + pass, ms, "ms", "of which this pass, over the slices"});
    AmbientOcclusionStats aoStats = renderer.ambientOcclusion() ? renderer.ambientOcclusion()->lastStats() : AmbientOcclusionStats{};
    double volumeVoxels = std::max<double>(double(aoStats.voxels), 1.0);
    table.add({"exact frame visited", 100.0 * double(aoStats.dispatched) / volumeVoxels, "%", "of the volume's voxels, steps IV and V of the last update"});
    table.add({"exact frame sample-tested", aoStats.bricks ? 100.0 * double(aoStats.sampledBricks) / double(aoStats.bricks) : 0.0, "%",
               "of its visited bricks, those where step IV tests clip samples"});
    table.add({"exact frame deep inside", aoStats.bricks ? 100.0 * double(aoStats.deepBricks) / double(aoStats.bricks) : 0.0, "%",
               "of its visited bricks, those with every clip sample inside a mesh, known without a test"});
    table.add({"exact frame recomputed", 100.0 * double(aoStats.recomputed) / volumeVoxels, "%", "of the volume's voxels, LAO rays cast in its step V"});
    table.add({"exact frame recast", renderer.lastRecastShare(), "", "share of the pixels its ray cast covered (the rest kept: --recast changed)"});
    table.add({"exact frame slices", static_cast<double>(exactSlices), "", "iterations that ran it (--exact-budget 0: one)"});
    table.add({"settle frame max", settleFrameMaxMs, "ms", "the longest the window waited between the last motion and the exact frame"});
    table.add({"playback: longest without a frame", playbackGapMs, "ms", "the longest the window went without presenting during the playback"});
    table.add({"last frame exact", lastIsExact ? "yes" : "NO", "", "the image on screen at the end is the exact frame of the last state"});
    if (freshHash) table.add({"equals a fresh render", *freshHash == hash ? "yes" : "NO", "", "image hash against a fresh renderer of the last state"});
    table.print();

    nlohmann::json firstJson = nlohmann::json::array(), playedJson = nlohmann::json::array();
    for (const LoopFrame& f : first) firstJson.push_back(toJson(f));
    for (const LoopFrame& f : played) playedJson.push_back(toJson(f));
    nlohmann::json document = {
        {"bench", "view"},
        {"session", file.string()},
        {"scene", scenePath.string()},
        {"size", {size.x, size.y}},
        {"renderer", context->info().renderer},
        {"quality", viewQualityName(settings.quality)},
        {"settings",
         {{"settle_s", settings.settleSeconds}, {"precompute_budget_ms", settings.precomputeBudgetMs}, {"preview_target_ms", settings.previewTargetMs}, {"exact_budget_ms", settings.exactBudgetMs},
          {"preview_scale_min", settings.minPreviewScale}, {"preview_scale_max", settings.maxPreviewScale}}},
        {"load_average", {{"start", loadBefore}, {"end", loadAfter}}},
        {"cores", std::thread::hardware_concurrency()},
        {"setup_ms", setupMs},
        {"first_image_ms", firstImageMs},
        {"step1",
         {{"wall_ms", step1Ms}, {"frames", step1Frames.size()}, {"frame_ms_p50", percentile(step1Frames, 50)}, {"frame_ms_max", percentile(step1Frames, 100)}}},
        {"first_exact_ms", firstExactMs},
        {"motion",
         {{"frames", intervals.size()},
          {"frame_ms", {{"p50", percentile(intervals, 50)}, {"p90", percentile(intervals, 90)}, {"p99", percentile(intervals, 99)}, {"max", percentile(intervals, 100)}}},
          {"fps", intervals.empty() ? 0.0 : 1000.0 / percentile(intervals, 50)},
          {"preview_render_ms_p50", percentile(previewMs, 50)},
          {"preview_scale_p50", percentile(previewScale, 50)},
          {"recorded_frames_skipped", skipped},
          {"presented_frames", presented}}},
        {"exact_after_motion_ms", fromRecordedMotion},
        {"exact_after_applied_motion_ms", fromAppliedMotion},
        {"exact_render_ms", exactRenderMs},
        {"exact_pass_ms", exactPassMs},
        {"exact_slices", exactSlices},
        {"exact_recast_share", renderer.lastRecastShare()},
        {"exact_ao", {{"voxels", aoStats.voxels}, {"visited", aoStats.dispatched}, {"bricks", aoStats.bricks}, {"sample_tested_bricks", aoStats.sampledBricks}, {"deep_inside_bricks", aoStats.deepBricks},
                      {"recomputed", aoStats.recomputed}}},
        {"settle_frame_max_ms", settleFrameMaxMs},
        {"longest_without_a_frame_ms", {{"first_frame", firstGapMs}, {"playback", playbackGapMs}, {"max", std::max(firstGapMs, playbackGapMs)}}},
        {"last_frame", {{"exact", lastIsExact}, {"image_hash", hash}, {"size", {size.x, size.y}}}},
        {"tables", {table.toJson()}},
        {"first_phase_frames", firstJson},
        {"playback_frames", playedJson}};
    if (freshHash) {
        document["fresh_render_hash"] = *freshHash;
        document["equals_fresh_render"] = *freshHash == hash;
    }
    writeJson(jsonPath, document);
    return lastIsExact && (!freshHash || *freshHash == hash) ? 0 : 1;
}

}  // namespace curette::bench
