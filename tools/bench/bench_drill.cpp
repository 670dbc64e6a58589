// bench drill: the drill's cost and accuracy. (1) On the scene's scan grid, straight strokes of sphere burrs at
// hand speed, 30 frames a second: stroke steps per second (the sweep into the removal), voxels and bricks
// touched per step, bytes per undo step, and the removed volume against the analytic capsule. (2) In the
// renderer (cao, the scene's size or --size): after each stroke, the exact frame (CAO IV-V over the bricks the
// stroke reached, then the ray cast), and at the end CAO against full LAO.
#include "tools/bench/bench_drill.h"

#include "gl/context.h"
#include "plan/undo_history.h"
#include "plan/drill_sweep.h"
#include "render/renderer.h"
#include "session/loaded_scene.h"
#include "tools/bench/report.h"
#include "tools/command_line.h"
#include "scene/scene.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace curette::bench {

namespace {
using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }
}  // namespace

int benchDrill(const CommandLine& cl) {
    std::filesystem::path scenePath = cl.valueOr("scene", "assets/scenes/head-drill.json");
    std::string jsonPath = cl.valueOr("json", "bench-drill.json");
    LoadedScene loaded = loadSceneWithVolume(scenePath);
    const glm::ivec3 dims = loaded.volume.dims;
    const glm::dmat4 affine = loaded.volume.indexToWorld;
    std::printf("curette bench drill: %s, grid %dx%dx%d\n", scenePath.c_str(), dims.x, dims.y, dims.z);

    // (1) The sweep on the CPU.
    Table sweepTable("Straight strokes, 1 s at 30 frames/s, sphere burrs (CPU, one core)",
                     {"burr diameter (mm)", "speed (mm/s)", "steps/s", "ms/step (median)", "voxels changed/step", "bricks touched/step",
                      "undo bytes/stroke", "removed (mm3)", "analytic capsule (mm3)", "error (%)"});
    glm::dvec3 centre = glm::dvec3(affine * glm::dvec4(glm::dvec3(dims - 1) * 0.5, 1.0));
    for (double diameter : {2.0, 4.0, 6.0})
        for (double speed : {30.0, 50.0}) {
            plan::RemovalVolume removal(dims, affine);
            plan::UndoHistory history;
            plan::DrillTool tool{clip::SolidShape{clip::SolidShape::Kind::Sphere, diameter / 2}};
            glm::dvec3 direction = glm::normalize(glm::dvec3(0.8, 0.5, 0.3));
            glm::dvec3 start = centre - 0.5 * speed * direction;
            std::vector<double> stepMs;
            std::size_t changed = 0, bricks = 0;
            history.beginStroke();
            for (int f = 0; f < 30; ++f) {
                clip::RigidPose a{start + speed * (f / 30.0) * direction, {}}, b{start + speed * ((f + 1) / 30.0) * direction, {}};
                std::uint64_t version = removal.version();
                auto t = Clock::now();
                plan::DrillSweep sweep(tool, a, b);
                changed += plan::applySweep(removal, sweep, false, history.before());
                stepMs.push_back(msSince(t));
                bricks += removal.bricksChangedSince(version).size();
            }
            history.endStroke(removal);
            double r = diameter / 2, analytic = std::numbers::pi * r * r * speed + 4.0 / 3.0 * std::numbers::pi * r * r * r;
            double removed = removal.drilledVolumeMm3();
            double ms = median(stepMs);
            sweepTable.add({diameter, speed, 1000.0 / ms, ms, double(changed) / 30.0, double(bricks) / 30.0, double(history.lastStrokeBytes()),
                            removed, analytic, 100.0 * (removed - analytic) / analytic});
        }
    sweepTable.print();

    // (2) The exact frame after each stroke, in the renderer.
    auto context = gl::createHeadlessContext(gpuChoice(cl));
    Renderer renderer(*context, loaded.volume, loaded.scene.transferFunction);
    configureRenderer(loaded, renderer);
    auto removal = std::make_shared<plan::RemovalVolume>(dims, affine);
    renderer.setRemoval(removal);
    FrameDescription frame = initialFrame(loaded.scene, renderer.geometry());
    if (cl.value("size")) frame.size = CommandLine::parseSize("size", *cl.value("size"));
    frame.shading = ShadingMode::Cao;
    auto t0 = Clock::now();
    renderer.render(frame);
    renderer.finish();
    double firstMs = msSince(t0);
    Table exactTable("Exact frame after a 4 mm burr's 0.33 s stroke at 40 mm/s (cao, " + std::to_string(frame.size.x) + "x" +
                         std::to_string(frame.size.y) + "; the first frame's step I: " + std::to_string(int(firstMs)) + " ms)",
                     {"stroke", "exact frame (ms)", "of it AO IV-V (ms)", "bricks visited", "voxels recomputed"});
    plan::DrillTool burr{clip::SolidShape{clip::SolidShape::Kind::Sphere, 2.0}};
    glm::dvec3 at = loaded.scene.clipMeshes.empty() ? centre : loaded.scene.clipMeshes[0].pose.position;
    std::vector<double> exactMs;
    for (int stroke = 0; stroke < 5; ++stroke) {
        glm::dvec3 direction = glm::normalize(glm::dvec3(std::cos(1.3 * stroke), std::sin(1.3 * stroke), -0.4));
        for (int f = 0; f < 10; ++f) {
            clip::RigidPose a{at, {}}, b{at + (40.0 / 30.0) * direction, {}};
            plan::DrillSweep sweep(burr, a, b);
            plan::applySweep(*removal, sweep, false);
            at = b.position;
        }
        renderer.collectTimings();
        auto t = Clock::now();
        renderer.render(frame);
        renderer.finish();
        double ms = msSince(t);
        exactMs.push_back(ms);
        const AmbientOcclusionStats& s = renderer.ambientOcclusion()->lastStats();
        exactTable.add({stroke + 1, ms, renderer.collectTimings().ambientOcclusionMs(), double(s.bricks), double(s.recomputed)});
    }
    exactTable.print();
    // CAO against full LAO on the drilled state.
    std::vector<std::uint16_t> cao = renderer.ambientOcclusion()->readAmbient();
    FrameDescription lao = frame;
    lao.shading = ShadingMode::Lao;
    renderer.render(lao);
    bool same = renderer.ambientOcclusion()->readAmbient() == cao;
    std::printf("drilled %.1f mm3 in 5 strokes; exact frame median %.0f ms; CAO == LAO after the strokes: %s\n", removal->drilledVolumeMm3(),
                median(exactMs), same ? "yes" : "NO");
    nlohmann::json document = {{"bench", "drill"},
                               {"scene", scenePath.string()},
                               {"tables", {sweepTable.toJson(), exactTable.toJson()}},
                               {"exact_frame_median_ms", median(exactMs)},
                               {"cao_equals_lao", same}};
    writeJson(jsonPath, document);
    return same ? 0 : 1;
}

}  // namespace curette::bench
