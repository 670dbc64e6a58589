// curette replay FILE: re-renders a recorded session headless, frame by frame, and checks it.
//   --out DIR        one PNG per rendered frame, and (with --check) frames.csv and frames.png (a plot)
//   --every N        render every Nth frame (poses are still followed on every frame)
//   --check          per frame: CAO equals full LAO (V_AO and image, for cao/lao frames), render time,
//                    recompute fraction and image hash, as CSV and a plot
//   --from-reports   re-derive every pose from the raw reports through the parsers and the recorded mapping,
//                    and check they equal the recorded poses exactly
//   --no-render      with --from-reports: check the poses only (no GL context)
//   --lenient        replay the valid prefix of a session with a bad line instead of refusing it
#include "app/command_line.h"
#include "app/commands/commands.h"
#include "app/interaction.h"
#include "app/loaded_scene.h"
#include "app/session.h"
#include "app/session_step.h"
#include "base/atomic_file.h"
#include "base/error.h"
#include "base/json_reader.h"
#include "clip/mesh_description.h"
#include "input/pipeline.h"
#include "render/renderer.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>

namespace curette::commands {

namespace {

// Writes a gnuplot script and runs it to turn frames.csv into frames.png (render time and recompute fraction).
void plot(const std::filesystem::path& dir) {
    std::string script = "set terminal pngcairo size 900,500 noenhanced\nset output '" + (dir / "frames.png").string() +
                         "'\nset datafile separator ','\nset key top left\nset xlabel 'frame'\nset ylabel 'ms'\n"
                         "set y2label 'recomputed voxels (%)'\nset y2tics\nset ytics nomirror\n"
                         "plot '" + (dir / "frames.csv").string() + "' using 1:3 skip 1 with lines title 'frame ms', "
                         "'' using 1:4 skip 1 with lines title 'AO ms', '' using 1:($5*100) skip 1 axes x1y2 with lines title 'recomputed %'\n";
    std::filesystem::path scriptPath = dir / "frames.gnuplot";
    writeFileAtomically(scriptPath, script);
    std::string command = "gnuplot '" + scriptPath.string() + "' 2>/dev/null";
    if (std::system(command.c_str()) != 0) std::fprintf(stderr, "curette replay: gnuplot failed; frames.csv is still written\n");
}

}  // namespace

int replay(const Arguments& args) {
    CommandLine cl(args, {{"out", true, "directory for PNGs, frames.csv and frames.png"},
                          {"every", true, "render every Nth frame (default 1)"},
                          {"check", false, "verify CAO == LAO per frame, write timing/recompute/hash CSV and a plot"},
                          {"from-reports", false, "re-derive poses from the raw reports and check them"},
                          {"lenient", false, "replay the valid prefix of a damaged session"},
                          {"size", true, "render at WxH instead of the recorded size"},
                          {"no-render", false, "with --from-reports: only check the poses, render nothing"}});
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
    std::filesystem::path scenePath = session.header.scene;
    if (scenePath.is_relative()) scenePath = file.parent_path() / scenePath;
    LoadedScene loaded = loadSceneWithVolume(scenePath);
    bool render = !cl.flag("no-render");
    if (!render && !fromReports) throw InputError("<command line>", "--no-render", "together with --from-reports (otherwise there is nothing to do)");
    std::unique_ptr<gl::Context> context;
    std::unique_ptr<Renderer> renderer;
    if (render) {
        context = gl::createHeadlessContext();
        renderer = std::make_unique<Renderer>(*context, loaded.volume, loaded.scene.transferFunction);
        configureRenderer(loaded, *renderer);
    }
    VolumeGeometry geometry{loaded.volume.dims, loaded.volume.indexToWorld};
    SessionStep step(InteractionState::fromSessionStart(session.header, loaded.scene, scenePath.parent_path(), file.string()),
                     initialFrame(loaded.scene, geometry));
    const InteractionState& state = step.state();

    std::optional<input::InputPipeline> pipeline;
    if (fromReports) {
        pipeline.emplace(input::parseMapping(session.header.mappingJson, file.string() + " line 1: mapping"), session.header.keyboardMmPerSecond,
                         session.header.keyboardDegPerSecond);
        pipeline->restore(session.header.inputState);
    }

    std::string csv = "frame,time_s,render_ms,ao_ms,recomputed_fraction,image_hash,cao_equals_lao\n";
    int rendered = 0, poseMismatches = 0, caoMismatches = 0, checked = 0;
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
            input::KeyboardMouseState keys{f.keys, f.drag};
            step.frame().camera = f.camera;
            step.frame().size = f.size;
            step.apply(pipeline->step(reports, keys, f.dt, static_cast<int>(state.meshes.size())), f.size.y);
            // The re-derived poses (and shading) must be the recorded ones, bit for bit.
            bool same = state.shading == f.shading && samePoses(state.sessionPoses(), f.meshes);
            if (!same && poseMismatches++ == 0)
                std::fprintf(stderr, "curette replay: %s: poses re-derived from the reports differ from the recorded ones\n", where.c_str());
        } else {
            // Follow the recorded poses: meshes added and removed, then every pose.
            step.follow(f, scenePath.parent_path(), where);
        }
        if (!render || n % static_cast<std::size_t>(every) != 0) continue;
        step.syncTo(renderer->clipMeshes());
        FrameDescription frame = step.frame();
        frame.size = size.value_or(f.size);
        frame.shading = f.shading;
        renderer->collectTimings();
        auto start = std::chrono::steady_clock::now();
        renderer->render(frame);
        renderer->finish();
        double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        double aoMs = renderer->collectTimings().ambientOcclusionMs();
        Image image = renderer->readImage();
        std::vector<std::uint8_t> rgba = toRgba8(image, glm::vec4(loaded.scene.background));
        std::string hash = imageHash(rgba);
        double fraction = renderer->ambientOcclusion() && usesAmbientOcclusion(frame.shading) ? renderer->ambientOcclusion()->lastStats().recomputedFraction() : 0.0;
        std::string equal = "-";
        if (check && usesAmbientOcclusion(frame.shading)) {
            // The exactness contract on this frame: the other AO mode under the same clipping.
            std::vector<std::uint16_t> ambient = renderer->ambientOcclusion()->readAmbient();
            FrameDescription other = frame;
            other.shading = frame.shading == ShadingMode::Cao ? ShadingMode::Lao : ShadingMode::Cao;
            renderer->render(other);
            bool same = renderer->ambientOcclusion()->readAmbient() == ambient &&
                        std::memcmp(renderer->readImage().pixels.data(), image.pixels.data(), image.pixels.size() * sizeof(glm::vec4)) == 0;
            equal = same ? "yes" : "NO";
            ++checked;
            if (!same) ++caoMismatches;
            renderer->collectTimings();
        }
        char line[256];
        std::snprintf(line, sizeof line, "%zu,%.4f,%.2f,%.2f,%.6f,%s,%s\n", f.index, f.time, ms, aoMs, fraction, hash.c_str(), equal.c_str());
        csv += line;
        if (out) {
            char name[64];
            std::snprintf(name, sizeof name, "frame_%06zu.png", f.index);
            writePng(*out / name, image, glm::vec4(loaded.scene.background));
        }
        std::printf("frame %6zu  %-5s %8.1f ms  AO %8.1f ms  recomputed %6.2f %%  %s%s\n", f.index, shadingModeName(frame.shading), ms, aoMs,
                    100.0 * fraction, hash.c_str(), equal == "-" ? "" : ("  CAO == LAO: " + equal).c_str());
        ++rendered;
    }
    if (out && check) {
        writeFileAtomically(*out / "frames.csv", csv);
        plot(*out);
        std::printf("wrote %s and %s\n", (*out / "frames.csv").c_str(), (*out / "frames.png").c_str());
    }
    std::printf("replayed %zu frames, rendered %d", session.frames.size(), rendered);
    if (fromReports) std::printf(", poses from reports: %s", poseMismatches ? "DIFFERENT" : "identical to the recorded ones");
    if (checked) std::printf(", CAO == LAO on %d of %d checked frames", checked - caoMismatches, checked);
    std::printf("\n");
    return poseMismatches || caoMismatches ? 1 : 0;
}

}  // namespace curette::commands
