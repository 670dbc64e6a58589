// curette bench tracts (issue 12): tracts at whole-brain scale. For the first N streamlines of the scene's
// tube entries, at several N, as illuminated lines, as tubes built on the CPU and as tubes expanded on the GPU
// (render/passes/gpu_tube_builder.h): the CPU time of each build step, the upload (or GPU expansion) time, the GPU
// memory of the vertex streams (Renderer::gpuAllocations), vertices and primitives, and the median frame time
// of an orbiting camera in each shading mode asked for, with the tube G-buffer pass's share. Next to the
// GPU-built tubes, their error against the CPU-built ones: the largest vertex distance and normal difference,
// whether indices and colours are identical, and the largest pixel difference of the rendered images. Impostor
// tubes (render/model/tube_impostors.h) beside them, with their image error against the CPU-built triangle
// tubes. With --million FILE, first a tractogram of about a million streamlines as impostors: its load time,
// the process's peak memory, the GPU bytes and one frame per mode.
#include "tools/bench/bench_tracts.h"

#include "tools/bench/report.h"
#include "session/loaded_scene.h"
#include "base/error.h"
#include "render/renderer.h"
#include "io/tract_file.h"

#include <sys/resource.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <set>
#include <sstream>

namespace curette::bench {

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) { return std::chrono::duration<double, std::milli>(Clock::now() - start).count(); }

// The first `count` streamlines of `t` (all of them when it has fewer).
Tractogram prefix(const Tractogram& t, std::size_t count) {
    if (count >= t.streamlineCount()) return t;
    Tractogram p;
    p.source = t.source;
    p.offsets.assign(t.offsets.begin(), t.offsets.begin() + static_cast<std::ptrdiff_t>(count) + 1);
    p.points.assign(t.points.begin(), t.points.begin() + p.offsets.back());
    return p;
}

std::size_t tubeBytes(const Renderer& renderer) {
    for (const GpuAllocation& a : renderer.gpuAllocations())
        if (a.resource == Resource::TubeGeometry) return a.bytes;
    return 0;
}

struct Frames {
    std::vector<double> ms, gbufferMs;   // per shading mode: median frame time, median tube G-buffer pass time
    std::vector<Image> images;           // per mode: the first frame of the orbit
};

// Orbits the camera 4 degrees a frame: one warm-up frame (unless `warmUp` is false: a frame of minutes needs
// none), then `frames` timed ones, per mode.
Frames measureFrames(Renderer& renderer, const FrameDescription& base, const std::vector<ShadingMode>& modes, int frames, bool warmUp = true) {
    Frames out;
    for (ShadingMode mode : modes) {
        std::vector<double> wall, gbuffer;
        for (int f = warmUp ? -1 : 0; f < frames; ++f) {
            FrameDescription frame = base;
            frame.shading = mode;
            frame.camera.azimuthDeg += 4.0 * (f + 1);
            renderer.collectTimings();
            auto start = Clock::now();
            renderer.render(frame);
            renderer.finish();
            double ms = msSince(start);
            FrameTimings timings = renderer.collectTimings();
            if (f == (warmUp ? -1 : 0)) out.images.push_back(renderer.readImage());   // the first frame of the orbit
            if (f < 0) continue;
            wall.push_back(ms);
            gbuffer.push_back(timings.ms(Pass::TubeGBuffer));
        }
        out.ms.push_back(median(wall));
        out.gbufferMs.push_back(median(gbuffer));
    }
    return out;
}

// The largest difference of any channel between two images, in 8-bit levels, and how many pixels differ by
// more than one level.
std::pair<double, std::size_t> imageDifference(const Image& a, const Image& b) {
    double worst = 0;
    std::size_t differing = 0;
    for (std::size_t i = 0; i < a.pixels.size() && i < b.pixels.size(); ++i) {
        double d = 0;
        for (int c = 0; c < 4; ++c) d = std::max(d, std::abs(double(a.pixels[i][c]) - double(b.pixels[i][c])));
        worst = std::max(worst, d);
        differing += 255.0 * d > 1.0;
    }
    return {255.0 * worst, differing};
}

struct VertexDifference {
    double positionMm = 0, direction = 0;
    bool indicesEqual = true, colorsEqual = true;
};

// The GPU set read back a million vertices at a time against the CPU-built vertices.
VertexDifference vertexDifference(const TubeSet& gpu, const TubeVertices& cpu) {
    VertexDifference d;
    if (gpu.vertexCount() != cpu.positions.size() || gpu.triangleCount() * 3 != cpu.indices.size()) return {1e30, 1e30, false, false};
    const std::size_t chunk = 1 << 20;
    for (std::size_t first = 0; first < cpu.positions.size(); first += chunk) {
        std::size_t n = std::min(chunk, cpu.positions.size() - first);
        TubeVertices back = gpu.readBack(first, n, 0, 0);
        for (std::size_t i = 0; i < n; ++i) {
            d.positionMm = std::max(d.positionMm, double(glm::distance(back.positions[i], cpu.positions[first + i])));
            d.direction = std::max(d.direction, double(glm::distance(back.directions[i], cpu.directions[first + i])));
            d.colorsEqual = d.colorsEqual && back.colors[i] == cpu.colors[first + i];
        }
    }
    for (std::size_t first = 0; first < cpu.indices.size(); first += chunk) {
        std::size_t n = std::min(chunk, cpu.indices.size() - first);
        TubeVertices back = gpu.readBack(0, 0, first, n);
        d.indicesEqual = d.indicesEqual && std::equal(back.indices.begin(), back.indices.end(), cpu.indices.begin() + static_cast<std::ptrdiff_t>(first));
    }
    return d;
}

// The process's peak resident memory so far (getrusage: kilobytes on Linux), MiB.
double peakMemoryMiB() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return double(usage.ru_maxrss) / 1024.0;
}

}  // namespace

int benchTracts(const CommandLine& cl) {
    std::string scenePath = cl.valueOr("scene", "assets/scenes/tracts-100k.json");
    LoadedScene loaded = loadSceneWithVolume(scenePath);
    if (loaded.scene.tubes.empty()) throw InputError(scenePath, "tubes", "a scene with tubes (e.g. assets/scenes/tracts-100k.json)", "none");
    std::vector<int> counts = CommandLine::parseIntList("counts", cl.valueOr("counts", "1000,10000,100000"), 1, 50'000'000);
    glm::ivec2 size = CommandLine::parseSize("size", cl.valueOr("size", "512x512"));
    int frames = CommandLine::parseInt("frames", cl.valueOr("frames", "3"), 1, 1000);
    std::vector<ShadingMode> modes = parseShadingList("modes", cl.valueOr("modes", "phong,dos"));
    std::string jsonPath = cl.valueOr("json", "bench-tracts.json");
    std::optional<std::string> imageDir = cl.value("images");
    std::optional<std::string> millionPath = cl.value("million");
    std::set<std::string> geometries;
    const std::string geometryList = cl.valueOr("geometries", "lines,cpu,gpu,impostor");
    for (std::size_t start = 0;;) {
        std::size_t comma = geometryList.find(',', start);
        std::string g = geometryList.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        if (g != "lines" && g != "cpu" && g != "gpu" && g != "impostor")
            throw InputError("<command line>", "--geometries", "a comma-separated list of lines, cpu, gpu, impostor", "\"" + g + "\"");
        geometries.insert(g);
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    auto measures = [&](const char* g) { return geometries.count(g) > 0; };

    auto context = gl::createHeadlessContext(gpuChoice(cl));
    Renderer renderer(*context, loaded.volume, loaded.scene.transferFunction);
    // Volume, labels and clip meshes as every command sets them up; the tubes are set per count below.
    std::vector<Tractogram> full = std::move(loaded.tracts);
    std::vector<SceneTubes> entries = loaded.scene.tubes;
    loaded.scene.tubes.clear();
    loaded.tracts.clear();
    configureRenderer(loaded, renderer);
    loaded.scene.tubes = entries;
    FrameDescription base = initialFrame(loaded.scene, renderer.geometry());
    base.size = size;
    const TubeShading shading = sceneTubeShading(loaded.scene.tubes, loaded.scene.tubeShading);
    std::size_t available = 0;
    for (const Tractogram& t : full) available += t.streamlineCount();
    std::string modeNames;
    for (ShadingMode m : modes) modeNames += (modeNames.empty() ? "" : ", ") + std::string(shadingModeName(m));
    std::printf("curette bench tracts: %s, %zu streamlines in %zu tube entries, %dx%d, %s; median of %d frames orbiting 4 degrees a frame "
                "(after one warm-up), modes %s\n",
                scenePath.c_str(), available, entries.size(), size.x, size.y, context->info().renderer.c_str(), frames, modeNames.c_str());
    const SceneTubes& first = entries.front();
    char settings[200];
    std::snprintf(settings, sizeof settings, "radius %.2f mm, %d sides, step %.2f mm, %s, caps %s", first.settings.radiusMm, first.settings.sides,
                  first.settings.stepMm, first.settings.smoothing == TubeSettings::Smoothing::CatmullRom ? "Catmull-Rom" : "no smoothing",
                  first.settings.caps ? "on" : "off");

    std::vector<std::string> columns = {"streamlines", "geometry", "load ms", "CPU sweep ms", "CPU expand ms", "upload / GPU build ms", "build total ms", "peak MiB",
                                        "GPU MiB", "bytes/streamline", "vertices", "primitives"};
    for (ShadingMode m : modes) {
        columns.push_back(std::string(shadingModeName(m)) + " ms/frame");
        columns.push_back(std::string(shadingModeName(m)) + " G-buffer ms");
    }
    columns.insert(columns.end(), {"max vertex error mm vs CPU", "max normal error vs CPU", "indices+colours equal", "max image diff vs CPU (8-bit)",
                                        "% pixels > 1 level off", "pixels > 1 level off"});
    Table table("Tracts at whole-brain scale (" + std::string(settings) + " for the first entry)", columns);
    nlohmann::json rows = nlohmann::json::array();

    auto addRow = [&](std::size_t streamlines, const std::string& geometry, nlohmann::json sweepMs, nlohmann::json expandMs, double uploadMs,
                      double totalMs, std::size_t vertices, std::size_t primitives, const Frames& f, nlohmann::json error,
                      nlohmann::json normalError, nlohmann::json equal, nlohmann::json imageDiff, nlohmann::json differingShare,
                      nlohmann::json differing = nlohmann::json(), nlohmann::json loadMs = nlohmann::json()) {
        std::size_t bytes = tubeBytes(renderer);
        double peak = peakMemoryMiB();
        std::vector<nlohmann::json> cells = {streamlines, geometry, loadMs, sweepMs, expandMs, uploadMs, totalMs, peak, double(bytes) / (1 << 20),
                                             double(bytes) / double(std::max<std::size_t>(streamlines, 1)), vertices, primitives};
        for (std::size_t m = 0; m < modes.size(); ++m) cells.push_back(f.ms[m]), cells.push_back(f.gbufferMs[m]);
        cells.insert(cells.end(), {error, normalError, equal, imageDiff, differingShare, differing});
        table.add(cells);
        // Each row as soon as it is measured (a 100k run takes a while; the table follows at the end).
        std::printf("    %s: build %.0f ms, %.1f MiB, %zu vertices", geometry.c_str(), totalMs, double(bytes) / (1 << 20), vertices);
        for (std::size_t m = 0; m < modes.size(); ++m) std::printf(", %s %.0f ms/frame (G-buffer %.0f)", shadingModeName(modes[m]), f.ms[m], f.gbufferMs[m]);
        std::printf("\n");
        std::fflush(stdout);
        nlohmann::json row = {{"streamlines", streamlines}, {"geometry", geometry}, {"gpu_bytes", bytes}, {"vertices", vertices},
                              {"primitives", primitives}, {"cpu_sweep_ms", sweepMs}, {"cpu_expand_ms", expandMs},
                              {"upload_or_gpu_build_ms", uploadMs}, {"build_total_ms", totalMs},
                              {"bytes_per_streamline", double(bytes) / double(std::max<std::size_t>(streamlines, 1))},
                              {"max_vertex_error_mm", error}, {"max_normal_error", normalError}, {"indices_and_colors_equal", equal},
                              {"max_image_difference_8bit", imageDiff}, {"percent_pixels_over_one_level", differingShare},
                              {"pixels_over_one_level", differing}, {"load_ms", loadMs}, {"peak_memory_mib", peak}};
        for (std::size_t m = 0; m < modes.size(); ++m) {
            row["frame_ms"][shadingModeName(modes[m])] = f.ms[m];
            row["gbuffer_ms"][shadingModeName(modes[m])] = f.gbufferMs[m];
        }
        rows.push_back(row);
    };
    auto writeImages = [&](const Frames& f, const std::string& name) {
        if (!imageDir) return;
        std::filesystem::create_directories(*imageDir);
        for (std::size_t m = 0; m < modes.size(); ++m)
            writePng(std::filesystem::path(*imageDir) / (name + "-" + shadingModeName(modes[m]) + ".png"), f.images[m], glm::vec4(loaded.scene.background));
    };

    // About a million streamlines as impostors, first, so the peak memory is this case's own.
    if (millionPath) {
        std::printf("  %s: load ...\n", millionPath->c_str());
        std::fflush(stdout);
        auto start = Clock::now();
        loaded.tracts = {io::readTractogram(*millionPath)};
        double loadMs = msSince(start);
        double loadPeak = peakMemoryMiB();
        std::size_t streamlines = loaded.tracts.front().streamlineCount();
        std::vector<SceneTubes> one = {entries.front()};
        one.front().path = *millionPath;
        start = Clock::now();
        TubeImpostors impostors = sceneTubeImpostors(one, loaded.tracts);
        double sweepMs = msSince(start);
        loaded.tracts.clear();
        std::size_t points = impostors.points.size();
        start = Clock::now();
        renderer.setTubeImpostors(impostors, sceneTubeShading(one, loaded.scene.tubeShading));
        renderer.finish();
        double uploadMs = msSince(start);
        impostors = {};
        std::printf("    loaded in %.0f ms (peak %.0f MiB after loading)\n", loadMs, loadPeak);
        Frames f = measureFrames(renderer, base, modes, 1, false);
        addRow(streamlines, "impostors (" + std::filesystem::path(*millionPath).extension().string() + ")", sweepMs, nlohmann::json(), uploadMs,
               sweepMs + uploadMs, points, points, f, nlohmann::json(), nlohmann::json(), nlohmann::json(), nlohmann::json(), nlohmann::json(),
               nlohmann::json(), loadMs);
        writeImages(f, std::to_string(streamlines) + "-impostors");
        renderer.clearTubes();
    }

    for (int count : counts) {
        loaded.tracts.clear();
        std::size_t streamlines = 0;
        for (const Tractogram& t : full) {
            loaded.tracts.push_back(prefix(t, static_cast<std::size_t>(count)));
            streamlines += loaded.tracts.back().streamlineCount();
        }
        std::string tag = std::to_string(streamlines);
        nlohmann::json none;

        if (measures("lines")) {   // illuminated lines, built on the CPU
            std::printf("  %zu streamlines: lines ...\n", streamlines);
            std::fflush(stdout);
            auto start = Clock::now();
            TubeVertices lines = sceneTubeVertices(loaded.scene.tubes, true, loaded.tracts);
            double linesBuildMs = msSince(start);
            std::size_t lineVertices = lines.positions.size(), segments = lines.indices.size() / 2;
            start = Clock::now();
            renderer.setTubes(lines, shading);
            renderer.finish();
            double linesUploadMs = msSince(start);
            lines = {};
            Frames lineFrames = measureFrames(renderer, base, modes, frames);
            addRow(streamlines, "lines (CPU)", linesBuildMs, none, linesUploadMs, linesBuildMs + linesUploadMs, lineVertices, segments, lineFrames,
                   none, none, none, none, none);
            writeImages(lineFrames, tag + "-lines");
            renderer.clearTubes();
        }

        // Tubes: one sweep, expanded on the CPU (the oracle) ...
        TubeRings rings;
        TubeVertices cpuTubes;
        Frames cpuFrames;
        double sweepMs = 0;
        if (measures("cpu") || measures("gpu")) {
            auto start = Clock::now();
            rings = sceneTubeRings(loaded.scene.tubes, loaded.tracts);
            sweepMs = msSince(start);
        }
        if (measures("cpu")) {
            std::printf("  %zu streamlines: tubes built on the CPU ...\n", streamlines);
            std::fflush(stdout);
            auto start = Clock::now();
            cpuTubes = expandTubeRings(rings);
            double expandMs = msSince(start);
            start = Clock::now();
            renderer.setTubes(cpuTubes, shading);
            renderer.finish();
            double uploadMs = msSince(start);
            cpuFrames = measureFrames(renderer, base, modes, frames);
            addRow(streamlines, "tubes (CPU)", sweepMs, expandMs, uploadMs, sweepMs + expandMs + uploadMs, cpuTubes.positions.size(),
                   cpuTubes.indices.size() / 3, cpuFrames, none, none, none, none, none);
            writeImages(cpuFrames, tag + "-tubes-cpu");
            renderer.clearTubes();
        }
        // The image error of another geometry against the CPU-built tubes: the largest over the modes.
        auto errorAgainstCpu = [&](const Frames& f) {
            std::array<nlohmann::json, 3> e;
            if (cpuFrames.images.empty()) return e;
            double imageDiff = 0, differingShare = 0;
            std::size_t differingMost = 0;
            for (std::size_t m = 0; m < modes.size(); ++m) {
                auto [worst, differing] = imageDifference(f.images[m], cpuFrames.images[m]);
                imageDiff = std::max(imageDiff, worst);
                differingMost = std::max(differingMost, differing);
                differingShare = std::max(differingShare, 100.0 * double(differing) / double(size.x * size.y));
            }
            return std::array<nlohmann::json, 3>{imageDiff, differingShare, differingMost};
        };

        if (measures("gpu")) {   // ... and on the GPU, against it
            std::printf("  %zu streamlines: tubes built on the GPU ...\n", streamlines);
            std::fflush(stdout);
            auto start = Clock::now();
            renderer.setTubeRings(rings, shading);
            renderer.finish();
            double gpuBuildMs = msSince(start);
            std::size_t vertices = rings.vertexCount, triangles = rings.indexCount / 3;
            rings = {};
            Frames gpuFrames = measureFrames(renderer, base, modes, frames);
            nlohmann::json positionError, normalError, equal;
            if (measures("cpu")) {
                VertexDifference difference = vertexDifference(*renderer.tubes(), cpuTubes);
                positionError = difference.positionMm, normalError = difference.direction;
                equal = difference.indicesEqual && difference.colorsEqual ? "yes" : "NO";
            }
            auto [imageDiff, differingShare, differing] = errorAgainstCpu(gpuFrames);
            addRow(streamlines, "tubes (GPU)", "(same sweep)", none, gpuBuildMs, sweepMs + gpuBuildMs, vertices, triangles, gpuFrames, positionError,
                   normalError, equal, imageDiff, differingShare, differing);
            writeImages(gpuFrames, tag + "-tubes-gpu");
            renderer.clearTubes();
        }
        rings = {};
        cpuTubes = {};

        if (measures("impostor")) {   // impostors: the sweep's points alone, ray-cast on quads
            std::printf("  %zu streamlines: impostor tubes ...\n", streamlines);
            std::fflush(stdout);
            auto start = Clock::now();
            TubeImpostors impostors = sceneTubeImpostors(loaded.scene.tubes, loaded.tracts);
            double impostorSweepMs = msSince(start);
            std::size_t points = impostors.points.size();
            start = Clock::now();
            renderer.setTubeImpostors(impostors, shading);
            renderer.finish();
            double uploadMs = msSince(start);
            impostors = {};
            Frames impostorFrames = measureFrames(renderer, base, modes, frames);
            auto [imageDiff, differingShare, differing] = errorAgainstCpu(impostorFrames);
            addRow(streamlines, "impostors", impostorSweepMs, none, uploadMs, impostorSweepMs + uploadMs, points, points, impostorFrames, none, none,
                   none, imageDiff, differingShare, differing);
            writeImages(impostorFrames, tag + "-impostors");
            renderer.clearTubes();
        }
    }
    table.print();
    std::printf("columns: CPU sweep = cleaning, Catmull-Rom resampling, rotation-minimising frames and colours of every ring "
                "(lines: the whole line build); CPU expand = rings to vertices and indices on the CPU; upload / GPU build = "
                "Renderer::setTubes until the GPU is idle (for GPU-built tubes: ring upload and the expansion shader); GPU MiB and "
                "bytes/streamline = the tube vertex streams as Renderer::gpuAllocations reports them; primitives = segments "
                "(lines) or triangles (impostors: vertices and primitives = points, a segment each); load ms = reading the --million file; "
                "peak MiB = the process's peak resident memory after the row (getrusage); ms/frame = wall time of a whole frame (median); G-buffer ms = the tube G-buffer pass's GPU "
                "time in it; errors = GPU-built tubes read back against the CPU-built ones (images: the first frame of each mode, "
                "largest channel difference in 8-bit levels, and the share of pixels more than one level off: where nearly coincident "
                "tubes of jittered copies tie in depth, a 1e-5 mm shift picks the other tube's colour); impostors: their images against the "
                "CPU-built triangle tubes' (the prism's facets and smooth normals against the exact cylinder, RGB8 colours)\n");
    writeJson(jsonPath, {{"bench", "tracts"}, {"scene", scenePath}, {"size", {size.x, size.y}}, {"frames", frames},
                         {"renderer", context->info().renderer}, {"tube_settings", settings}, {"rows", rows}, {"tables", {table.toJson()}}});
    return 0;
}

}  // namespace curette::bench
