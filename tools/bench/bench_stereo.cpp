// curette bench stereo: how consistently each shading mode shades one surface point in the two eyes of a
// stereo pair (render/model/stereo.h, render/reference/stereo_match.h). Modes that shade in data space (solid, lao, cao: the
// colour of a point depends on the point only) should agree between the eyes up to what the ray integral
// itself changes with the direction; phong's specular term is view-dependent by design; dos (view-aligned
// slices, an occlusion buffer in image space) and ismos (image-space layers) compute their shadows from each
// eye's view. The CAO paper's argument for data-space AO, measured.
//
// Every mode renders the same pair (the scene's first frame, ray jitter off: its per-pixel offsets would make
// the two eyes' samples of one point differ in every mode alike). Surface points are matched once, on the
// CPU; per mode the table gives, over the matched points, the largest RGB difference between the left pixel
// and the right one (display values in 8-bit levels: RMS, maximum, mean), and that RMS over solid's, the
// floor every mode shares (different rays through the same point).
#include "tools/bench/bench_stereo.h"

#include "tools/bench/report.h"
#include "session/interaction.h"
#include "session/loaded_scene.h"
#include "base/error.h"
#include "plan/removal_field.h"
#include "render/renderer.h"
#include "render/model/stereo.h"
#include "render/reference/stereo_match.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>

namespace curette::bench {

namespace {

using Clock = std::chrono::steady_clock;

struct EyeImages {
    Image left, right;
    double msPerEye = 0;
};

std::vector<StereoMatch> onSurface(const std::vector<StereoMatch>& matches, bool tube) {
    std::vector<StereoMatch> subset;
    for (const StereoMatch& m : matches)
        if (m.tube == tube) subset.push_back(m);
    return subset;
}

}  // namespace

int benchStereo(const CommandLine& cl) {
    LoadedScene loaded = loadSceneWithVolume(cl.required("scene"));
    glm::ivec2 size = CommandLine::parseSize("size", cl.valueOr("size", "256x256"));
    double separationMm = CommandLine::parseDouble("eye-separation", cl.valueOr("eye-separation", "65"), 0.1, 1000);
    MatchSettings settings;
    settings.stride = CommandLine::parseInt("stride", cl.valueOr("stride", "2"), 1, 64);
    std::vector<ShadingMode> modes{ShadingMode::Solid};   // first: the floor every mode shares
    for (ShadingMode mode : parseShadingList("modes", cl.valueOr("modes", "solid,phong,lao,cao,dos,ismos")))
        if (mode != ShadingMode::Solid) modes.push_back(mode);
    std::string jsonPath = cl.valueOr("json", "bench-stereo.json");

    auto context = gl::createHeadlessContext(gpuChoice(cl));
    Renderer renderer(*context, loaded.volume, loaded.scene.transferFunction);
    configureRenderer(loaded, renderer);
    FrameDescription base = initialFrame(loaded.scene, renderer.geometry());
    base.size = size;
    base.raycast.jitterSeed = 0;
    const double stepMm = renderer.resolveStepMm(base.raycast);
    // Two eyes' rays sample one surface on different lattices: each crossing lies up to a step past the surface.
    settings.depthToleranceMm = CommandLine::parseDouble("depth-tolerance", cl.valueOr("depth-tolerance", std::to_string(2.0 * stepMm)), 0, 1000);
    StereoRig rig = stereoRig(base, separationMm);
    EyeView left{rig.eyeFrame(Eye::Left), {}}, right{rig.eyeFrame(Eye::Right), {}};

    // The clip region as the scene poses it (the CPU twin of the renderer's clip test).
    InteractionState state = InteractionState::fromScene(loaded.scene);
    std::vector<plan::PosedMesh> posed = state.posedMeshes();
    SurfaceScene scene{loaded.volume, loaded.scene.transferFunction, posed.empty() ? plan::InsideTest() : plan::insideAnyMesh(posed), stepMm};

    const VolumeData& v = loaded.volume;
    std::printf("curette bench stereo: %s (%dx%dx%d), eyes %dx%d (rendered %dx%d), %s\n", loaded.scene.volumePath.c_str(), v.dims.x, v.dims.y,
                v.dims.z, size.x, size.y, left.frame.size.x, left.frame.size.y, context->info().renderer.c_str());
    std::printf("off-axis rig: eyes %.1f mm apart, camera %.0f mm from the target, zero parallax at %.1f mm; step %.3g mm, jitter off, "
                "%zu clip meshes, %s\n",
                separationMm, base.camera.distanceMm, rig.convergenceMm, stepMm, posed.size(), renderer.hasTubes() ? "tubes" : "no tubes");

    // Tubes: each eye's nearest tube surface, from the G-buffer of a solid frame.
    for (EyeView* eye : {&left, &right}) {
        FrameDescription f = eye->frame;
        f.shading = ShadingMode::Solid;
        renderer.render(f);
        if (renderer.hasTubes() && renderer.lastPlan().runs(Pass::TubeGBuffer)) eye->tubeViewDepth = renderer.gbuffer().readDepth();
    }
    auto matchStart = Clock::now();
    MatchCounts counts;
    std::vector<StereoMatch> matches = matchSurfacePoints(scene, left, right, settings, &counts);
    double matchMs = std::chrono::duration<double, std::milli>(Clock::now() - matchStart).count();
    std::vector<StereoMatch> volumePoints = onSurface(matches, false), tubePoints = onSurface(matches, true);

    char title[256];
    std::snprintf(title, sizeof title,
                  "A: surface points (left eye, every %d. pixel; matched within %.2g px of a right-eye pixel centre and %.3g mm of its surface point)",
                  settings.stride, settings.maxColumnOffsetPx, settings.depthToleranceMm);
    Table found(title,
                {"pixels tried", "with a surface", "outside the right image", "off a pixel centre", "hidden or too far", "matched volume",
                 "matched tubes", "CPU ms"});
    found.add({counts.tried, counts.surfaces, counts.outside, counts.offCentre, counts.hidden, static_cast<int>(volumePoints.size()),
               static_cast<int>(tubePoints.size()), matchMs});
    found.print();

    Table consistency("B: stereo consistency per shading mode: |left - right| at matched surface points (max over RGB, 8-bit levels)",
                      {"shading", "surface", "points", "RMS", "max", "mean", "mean shade", "RMS / mean shade %", "that / solid's", "ms per eye"});
    std::map<bool, double> solidRelative;   // solid's RMS / mean shade per surface kind: the floor
    for (ShadingMode mode : modes) {
        EyeImages images;
        {
            FrameDescription f = left.frame;
            f.shading = mode;
            renderer.render(f);   // warm-up: programs, and step I for lao/cao
            renderer.finish();
        }
        double ms = 0;
        for (Eye eye : {Eye::Left, Eye::Right}) {
            FrameDescription f = eye == Eye::Left ? left.frame : right.frame;
            f.shading = mode;
            auto start = Clock::now();
            renderer.render(f);
            renderer.finish();
            ms += std::chrono::duration<double, std::milli>(Clock::now() - start).count();
            (eye == Eye::Left ? images.left : images.right) = renderer.readImage();
        }
        renderer.collectTimings();
        for (bool tube : {false, true}) {
            const std::vector<StereoMatch>& points = tube ? tubePoints : volumePoints;
            if (points.empty()) continue;
            ShadeDifference d = shadeDifference(images.left, images.right, points);
            if (mode == ShadingMode::Solid) solidRelative[tube] = d.relativeRms();
            double floor = solidRelative.count(tube) ? solidRelative[tube] : 0.0;
            consistency.add({shadingModeName(mode), tube ? "tubes" : "volume", d.points, 255.0 * d.rms, 255.0 * d.max, 255.0 * d.mean,
                             255.0 * d.meanShade, 100.0 * d.relativeRms(), floor > 0 ? nlohmann::json(d.relativeRms() / floor) : nlohmann::json(),
                             ms / 2});
        }
    }
    consistency.print(3);
    std::printf("(a point: where the left ray's opacity first reaches 0.5, or a tube surface; solid is the floor: the same point seen "
                "along two rays; 1 level = 1/255)\n");
    writeJson(jsonPath, {{"bench", "stereo"},
                         {"scene", cl.required("scene")},
                         {"volume", loaded.scene.volumePath.string()},
                         {"eye_size", {size.x, size.y}},
                         {"eye_separation_mm", separationMm},
                         {"convergence_mm", rig.convergenceMm},
                         {"camera_distance_mm", base.camera.distanceMm},
                         {"step_mm", stepMm},
                         {"depth_tolerance_mm", settings.depthToleranceMm},
                         {"max_column_offset_px", settings.maxColumnOffsetPx},
                         {"renderer", context->info().renderer},
                         {"tables", {found.toJson(), consistency.toJson()}}});
    return 0;
}

}  // namespace curette::bench
