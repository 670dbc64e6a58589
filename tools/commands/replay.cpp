// curette replay FILE: re-renders a recorded session headless, frame by frame, and checks it. A head-mounted
// display session (`view --xr --record`, session version 6) renders each frame's two eyes from the recorded
// views and fields of view, left and right side by side in one image.
//   --out DIR        one PNG per rendered frame, and (with --check) frames.csv and frames.png (a plot)
//   --every N        render every Nth frame (poses are still followed on every frame)
//   --check          per frame: CAO equals full LAO (V_AO and image, for cao/lao frames), render time,
//                    recompute fraction and image hash, as CSV and a plot
//   --from-reports   re-derive every pose and light direction (and from session version 6 the drilling: which
//                    meshes drilled, undo and redo) from the raw reports and keys through the parsers and the
//                    recorded mapping (in a head-mounted display session also from the controllers' recorded grip
//                    poses and action states through session/xr_hands.h, and the volume's place in the room), and check
//                    they equal the recorded ones exactly
//   --no-render      with --from-reports: check the poses only (no GL context)
//   --lenient        replay the valid prefix of a session with a bad line instead of refusing it
//   --mp4            with --out: DIR/replay.mp4 of the frames at the recorded rate (tools/movie.h; needs ffmpeg)
//   --save-scene F   the state after the last frame as a scene file (meshes, lights, edited settings, camera)
//   --report         with --out: the removal report (session/carve_report.h) of every Nth frame in
//                    DIR/report/frame_NNNNNN/, the plan's exports for the last of them, and removal.csv and
//                    removal.png (removed mL and cut streamlines over time)
#include "session/carve_report.h"
#include "tools/command_line.h"
#include "tools/commands/commands.h"
#include "session/interaction.h"
#include "session/loaded_scene.h"
#include "session/removal_file.h"
#include "tools/movie.h"
#include "session/plan_scene.h"
#include "session/session.h"
#include "session/session_step.h"
#include "base/atomic_file.h"
#include "base/error.h"
#include "base/json_reader.h"
#include "mesh/mesh_description.h"
#include "input/pipeline.h"
#include "render/renderer.h"
#include "render/stereo_render.h"
#include "session/xr_hands.h"
#include "tools/xr_loop.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>

namespace curette::commands {

namespace {

// Writes `name`.gnuplot (a PNG terminal, CSV input, `settings`, then `plot` with `plotArguments`) and runs gnuplot on it to turn
// `name`.csv into `name`.png; a missing or failing gnuplot leaves the CSV and says so.
void plot(const std::filesystem::path& dir, const std::string& name, const std::string& settings, const std::string& plotArguments) {
    std::string csv = (dir / (name + ".csv")).string();
    std::string script = "set terminal pngcairo size 900,500 noenhanced\nset output '" + (dir / (name + ".png")).string() +
                         "'\nset datafile separator ','\nset key top left\n" + settings + "plot '" + csv + "' " + plotArguments + "\n";
    std::filesystem::path scriptPath = dir / (name + ".gnuplot");
    writeFileAtomically(scriptPath, script);
    std::string command = "gnuplot '" + scriptPath.string() + "' 2>/dev/null";
    if (std::system(command.c_str()) != 0) std::fprintf(stderr, "curette replay: gnuplot failed; %s is still written\n", csv.c_str());
}

// frames.csv -> frames.png: render time and recompute fraction.
void plotFrames(const std::filesystem::path& dir) {
    plot(dir, "frames", "set xlabel 'frame'\nset ylabel 'ms'\nset y2label 'recomputed voxels (%)'\nset y2tics\nset ytics nomirror\n",
         "using 1:3 skip 1 with lines title 'frame ms', '' using 1:4 skip 1 with lines title 'AO ms', "
         "'' using 1:($5*100) skip 1 axes x1y2 with lines title 'recomputed %'");
}

// removal.csv -> removal.png: removed mL and cut streamlines (all bundles) over the session.
void plotRemoval(const std::filesystem::path& dir) {
    plot(dir, "removal", "set xlabel 'time (s)'\nset ylabel 'removed (mL)'\nset y2label 'cut streamlines'\nset y2tics\nset ytics nomirror\n",
         "using 2:3 skip 1 with lines title 'removed mL', '' using 2:5 skip 1 axes x1y2 with lines title 'cut streamlines'");
}

int replay(const CommandLine& cl) {
    if (cl.positional().size() != 1) throw InputError("<command line>", "FILE", "one session file: curette replay FILE [options]");
    std::filesystem::path file = cl.positional()[0];
    int every = CommandLine::parseInt("every", cl.valueOr("every", "1"), 1, 1 << 20);
    bool check = cl.flag("check"), fromReports = cl.flag("from-reports");
    std::optional<glm::ivec2> size;
    if (auto s = cl.value("size")) size = CommandLine::parseSize("size", *s);
    std::optional<std::filesystem::path> out;
    if (auto o = cl.value("out")) {
        out = *o;
        std::error_code ec;
        std::filesystem::create_directories(*out, ec);
        if (ec) throw SystemError(out->string() + ": cannot create the output directory (" + ec.message() + ")");
    }

    Session session = readSession(file, cl.flag("lenient"));
    std::filesystem::path scenePath = sessionScenePath(session);
    LoadedScene loaded = loadSceneWithVolume(scenePath);
    bool render = !cl.flag("no-render");
    bool reporting = cl.flag("report");
    bool movie = cl.flag("mp4");
    if (movie && !out) throw InputError("<command line>", "--mp4", "together with --out DIR (where the frames and the movie go)");
    if (movie && !ffmpegAvailable()) throw SystemError("--mp4 needs ffmpeg on PATH (apt-get install ffmpeg)");
    if (reporting && !out) throw InputError("<command line>", "--report", "together with --out DIR (where the reports go)");
    if (!render && !fromReports) throw InputError("<command line>", "--no-render", "together with --from-reports (otherwise there is nothing to do)");
    if (!render && reporting) throw InputError("<command line>", "--report", "without --no-render (the report uses the renderer's clip maps)");
    std::unique_ptr<gl::Context> context;
    std::unique_ptr<Renderer> renderer;
    if (render) {
        context = gl::createHeadlessContext(gpuChoice(cl));
        renderer = std::make_unique<Renderer>(*context, loaded.volume, loaded.scene.transferFunction);
        configureRenderer(loaded, *renderer);
    }
    VolumeGeometry geometry{loaded.volume.dims, loaded.volume.indexToWorld};
    SessionStep step(InteractionState::fromSessionStart(session.header, loaded.scene, scenePath.parent_path(), file.string()),
                     initialFrame(loaded.scene, geometry));
    step.attachRemoval(loaded.volume.dims, loaded.volume.indexToWorld, sessionStartRemoval(session, loaded).get());
    const InteractionState& state = step.state();
    std::optional<CarveReporter> reporter;
    if (reporting) reporter.emplace(loaded, geometry, programVersion());
    std::string removalCsv = "frame,time_s,removed_ml,touched_voxels,cut_streamlines,protected_touched\n";
    std::optional<plan::Report> lastReport;
    InteractionState lastReportState;

    // A head-mounted display session (`view --xr --record`): both eyes from the recorded views, side by side;
    // re-derived, the hands' actions from their recorded states.
    const std::optional<SessionXr>& xr = session.header.xr;
    // The volume's place in the room: followed from the recorded frames, or re-derived from the hands.
    std::optional<RoomAnchor> anchor;
    if (xr) anchor = tableAnchor(geometry, xr->space);
    XrHands xrHands(anchor.value_or(RoomAnchor{}), session.header.version);
    const glm::vec4 background(loaded.scene.background);

    std::optional<input::InputPipeline> pipeline;
    if (fromReports) {
        pipeline.emplace(input::parseMapping(session.header.mappingJson, file.string() + " line 1: mapping"), session.header.keyboardMmPerSecond,
                         session.header.keyboardDegPerSecond);
        pipeline->restore(session.header.inputState);
    }

    std::string csv = "frame,time_s,render_ms,ao_ms,recomputed_fraction,image_hash,cao_equals_lao\n";
    int rendered = 0, poseMismatches = 0, caoMismatches = 0, checked = 0;
    std::vector<std::string> movieFrames;
    std::printf("curette replay: %s, %zu frames, scene %s%s\n", file.c_str(), session.frames.size(), scenePath.c_str(),
                session.warning.empty() ? "" : " (lenient: a bad tail was dropped)");
    for (std::size_t n = 0; n < session.frames.size(); ++n) {
        const SessionFrame& f = session.frames[n];
        std::string where = file.string() + " line " + std::to_string(n + 2);
        if (fromReports) {
            for (const SessionDevice& d : f.devicesAdded)
                if (auto family = input::familyFromName(d.family)) pipeline->addDevice(d.id, *family);
            for (int id : f.devicesRemoved) pipeline->removeDevice(id);
            std::vector<input::RawReport> reports;
            for (const SessionReport& r : f.reports) reports.push_back({r.device, r.time, r.bytes});
            input::KeyboardMouseState keys{f.keys, f.drag, f.lightDrag};
            step.frame().camera = f.camera;
            step.frame().size = f.size;
            std::vector<input::Action> actions = pipeline->step(reports, keys, f.dt, static_cast<int>(state.meshes.size()), f.holds);
            if (f.xr)
                for (input::Action& a : xrHands.step(f.xr->hands, f.dt)) actions.push_back(std::move(a));
            // From version 6 the drilling comes from the keys, devices and controllers (actions) like the poses, and
            // the frame's "drill" records what they applied; before, it is the drilling input itself (no key or
            // button drilled).
            bool drillFromInput = session.header.version >= kDrillFromInputVersion || f.xr;
            step.apply(actions, f.size.y, f.edits, where, drillFromInput ? DrillInput{} : DrillInput{f.drills, f.historyCommands});
            // The re-derived poses, lights (version 2), shading and drilling must be the recorded ones, bit for bit.
            // A head-mounted display's volume (version 7): where the re-derived hands put it is where it was recorded.
            const bool sameVolume = !f.xr || !f.xr->anchor || (xrHands.anchor().volumeCentreRoomM == f.xr->anchor->volumeCentreRoomM &&
                                                               xrHands.anchor().volumeTurnRoom == f.xr->anchor->volumeTurnRoom &&
                                                               xrHands.anchor().volumeScale == f.xr->anchor->volumeScale);
            if (f.xr) anchor = xrHands.anchor();
            bool same = state.shading == f.shading && samePoses(state.sessionPoses(), f.meshes) && (!f.lights || state.lightDirections() == *f.lights) &&
                        (!drillFromInput || (state.appliedDrills == f.drills && state.appliedHistory == f.historyCommands &&
                                              state.appliedHistoryEdits == f.historyEdits)) &&
                        sameVolume;
            if (!same && poseMismatches++ == 0)
                std::fprintf(stderr, "curette replay: %s: poses, lights, drilling or the volume's place re-derived from the reports differ from the recorded ones\n",
                             where.c_str());
        } else {
            // Follow the recorded poses: meshes added and removed, then every pose.
            step.follow(f, scenePath.parent_path(), where);
            if (f.xr) anchor = recordedAnchor(*anchor, *f.xr);
        }
        if (!render || n % static_cast<std::size_t>(every) != 0) continue;
        step.syncTo(*renderer, loaded.tracts);
        FrameDescription frame = step.frame();
        frame.size = size.value_or(f.size);
        frame.shading = f.shading;
        const bool xrFrame = xr && f.xr && f.xr->views;
        if (xr && !xrFrame) continue;   // a frame the runtime did not ask to render
        std::array<TrackedEye, 2> eyes;
        std::array<Image, 2> eyeImages;
        renderer->collectTimings();
        auto start = std::chrono::steady_clock::now();
        Image image;
        if (xrFrame) {
            // Both eyes (one V_AO: the second reuses the first's), left and right side by side in one image.
            eyes = xrEyes(frame, *f.xr->views, *anchor, size ? std::array<glm::ivec2, 2>{*size, *size} : xr->recommendedSize);
            for (std::size_t e = 0; e < 2; ++e) eyeImages[e] = renderTrackedEye(*renderer, eyes[e]);
            image = composeStereo(StereoMode::SideBySide, eyeImages[0], eyeImages[1], background);
        } else {
            renderer->render(frame);
            renderer->finish();
        }
        double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        double aoMs = renderer->collectTimings().ambientOcclusionMs();
        if (!xrFrame) image = renderer->readImage();
        std::vector<std::uint8_t> rgba = toRgba8(image, background);
        std::string hash = imageHash(rgba);
        double fraction = renderer->ambientOcclusion() && usesAmbientOcclusion(frame.shading) ? renderer->ambientOcclusion()->lastStats().recomputedFraction() : 0.0;
        std::string equal = "-";
        if (check && usesAmbientOcclusion(frame.shading)) {
            // The exactness contract on this frame: the other AO mode under the same clipping.
            bool same = false;
            if (xrFrame) {
                same = xrCaoEqualsLao(*renderer, eyes, eyeImages);
            } else {
                std::vector<std::uint16_t> ambient = renderer->ambientOcclusion()->readAmbient();
                FrameDescription other = frame;
                other.shading = frame.shading == ShadingMode::Cao ? ShadingMode::Lao : ShadingMode::Cao;
                renderer->render(other);
                same = renderer->ambientOcclusion()->readAmbient() == ambient &&
                       std::memcmp(renderer->readImage().pixels.data(), image.pixels.data(), image.pixels.size() * sizeof(glm::vec4)) == 0;
            }
            equal = same ? "yes" : "NO";
            ++checked;
            if (!same) ++caoMismatches;
            renderer->collectTimings();
        }
        char line[256];
        std::snprintf(line, sizeof line, "%zu,%.4f,%.2f,%.2f,%.6f,%s,%s\n", f.index, f.time, ms, aoMs, fraction, hash.c_str(), equal.c_str());
        csv += line;
        if (out) {
            movieFrames.push_back(movieFrameName(f.index));
            writePng(*out / movieFrames.back(), image, background);
        }
        if (reporter) {
            plan::Report report = reporter->compute(renderer->clipMeshes(), state);
            char name[64];
            std::snprintf(name, sizeof name, "frame_%06zu", f.index);
            reporter->write(*out / "report" / name, report, state, PlanExportOptions{io::MeshSpace::Ras, false});
            std::uint64_t cut = 0;
            for (const plan::BundleRow& b : report.bundles) cut += b.cut;
            char row[160];
            std::snprintf(row, sizeof row, "%zu,%.4f,%.6f,%llu,%llu,%zu\n", f.index, f.time, report.removedMl,
                          static_cast<unsigned long long>(report.touchedVoxels), static_cast<unsigned long long>(cut), report.warnings().size());
            removalCsv += row;
            std::printf("           removed %.3f mL, %llu streamlines cut%s\n", report.removedMl, static_cast<unsigned long long>(cut),
                        report.warnings().empty() ? "" : ", PROTECTED TOUCHED");
            lastReport = std::move(report);
            lastReportState = state;
        }
        std::printf("frame %6zu  %-5s %8.1f ms  AO %8.1f ms  recomputed %6.2f %%  %s%s\n", f.index, shadingModeName(frame.shading), ms, aoMs,
                    100.0 * fraction, hash.c_str(), equal == "-" ? "" : ("  CAO == LAO: " + equal).c_str());
        ++rendered;
    }
    if (state.removal && !state.removal->empty())
        std::printf("drilled %.3f mL; removal %s\n", state.removal->drilledVolumeMm3() / 1000.0, state.removal->digest().c_str());
    if (reporter && lastReport) {
        // The whole plan (exports included) for the last reported frame; the series as CSV and a plot.
        reporter->write(*out / "report", *lastReport, lastReportState, PlanExportOptions{});
        writeFileAtomically(*out / "removal.csv", removalCsv);
        plotRemoval(*out);
        std::printf("wrote %s, %s and the plan of the last reported frame in %s\n", (*out / "removal.csv").c_str(),
                    (*out / "removal.png").c_str(), (*out / "report").c_str());
    }
    if (auto saved = cl.value("save-scene")) {
        std::vector<std::uint8_t> text = readFileBytes(scenePath);
        saveScene(*saved, loaded.scene, std::string(text.begin(), text.end()), state, &step.frame().camera);
        std::printf("wrote the scene %s\n", saved->c_str());
    }
    if (movie && !movieFrames.empty()) {
        // The recorded rate, over the frames rendered: a movie as long as the session.
        double seconds = session.frames.back().time - session.frames.front().time;
        double fps = seconds > 0 && session.frames.size() > 1 ? double(session.frames.size() - 1) / seconds / every : 30.0;
        encodeMovie(*out, movieFrames, fps, *out / "replay.mp4");
        std::printf("wrote %s (%zu frames at %.3g fps)\n", (*out / "replay.mp4").c_str(), movieFrames.size(), fps);
    }
    if (out && check) {
        writeFileAtomically(*out / "frames.csv", csv);
        plotFrames(*out);
        std::printf("wrote %s and %s\n", (*out / "frames.csv").c_str(), (*out / "frames.png").c_str());
    }
    std::printf("replayed %zu frames, rendered %d", session.frames.size(), rendered);
    if (fromReports)
        std::printf(", %s from reports: %s", session.header.version >= kDrillFromInputVersion ? "poses and drilling" : "poses",
                    poseMismatches ? "DIFFERENT" : "identical to the recorded ones");
    if (checked) std::printf(", CAO == LAO on %d of %d checked frames", checked - caoMismatches, checked);
    std::printf("\n");
    return poseMismatches || caoMismatches ? 1 : 0;
}

}  // namespace

Command replayCommand() {
    return {{"replay", "F.jsonl", "re-render a recorded session headless, frame by frame, and check it",
             withGpuOption({{"out", true, "directory for PNGs, frames.csv and frames.png"},
              {"every", true, "render every Nth frame (default 1)"},
              {"check", false, "verify CAO == LAO per frame, write timing/recompute/hash CSV and a plot"},
              {"from-reports", false, "re-derive poses from the raw reports (and XR controller states) and check them"},
              {"lenient", false, "replay the valid prefix of a damaged session"},
              {"size", true, "render at WxH instead of the recorded size", "WxH"},
              {"no-render", false, "with --from-reports: only check the poses, render nothing"},
              {"report", false, "with --out: the removal report every Nth frame, removal.csv and removal.png"},
              {"mp4", false, "with --out: also DIR/replay.mp4 of the frames, at the recorded rate (needs ffmpeg on PATH)"},
              {"save-scene", true, "write the state after the last frame as a scene file (session/plan_scene.h), camera included"}})},
            &replay};
}

}  // namespace curette::commands
