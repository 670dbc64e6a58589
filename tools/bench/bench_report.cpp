// curette bench report: the time of the removal report (session/carve_report.h) for a scene's meshes, by stage,
// with its error against the CPU oracle next to it. Each repeat moves every mesh by 0.5 mm, so each report
// is a new one (the clip maps are not redrawn: a rigid motion changes only the cameras).
//   Table A, time per stage (ms, min / median / max over the repeats after one warm-up):
//     GPU field     removal_count.comp over the meshes' voxel box, read back (render/passes/removal_probe.h)
//     tract flags   clip_probe.comp at every probe point of every bundle, read back
//     tissue, distance transform, structures, intrusion, bundles: computeReport's stages (plan/removal_report.h)
//     total         all of the above: what the viewer waits for after the meshes stop
//   Tables B and C, error of the GPU inputs against the CPU oracle (clip::insideSampleCount and
//   plan::insideFlagsCpu with the winding-number inside test of the same posed meshes), on the last poses:
//     B, field      over `oracle-voxels` voxels drawn from those the GPU or the CPU counts as partly covered
//                   (the only ones that can differ) plus as many drawn from the whole box: mean and max
//                   |count difference| in samples of 9 + N, and the removed volume of the drawn voxels
//                   GPU vs CPU (relative)
//     C, flags      per bundle, probe points whose inside flag differs and streamlines whose cut verdict differs
//   Table D, the report on cases whose answers are known (tools/bench/report_analytic.h): removed volumes
//   against the meshes' exact volumes and margins against analytic gaps, each with its stated uncertainty,
//   its error and the time of its field and report.
#include "tools/bench/bench_report.h"

#include "tools/bench/report.h"
#include "render/model/lao_settings.h"
#include "tools/bench/report_analytic.h"
#include "tools/commands/commands.h"
#include "session/carve_report.h"
#include "session/loaded_scene.h"
#include "session/session_step.h"
#include "base/error.h"
#include "mesh/coverage.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>

namespace curette::bench {

int benchReport(const CommandLine& cl) {
    LoadedScene loaded = loadSceneWithVolume(cl.required("scene"));
    int repeats = CommandLine::parseInt("repeats", cl.valueOr("repeats", "8"), 1, 1000);
    int oracleVoxels = CommandLine::parseInt("oracle-voxels", cl.valueOr("oracle-voxels", "1500"), 0, 10000000);
    std::string jsonPath = cl.valueOr("json", "bench-report.json");
    if (loaded.scene.clipMeshes.empty()) throw InputError(cl.required("scene"), "clip_meshes", "a scene with clip meshes", "none");

    auto context = gl::createHeadlessContext(gpuChoice(cl));
    Renderer renderer(*context, loaded.volume, loaded.scene.transferFunction);
    configureRenderer(loaded, renderer);
    CarveReporter reporter(loaded, renderer.geometry(), commands::programVersion());
    std::size_t probePoints = 0, streamlines = 0;
    for (const plan::BundleInput& b : reporter.bundles()) probePoints += b.probe.points.size(), streamlines += b.tracts->streamlineCount();
    const VolumeData& v = loaded.volume;
    std::printf("curette bench report: %s (%dx%dx%d), %zu meshes, %zu label sets, %zu bundles (%zu streamlines, %zu probe points), %s\n",
                loaded.scene.volumePath.c_str(), v.dims.x, v.dims.y, v.dims.z, loaded.scene.clipMeshes.size(), loaded.labels.size(),
                reporter.bundles().size(), streamlines, probePoints, context->info().renderer.c_str());

    InteractionState state = InteractionState::fromScene(loaded.scene);
    std::map<std::string, std::vector<double>> ms;
    std::vector<std::string> stages{"GPU field", "tract flags", "tissue", "distance transform", "structures", "intrusion", "bundles", "total"};
    plan::Report report;
    for (int r = -1; r < repeats; ++r) {
        for (MeshState& m : state.meshes) m.pose.position += glm::dvec3(0.5, 0.0, 0.0);
        syncClipMeshes(state, renderer.clipMeshes());
        auto start = std::chrono::steady_clock::now();
        report = reporter.compute(renderer.clipMeshes(), state);
        double total = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        if (r < 0) continue;  // warm-up: shader compilation, first map drawing
        const plan::ReportTimings& t = report.timings;
        for (auto [name, value] : std::vector<std::pair<std::string, double>>{
                 {"GPU field", reporter.lastFieldMs()}, {"tract flags", reporter.lastFlagsMs()}, {"tissue", t.tissueMs},
                 {"distance transform", t.distanceMs}, {"structures", t.structuresMs}, {"intrusion", t.intrusionMs},
                 {"bundles", t.bundlesMs}, {"total", total}})
            ms[name].push_back(value);
    }
    Table a("A: removal report, ms per stage over " + std::to_string(repeats) + " repeats (each moves the meshes 0.5 mm)",
            {"stage", "min ms", "median ms", "max ms"});
    for (const std::string& s : stages) {
        std::vector<double>& list = ms[s];
        a.add({s, *std::min_element(list.begin(), list.end()), median(list), *std::max_element(list.begin(), list.end())});
    }
    a.print();
    std::printf("removed %.3f mL, %zu structure rows, %zu warnings\n", report.removedMl, report.structures.size(), report.warnings().size());

    // The oracle on the last poses.
    std::vector<plan::PosedMesh> posed = state.posedMeshes();
    plan::InsideTest inside = plan::insideAnyMesh(posed);
    const plan::RemovalField& field = reporter.lastField();
    int samples = field.samplesPerVoxel;
    std::vector<glm::dvec3> offsets = clip::antiAliasingOffsets(std::max(samples - 9, 1));
    offsets.resize(std::size_t(samples - 9));
    std::mt19937 random(1);
    std::vector<std::size_t> partial;
    for (std::size_t i = 0; i < field.insideSamples.size(); ++i)
        if (field.insideSamples[i] > 0 && field.insideSamples[i] < samples) partial.push_back(i);
    std::shuffle(partial.begin(), partial.end(), random);
    partial.resize(std::min<std::size_t>(partial.size(), std::size_t(oracleVoxels)));
    std::uniform_int_distribution<std::size_t> any(0, field.insideSamples.empty() ? 0 : field.insideSamples.size() - 1);
    std::vector<std::size_t> drawn = partial;
    for (int n = 0; n < oracleVoxels && !field.insideSamples.empty(); ++n) drawn.push_back(any(random));
    double sumAbs = 0, maxAbs = 0, gpuSum = 0, cpuSum = 0;
    for (std::size_t i : drawn) {
        glm::ivec3 local(int(i % std::size_t(field.size.x)), int((i / std::size_t(field.size.x)) % std::size_t(field.size.y)),
                         int(i / (std::size_t(field.size.x) * std::size_t(field.size.y))));
        int cpu = clip::insideSampleCount(inside, field.indexToWorld, glm::dvec3(field.origin + local), offsets);
        double d = std::abs(double(cpu) - double(field.insideSamples[i]));
        sumAbs += d, maxAbs = std::max(maxAbs, d);
        gpuSum += field.insideSamples[i], cpuSum += cpu;
    }
    Table b("B: GPU removal field vs the CPU winding-number oracle (last poses; counts of " + std::to_string(samples) + " samples)",
            {"voxels compared", "mean |count diff|", "max |count diff|", "removed volume GPU/CPU - 1"});
    b.add({static_cast<double>(drawn.size()), drawn.empty() ? 0.0 : sumAbs / double(drawn.size()), maxAbs, cpuSum > 0 ? (gpuSum - cpuSum) / cpuSum : 0.0});
    Table c("C: GPU tract flags vs the CPU winding-number oracle (last poses)",
            {"bundle", "probe points", "points differing", "streamlines", "cut verdicts differing"});
    for (const plan::BundleInput& bundle : reporter.bundles()) {
        std::vector<std::uint8_t> cpu = plan::insideFlagsCpu(bundle.probe.points, inside);
        std::size_t differ = 0, verdicts = 0;
        for (std::size_t i = 0; i < cpu.size(); ++i) differ += cpu[i] != bundle.probe.insideFlags[i];
        for (std::size_t s = 0; s + 1 < bundle.probe.streamlineOffsets.size(); ++s) {
            bool gpuCut = false, cpuCut = false;
            for (std::uint32_t p = bundle.probe.streamlineOffsets[s]; p < bundle.probe.streamlineOffsets[s + 1]; ++p)
                gpuCut = gpuCut || bundle.probe.insideFlags[p], cpuCut = cpuCut || cpu[p];
            verdicts += gpuCut != cpuCut;
        }
        c.add({bundle.name, static_cast<double>(cpu.size()), static_cast<double>(differ),
               static_cast<double>(bundle.probe.streamlineOffsets.size() - 1), static_cast<double>(verdicts)});
    }
    b.print();
    c.print();
    Table d("D: the report on analytic cases (volumes mL, margins mm)",
            {"kind", "grid", "case", "exact", "reported", "+-", "error", "error %", "image's N: error %", "image - report %", "ms"});
    double worstVolume = 0, worstMargin = 0, worstImage = 0, worstImageVsReport = 0;
    for (const AnalyticCase& x : analyticReportCases(*context)) {
        const bool volume = x.kind == "volume";
        const double relative = volume ? 100.0 * x.error() / x.exact : 0.0;
        (volume ? worstVolume : worstMargin) = std::max(volume ? worstVolume : worstMargin, volume ? std::abs(relative) : std::abs(x.error()));
        const double image = volume ? 100.0 * (x.atImageSamples - x.exact) / x.exact : 0.0;
        const double imageVsReport = volume ? 100.0 * (x.atImageSamples - x.reported) / x.reported : 0.0;
        if (volume) worstImage = std::max(worstImage, std::abs(image)), worstImageVsReport = std::max(worstImageVsReport, std::abs(imageVsReport));
        d.add({x.kind, x.grid, x.name + (x.wallTouched ? " (touched)" : ""), x.exact, x.reported, x.uncertainty, x.error(),
               volume ? nlohmann::json(relative) : nlohmann::json("-"), volume ? nlohmann::json(image) : nlohmann::json("-"),
               volume ? nlohmann::json(imageVsReport) : nlohmann::json("-"), x.ms});
    }
    d.print();
    std::printf("analytic cases: worst volume error %.3f %%, worst margin error %.3f mm; the image's coverage (N = %d): worst "
                "volume error %.3f %%, worst difference from the report %.3f %%\n",
                worstVolume, worstMargin, LaoSettings{}.antiAliasingSamples, worstImage, worstImageVsReport);
    nlohmann::json doc;
    doc["scene"] = cl.required("scene");
    doc["renderer"] = context->info().renderer;
    doc["removed_ml"] = report.removedMl;
    doc["tables"] = {a.toJson(), b.toJson(), c.toJson(), d.toJson()};
    doc["analytic_worst_volume_error_percent"] = worstVolume;
    doc["analytic_worst_margin_error_mm"] = worstMargin;
    doc["analytic_worst_image_volume_error_percent"] = worstImage;
    doc["analytic_worst_image_vs_report_percent"] = worstImageVsReport;
    writeJson(jsonPath, doc);
    return 0;
}

}  // namespace curette::bench
