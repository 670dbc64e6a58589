// curette bench cao: Contextual Ambient Occlusion against full LAO recompute on a scene's volume with a
// sphere moving along a fixed, seeded path (and optionally a second, overlapping one), printing the
// paper's tables (seed 002: Table 2 recompute fraction, Table 3 frame times and speedup, Fig. 10 time per
// step, Table 4 second-mesh slowdown) beside ours, with the error against a 512-ray ground truth next to
// the timings and whether CAO was bit-identical to LAO on every frame.
#include "tools/bench/bench_cao.h"

#include "tools/bench/lao_options.h"
#include "tools/bench/report.h"
#include "session/loaded_scene.h"
#include "session/session_step.h"
#include "base/error.h"
#include "gl/bindings.h"
#include "mesh/primitives.h"
#include "render/reference/lao_reference.h"
#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <random>

namespace curette::bench {

namespace {

using Clock = std::chrono::steady_clock;

// The paper's measurements (seed 002, Tables 2-4), for the side-by-side columns.
struct PaperRow {
    int rays;
    double engineSpeedup, beetleSpeedup, skeletonSpeedup;
    double engineSlowdown, skeletonSlowdown;  // Table 4, % for a second mesh
};
const PaperRow kPaper[] = {{6, 1.66, 2.75, 4.06, 14.3, 10.3},
                           {14, 2.29, 3.41, 4.75, 14.6, 8.3},
                           {26, 2.95, 3.83, 5.18, 15.3, 9.7},
                           {54, 3.79, 4.24, 5.34, 15.7, 10.5}};

std::uint64_t hashWords(const std::vector<std::uint16_t>& values) {
    std::uint64_t h = 1469598103934665603ull;
    for (std::uint16_t v : values) {
        h ^= v;
        h *= 1099511628211ull;
    }
    return h;
}

// The seeded motion path: the sphere's centre sweeps a Lissajous curve around a point on the volume's
// surface region, so every frame carves and every frame moves.
glm::dvec3 pathPoint(const VolumeGeometry& g, int frame, std::uint32_t seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    double a = 1 + 2 * u(random), b = 1 + 2 * u(random), phase = 6.283 * u(random);
    double radius = g.boundingRadiusMm();
    glm::dvec3 centre = g.worldCenter() + glm::dvec3(0.0, 0.35 * radius, 0.25 * radius);
    double t = 0.35 * frame;
    return centre + 0.18 * radius * glm::dvec3(std::sin(a * t + phase), std::sin(b * t), std::cos(t));
}

// One measured frame of one configuration.
struct FrameSample {
    double ms = 0;                          // wall time of the frame (render and finish)
    std::map<std::string, double> stepMs;   // GPU time per pass name (render/model/frame_plan.h)
    AmbientOcclusionStats stats;
    std::uint64_t aoHash = 0, imageHash = 0;
};

struct ModeResult {
    double msPerFrame = 0;
    double msSpread = 0;                   // half the range of the frame times (min..max) around the median
    std::map<std::string, double> stepMs;  // median per step name
    double recomputedFraction = 0;
    double visitedFraction = 0;   // voxels steps IV and V visited (the bricks where the meshes' dilated boxes and reach balls meet)
    double visitedVoxels = 0;     // the same as a count, mean over frames
    double laoBrickFraction = 0;  // of the visited bricks, those where LAO can change (render/model/lao_reach.h)
    std::vector<std::uint64_t> aoHashes, imageHashes;
    std::vector<double> frameMs;
};

ModeResult summarize(const std::vector<FrameSample>& samples) {
    ModeResult result;
    if (samples.empty()) return result;
    std::map<std::string, std::vector<double>> steps;
    double fractions = 0, visited = 0, visitedVoxels = 0, laoBricks = 0;
    for (const FrameSample& s : samples) {
        result.frameMs.push_back(s.ms);
        for (const auto& [name, ms] : s.stepMs) steps[name].push_back(ms);
        if (s.stats.voxels) {
            fractions += s.stats.recomputedFraction();
            visited += static_cast<double>(s.stats.dispatched) / static_cast<double>(s.stats.voxels);
            visitedVoxels += static_cast<double>(s.stats.dispatched);
            laoBricks += s.stats.bricks ? static_cast<double>(s.stats.laoBricks) / static_cast<double>(s.stats.bricks) : 0.0;
            result.aoHashes.push_back(s.aoHash);
        }
        result.imageHashes.push_back(s.imageHash);
    }
    double n = static_cast<double>(samples.size());
    result.msPerFrame = median(result.frameMs);
    result.msSpread = 0.5 * (*std::max_element(result.frameMs.begin(), result.frameMs.end()) -
                             *std::min_element(result.frameMs.begin(), result.frameMs.end()));
    for (auto& [name, list] : steps) result.stepMs[name] = median(list);
    result.recomputedFraction = fractions / n;
    result.visitedFraction = visited / n;
    result.visitedVoxels = visitedVoxels / n;
    result.laoBrickFraction = laoBricks / n;
    return result;
}

// Accuracy next to speed: V_AO of the last CAO frame (equal to full LAO's) against the 512-ray CPU ground
// truth on the GPU's own clipped V_o (Table 5's measure, on a random sample of visible voxels). Two samples:
// visible voxels anywhere (most far from the cut, where CAO copies V_PAO), and the voxels of category b (near
// the cut).
struct GroundTruthRms {
    double visible = 0, recomputed = 0;
};

GroundTruthRms groundTruthRms(const Renderer& renderer, const LoadedScene& loaded, const LaoSettings& lao, int groundTruthVoxels,
                              std::uint32_t seed) {
    const VolumeGeometry& g = renderer.geometry();
    const VolumeData& v = loaded.volume;
    const AmbientOcclusion* ao = renderer.ambientOcclusion();
    std::vector<std::uint16_t> opacity = ao->readOpacity(), ambient = ao->readAmbient();
    std::vector<std::uint8_t> mask = ao->readMask();
    reference::Grid grid;
    grid.dims = g.dims;
    for (std::uint16_t o : opacity) grid.values.push_back(o / 65535.0);
    LaoDirectionSet truth;
    parseLaoPattern("fibonacci:512", truth);
    reference::LaoParameters p{truth.build(), lao.samples, lao.stepMm, loaded.scene.transferFunction.unitLengthMm};
    auto sampleRms = [&](bool recomputedOnly) {
        std::mt19937 random(seed);
        double sum = 0;
        int used = 0;
        for (int attempts = 0; used < groundTruthVoxels && attempts < 1000 * groundTruthVoxels; ++attempts) {
            glm::ivec3 voxel(random() % g.dims.x, random() % g.dims.y, random() % g.dims.z);
            std::size_t index = v.linearIndex(voxel.x, voxel.y, voxel.z);
            if (mask[index] == binding::categoryClipped || opacity[index] == 0) continue;  // visible, non-empty tissue
            if (recomputedOnly && mask[index] != binding::categoryAffected) continue;
            double expected = reference::localAmbientOcclusion(grid, g.worldToTexture(), g.indexToWorld, voxel, p);
            double d = ambient[index] / 65535.0 - expected;
            sum += d * d;
            ++used;
        }
        return used ? std::sqrt(sum / used) : 0.0;
    };
    GroundTruthRms rms;
    rms.visible = sampleRms(false);
    rms.recomputed = sampleRms(true);
    return rms;
}

using Series = std::map<int, std::map<ShadingMode, std::vector<FrameSample>>>;  // meshes -> mode -> frames

// The renderers, the meshes and the motion path every configuration runs on.
struct CaoBench {
    const LoadedScene& loaded;
    int frames = 0;
    bool secondStill = false;
    std::uint32_t seed = 0;
    // One renderer per mesh count and AO mode (cao, lao; solid frames run on the cao one, they touch no AO
    // volume): each renderer's frames follow its own previous frame, as in a session, so a CAO frame visits
    // this and the last pose's bricks and redraws no map.
    std::map<std::pair<ShadingMode, int>, std::unique_ptr<Renderer>> renderers;
    FrameDescription base;
    double sphereRadius = 0;
    std::shared_ptr<const clip::TriangleMesh> sphere, secondSphere;
    // The meshes reach the renderer through the session step, as in every command.
    std::map<Renderer*, InteractionState> states;

    CaoBench(gl::Context& context, const LoadedScene& scene, const std::vector<int>& meshCounts, bool depthBoxTests, glm::ivec2 size)
        : loaded(scene) {
        for (int meshes : meshCounts)
            for (ShadingMode mode : {ShadingMode::Cao, ShadingMode::Lao}) {
                auto& r = renderers[{mode, meshes}];
                r = std::make_unique<Renderer>(context, loaded.volume, loaded.scene.transferFunction);
                configureRenderer(loaded, *r);
                r->clipMeshes().setDepthBoxTests(depthBoxTests);
                // Every frame's ray cast covers the whole image, like for like: the solid frames in between would keep
                // the cao renderer from keeping pixels, not the lao one (Renderer::setRecastOnlyChangedPixels).
                r->setRecastOnlyChangedPixels(false);
            }
        base = initialFrame(loaded.scene, geometry());
        base.size = size;
        sphereRadius = 0.14 * geometry().boundingRadiusMm();
        sphere = std::make_shared<const clip::TriangleMesh>(clip::makeSphere(sphereRadius, 4));
        secondSphere = std::make_shared<const clip::TriangleMesh>(clip::makeSphere(0.8 * sphereRadius, 4));
    }

    const VolumeGeometry& geometry() const { return renderers.begin()->second->geometry(); }
    Renderer& rendererFor(ShadingMode mode, int meshes) {
        return *renderers.at({mode == ShadingMode::Lao ? ShadingMode::Lao : ShadingMode::Cao, meshes});
    }
    void setMeshes(Renderer& renderer, int count, int frame);
    FrameSample renderOne(int meshes, ShadingMode mode, int frame);
    Series runInterleaved(const std::vector<int>& counts, bool withSolidAndLao);
};

void CaoBench::setMeshes(Renderer& renderer, int count, int frame) {
    const VolumeGeometry& g = geometry();
    InteractionState& state = states[&renderer];
    if (static_cast<int>(state.meshes.size()) != count) {
        state.meshes.clear();
        for (int i = 0; i < count; ++i)
            state.meshes.push_back(MeshState::make(i, {.name = i == 0 ? "moving sphere" : "second sphere", .geometry = i == 0 ? sphere : secondSphere}));
    }
    glm::dvec3 p = pathPoint(g, frame, seed);
    state.meshes[0].pose = clip::RigidPose{p, {}};
    // The second sphere overlaps the first (as in the paper's Table 4 scenes) and moves with it, or stays where
    // it overlaps the first at the path's start (--second-mesh still: an update leaves it alone).
    glm::dvec3 second = (secondStill ? pathPoint(g, 0, seed) : p) + glm::dvec3(0.9 * sphereRadius, 0.0, 0.3 * sphereRadius);
    if (count == 2) state.meshes[1].pose = clip::RigidPose{second, {}};
    syncClipMeshes(state, renderer.clipMeshes());
}

// One frame of one configuration at path position `frame`.
FrameSample CaoBench::renderOne(int meshes, ShadingMode mode, int frame) {
    Renderer& renderer = rendererFor(mode, meshes);
    FrameSample sample;
    FrameDescription description = base;
    description.shading = mode;
    setMeshes(renderer, meshes, frame);
    renderer.finish();
    renderer.collectTimings();
    auto start = Clock::now();
    renderer.render(description);
    renderer.finish();
    sample.ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    for (const FrameTimings::Entry& e : renderer.collectTimings().passes) sample.stepMs[passInfo(e.pass).name] += e.ms;
    if (mode != ShadingMode::Solid && renderer.ambientOcclusion()) {
        sample.stats = renderer.ambientOcclusion()->lastStats();
        sample.aoHash = hashWords(renderer.ambientOcclusion()->readAmbient());
    }
    Image image = renderer.readImage();
    sample.imageHash = std::hash<std::string_view>{}(
        std::string_view(reinterpret_cast<const char*>(image.pixels.data()), image.pixels.size() * sizeof(glm::vec4)));
    return sample;
}

// The configurations of one K, round-robin frame by frame, so that a changing load on a shared machine falls
// on all of them alike: per frame, CAO with every mesh count (adjacent: the second mesh's cost is a paired
// difference), then solid, then full LAO. The first frame after step I (which visits every voxel) is not
// counted.
Series CaoBench::runInterleaved(const std::vector<int>& counts, bool withSolidAndLao) {
    Series series;
    for (int f = -1; f < frames; ++f) {
        for (ShadingMode mode : {ShadingMode::Cao, ShadingMode::Solid, ShadingMode::Lao}) {
            if (mode != ShadingMode::Cao && !withSolidAndLao) continue;
            for (int meshes : counts) {
                FrameSample sample = renderOne(meshes, mode, f + 1);
                if (f >= 0) series[meshes][mode].push_back(std::move(sample));
            }
        }
    }
    return series;
}

struct CaoTables {
    Table speed, fraction, perStep, slowdown, dispatch;
    nlohmann::json raw = nlohmann::json::array();
    bool allIdentical = true;

    explicit CaoTables(bool secondStill)
        : speed("Table 3: frame time while the sphere moves (ours, ms, median over frames; +- half the range) and CAO speedup over "
                "full LAO (ours vs paper)",
                {"rays K", "meshes", "solid ms", "LAO ms", "LAO +- ms", "CAO ms", "CAO +- ms", "speedup", "paper speedup Engine", "paper Beetle",
                 "paper Skeleton", "CAO == LAO (V_AO, image)", "RMS vs 512 rays (visible voxels)",
                 "RMS vs 512 rays (recomputed voxels, category b)"}),
          fraction("Table 2: voxels whose LAO CAO recomputed (category b and the seam, where a clipped opacity is within reach), "
                   "and the voxels steps IV and V visited, mean over frames",
                   {"rays K", "meshes", "recomputed %", "paper Engine %", "paper Beetle %", "paper Skeleton %",
                    "visited by IV and V %", "visited voxels", "visited bricks where LAO can change %"}),
          perStep("Fig. 10: GPU time per step (ms, median)",
                  {"rays K", "meshes", "mode", passInfo(Pass::VoxelClipping).name, passInfo(Pass::LaoRecompute).name,
                   passInfo(Pass::RayCast).name, "total frame"}),
          slowdown(std::string("Table 4: slowdown of a second, overlapping mesh ") + (secondStill ? "that stays where it is" : "that moves with the first") +
                   " (CAO; median over frames of the paired 2-mesh / 1-mesh "
                   "frame, +- half the range; where it goes: median paired difference per step, and the ray caster alone)",
                   {"rays K", "CAO 1 mesh ms", "CAO 2 meshes ms", "slowdown %", "slowdown +- %", std::string(passInfo(Pass::VoxelClipping).name) + " +ms",
                    std::string(passInfo(Pass::LaoRecompute).name) + " +ms", std::string(passInfo(Pass::RayCast).name) + " +ms",
                    "solid (VI alone) slowdown %", "paper Engine %", "paper Skeleton %"}),
          dispatch("Step V dispatch: full grid with early exit vs compacted list (CAO, 1 mesh)",
                   {"rays K", "full grid: V ms", "compacted: V ms (incl. compaction)", "faster"}) {}

    // Tables 2 and 3, Fig. 10 and the raw runs: one K, one mesh count.
    void addRun(int rays, int meshes, const PaperRow* paper, Series& series, int groundTruthVoxels, const GroundTruthRms& rms);
    // Table 4: the second mesh's cost at one K, from the paired 1- and 2-mesh frames.
    void addSlowdown(int rays, const PaperRow* paper, Series& series);
};

void CaoTables::addRun(int rays, int meshes, const PaperRow* paper, Series& series, int groundTruthVoxels, const GroundTruthRms& rms) {
    ModeResult solid = summarize(series[meshes][ShadingMode::Solid]);
    ModeResult full = summarize(series[meshes][ShadingMode::Lao]);
    ModeResult cao = summarize(series[meshes][ShadingMode::Cao]);
    bool identical = full.aoHashes == cao.aoHashes && full.imageHashes == cao.imageHashes;
    allIdentical = allIdentical && identical;
    double speedup = full.msPerFrame / cao.msPerFrame;
    speed.add({rays, meshes, solid.msPerFrame, full.msPerFrame, full.msSpread, cao.msPerFrame, cao.msSpread, speedup,
               paper ? nlohmann::json(paper->engineSpeedup) : nlohmann::json(),
               paper ? nlohmann::json(paper->beetleSpeedup) : nlohmann::json(),
               paper ? nlohmann::json(paper->skeletonSpeedup) : nlohmann::json(), identical ? "yes" : "NO",
               groundTruthVoxels ? nlohmann::json(rms.visible) : nlohmann::json(),
               groundTruthVoxels ? nlohmann::json(rms.recomputed) : nlohmann::json()});
    fraction.add({rays, meshes, 100.0 * cao.recomputedFraction, 14.94, 20.24, 16.13, 100.0 * cao.visitedFraction,
                  std::llround(cao.visitedVoxels), 100.0 * cao.laoBrickFraction});
    for (auto [name, r] : {std::pair<const char*, ModeResult*>{"LAO", &full}, {"CAO", &cao}})
        perStep.add({rays, meshes, name, r->stepMs[passInfo(Pass::VoxelClipping).name], r->stepMs[passInfo(Pass::LaoRecompute).name],
                     r->stepMs[passInfo(Pass::RayCast).name], r->msPerFrame});
    raw.push_back({{"rays", rays}, {"meshes", meshes}, {"solid_ms", solid.msPerFrame}, {"lao_ms", full.msPerFrame},
                   {"cao_ms", cao.msPerFrame}, {"recomputed_fraction", cao.recomputedFraction},
                   {"visited_fraction", cao.visitedFraction}, {"visited_voxels", cao.visitedVoxels},
                   {"lao_brick_fraction", cao.laoBrickFraction}, {"lao_ms_spread", full.msSpread}, {"cao_ms_spread", cao.msSpread},
                   {"identical", identical}, {"rms_vs_512", rms.visible}, {"rms_vs_512_recomputed", rms.recomputed}, {"lao_steps_ms", full.stepMs},
                   {"cao_steps_ms", cao.stepMs}, {"cao_frame_ms", cao.frameMs}, {"lao_frame_ms", full.frameMs}});
}

void CaoTables::addSlowdown(int rays, const PaperRow* paper, Series& series) {
    const auto& one = series[1][ShadingMode::Cao];
    const auto& two = series[2][ShadingMode::Cao];
    std::vector<double> ratios, solidRatios;
    std::map<std::string, std::vector<double>> deltas;
    for (std::size_t f = 0; f < one.size() && f < two.size(); ++f) {
        ratios.push_back(two[f].ms / one[f].ms - 1.0);
        for (Pass pass : {Pass::VoxelClipping, Pass::LaoRecompute, Pass::RayCast}) {
            std::string name = passInfo(pass).name;
            auto at = [&](const FrameSample& s) { auto it = s.stepMs.find(name); return it == s.stepMs.end() ? 0.0 : it->second; };
            deltas[name].push_back(at(two[f]) - at(one[f]));
        }
        solidRatios.push_back(series[2][ShadingMode::Solid][f].ms / series[1][ShadingMode::Solid][f].ms - 1.0);
    }
    double lowest = 1e300, highest = -1e300;  // ratios holds one per frame, at least one
    for (double r : ratios) lowest = std::min(lowest, r), highest = std::max(highest, r);
    double spread = 0.5 * (highest - lowest);
    slowdown.add({rays, summarize(one).msPerFrame, summarize(two).msPerFrame, 100.0 * median(ratios), 100.0 * spread,
                  median(deltas[passInfo(Pass::VoxelClipping).name]), median(deltas[passInfo(Pass::LaoRecompute).name]),
                  median(deltas[passInfo(Pass::RayCast).name]), 100.0 * median(solidRatios),
                  paper ? nlohmann::json(paper->engineSlowdown) : nlohmann::json(),
                  paper ? nlohmann::json(paper->skeletonSlowdown) : nlohmann::json()});
}

// Step V variants at one K with one mesh: the full grid with early exit, then the compacted list.
void addDispatchRow(CaoBench& bench, Table& dispatch, int rays, const LaoSettings& lao) {
    double vMs[2] = {0, 0};
    for (int variant = 0; variant < 2; ++variant) {
        LaoSettings s = lao;
        s.dispatch = variant == 0 ? LaoSettings::Dispatch::FullGrid : LaoSettings::Dispatch::Compacted;
        bench.rendererFor(ShadingMode::Cao, 1).setLaoSettings(s);
        ModeResult r = summarize(bench.runInterleaved({1}, false)[1][ShadingMode::Cao]);
        vMs[variant] = r.stepMs[passInfo(Pass::LaoRecompute).name];
    }
    dispatch.add({rays, vMs[0], vMs[1], vMs[0] < vMs[1] ? "full grid" : "compacted"});
    bench.rendererFor(ShadingMode::Cao, 1).setLaoSettings(lao);
}

const PaperRow* paperRow(int rays) {
    const PaperRow* paper = nullptr;
    for (const PaperRow& row : kPaper)
        if (row.rays == rays) paper = &row;
    return paper;
}

}  // namespace

int benchCao(const CommandLine& cl) {
    LoadedScene loaded = loadSceneWithVolume(cl.required("scene"));
    std::vector<int> rayCounts = CommandLine::parseIntList("rays", cl.valueOr("rays", "6,14,26,54"), 1, 4096);
    std::vector<int> meshCounts = CommandLine::parseIntList("meshes", cl.valueOr("meshes", "1,2"), 1, 2);
    int frames = CommandLine::parseInt("frames", cl.valueOr("frames", "3"), 1, 1000);
    int groundTruthVoxels = CommandLine::parseInt("ground-truth-voxels", cl.valueOr("ground-truth-voxels", "400"), 0, 1000000);
    glm::ivec2 size = CommandLine::parseSize("size", cl.valueOr("size", "512x512"));
    std::string jsonPath = cl.valueOr("json", "bench-cao.json");
    // off: the ray caster and step IV test every sample against every mesh (the same results;
    // ClipMeshSet::setDepthBoxTests)
    std::string depthBoxTests = cl.valueOr("depth-box-tests", "on");
    if (depthBoxTests != "on" && depthBoxTests != "off")
        throw InputError("<command line>", "--depth-box-tests", "on or off", depthBoxTests);
    applyUnseenVoxelsOption(cl, loaded.scene.lao);
    std::string secondMesh = cl.valueOr("second-mesh", "moves");
    if (secondMesh != "moves" && secondMesh != "still")
        throw InputError("<command line>", "--second-mesh", "moves or still", "\"" + secondMesh + "\"");
    const bool secondStill = secondMesh == "still";
    const std::uint32_t seed = 20231101;

    auto context = gl::createHeadlessContext(gpuChoice(cl));
    CaoBench bench(*context, loaded, meshCounts, depthBoxTests == "on", size);
    bench.frames = frames;
    bench.secondStill = secondStill;
    bench.seed = seed;
    const VolumeData& v = loaded.volume;
    std::printf("curette bench cao: %s (%dx%dx%d), %dx%d image, %d frames per configuration, sphere radius %.1f mm, %s\n",
                loaded.scene.volumePath.c_str(), v.dims.x, v.dims.y, v.dims.z, size.x, size.y, frames, bench.sphereRadius,
                context->info().renderer.c_str());

    CaoTables tables(secondStill);
    for (int rays : rayCounts) {
        LaoSettings lao = loaded.scene.lao;
        if (!parseLaoPattern(std::to_string(rays), lao.directions)) parseLaoPattern("fibonacci:" + std::to_string(rays), lao.directions);
        for (auto& [key, renderer] : bench.renderers) renderer->setLaoSettings(lao);
        const PaperRow* paper = paperRow(rays);
        Series series = bench.runInterleaved(meshCounts, true);
        for (int meshes : meshCounts) {
            GroundTruthRms rms;
            if (groundTruthVoxels > 0)
                rms = groundTruthRms(bench.rendererFor(ShadingMode::Cao, meshes), loaded, lao, groundTruthVoxels, seed);
            tables.addRun(rays, meshes, paper, series, groundTruthVoxels, rms);
        }
        if (series.count(1) && series.count(2)) tables.addSlowdown(rays, paper, series);
        if (bench.renderers.count({ShadingMode::Cao, 1}) && (cl.flag("compare-dispatch") || rays == 26))
            addDispatchRow(bench, tables.dispatch, rays, lao);
    }
    tables.fraction.print();
    tables.speed.print();
    tables.perStep.print();
    tables.slowdown.print();
    tables.dispatch.print();
    std::printf("\nCAO identical to LAO on every frame: %s\n", tables.allIdentical ? "yes" : "NO");
    std::vector<nlohmann::json> json{tables.fraction.toJson(), tables.speed.toJson(), tables.perStep.toJson(), tables.slowdown.toJson(),
                                     tables.dispatch.toJson()};
    writeJson(jsonPath, {{"bench", "cao"}, {"scene", cl.required("scene")}, {"volume", loaded.scene.volumePath.string()},
                         {"frames", frames}, {"second_mesh", secondMesh}, {"size", {size.x, size.y}}, {"renderer", context->info().renderer},
                         {"sphere_radius_mm", bench.sphereRadius}, {"depth_box_tests", depthBoxTests == "on"},
                         {"unseen_voxels_skipped", loaded.scene.lao.onlyWhereSeen}, {"identical_every_frame", tables.allIdentical},
                         {"tables", json}, {"runs", tables.raw}});
    return tables.allIdentical ? 0 : 1;
}

}  // namespace curette::bench
