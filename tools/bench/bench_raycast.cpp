// curette bench raycast: ray-casting speed at a fixed size while the camera orbits, with the error of a
// sample of pixels against the CPU double reference next to each timing.
#include "tools/bench/bench_raycast.h"

#include "tools/bench/report.h"
#include "session/loaded_scene.h"
#include "base/error.h"
#include "render/reference/raycast_reference.h"
#include "render/renderer.h"
#include "render/shader_pieces.h"

#include <chrono>
#include <cstdio>
#include <random>

namespace curette::bench {

using Clock = std::chrono::steady_clock;

int benchRaycast(const CommandLine& cl) {
    LoadedScene loaded = loadSceneWithVolume(cl.required("scene"));
    glm::ivec2 size = CommandLine::parseSize("size", cl.valueOr("size", "512x512"));
    int frames = CommandLine::parseInt("frames", cl.valueOr("frames", "8"), 1, 10000);
    int referencePixels = CommandLine::parseInt("reference-pixels", cl.valueOr("reference-pixels", "48"), 0, 100000);
    std::string jsonPath = cl.valueOr("json", "bench-raycast.json");

    auto context = gl::createHeadlessContext(gpuChoice(cl));
    Renderer renderer(*context, loaded.volume, loaded.scene.transferFunction);
    configureRenderer(loaded, renderer);
    FrameDescription base = initialFrame(loaded.scene, renderer.geometry());
    base.size = size;
    const VolumeData& v = loaded.volume;
    std::printf("curette bench raycast: %s (%dx%dx%d %s), %dx%d, %d frames orbiting 360 degrees, %s\n",
                loaded.scene.volumePath.c_str(), v.dims.x, v.dims.y, v.dims.z, scalarTypeName(v.sourceType), size.x,
                size.y, frames, context->info().renderer.c_str());

    Table table("Ray casting (step " + std::to_string(renderer.resolveStepMm(base.raycast)) + " mm)",
                       {"shading", "phong shades", "phong gradients", "empty space", "tile order", "ms/frame (median)", "ms/frame (min)", "GPU ms (median)",
                        "Msamples/frame", "Mray steps/frame", "2-thread balance", "Msamples/s", "Mtexel fetches/s",
                        "max error vs CPU", "rms error vs CPU"});
    // Empty space: jumps by the distance map (the default), one empty brick per step (as before the distance
    // map), or not skipped at all; all three take the same samples and give the same image. Tile order: bands
    // (the default) or scanline, how llvmpipe's worker threads share the frame (shaders/tile_order.glsl).
    // 2-thread balance: the ray steps of the busier half of the dispatch over the mean of both halves (two
    // threads each take one half; 1 = balanced; the frame takes about this factor longer than balanced).
    // Phong shades its visible samples where the renderer chooses (render/model/phong_shading_placement.h), and
    // once more in the other place, which takes the same samples and gives the same image. Phong's gradients
    // come from the gradient volume on an 8-bit scan (render/gradient_volume.h), and once more from six reads of
    // the scan (the same central differences; llvmpipe filters the scan with 8-bit weights, so the error differs).
    struct Configuration {
        const char* emptySpace;
        bool skip;
        int jumpLimit;
        const char* order;
        int rowsPerBand;
        bool otherPhongPlace;
        bool sixReads = false;
    };
    const int bands = TileOrderPiece::defaultRowsPerBand();
    const Configuration kConfigurations[] = {{"distance map", true, 255, "bands", bands, false},
                                             {"distance map", true, 255, "scanline", 1, false},
                                             {"one brick", true, 1, "bands", bands, false},
                                             {"off", false, 1, "bands", bands, false},
                                             {"distance map", true, 255, "bands", bands, true},
                                             {"distance map", true, 255, "bands", bands, false, true}};
    for (ShadingMode mode : {ShadingMode::Solid, ShadingMode::Phong}) {
        for (const Configuration& configuration : kConfigurations) {
            if ((configuration.otherPhongPlace || configuration.sixReads) && mode != ShadingMode::Phong) continue;
            if (configuration.sixReads && !renderer.gradientVolumeSupported()) continue;
            renderer.setGradientVolume(!configuration.sixReads);
            FrameDescription frame = base;
            frame.shading = mode;
            frame.raycast.skipEmptySpace = configuration.skip;
            renderer.setEmptySpaceJumpLimit(configuration.jumpLimit);
            renderer.setTileRowsPerBand(configuration.rowsPerBand);
            renderer.setPhongShading(std::nullopt);
            const PhongShading chosen = renderer.phongShading(frame);
            if (configuration.otherPhongPlace)
                renderer.setPhongShading(chosen == PhongShading::InLoop ? PhongShading::BetweenRounds : PhongShading::InLoop);
            std::string phongShades = mode != ShadingMode::Phong ? "-"
                                      : std::string(phongShadingName(renderer.phongShading(frame))) + (configuration.otherPhongPlace ? "" : " (chosen)");
            auto frameAt = [&](int i) {
                FrameDescription f = frame;
                f.camera.azimuthDeg = base.camera.azimuthDeg + 360.0 * i / frames;
                return f;
            };
            // Warm-up: compiles the program and touches every texture.
            renderer.render(frameAt(0));
            renderer.finish();
            renderer.collectTimings();
            std::vector<double> wall, gpu;
            for (int i = 0; i < frames; ++i) {
                auto start = Clock::now();
                renderer.render(frameAt(i));
                renderer.finish();
                wall.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
                gpu.push_back(renderer.collectTimings().ms(Pass::RayCast));
            }
            // Samples per frame, counted in a separate pass over the same path (the counter costs time).
            renderer.setCountSamples(true);
            double samples = 0, steps = 0, balance = 0;
            for (int i = 0; i < frames; ++i) {
                renderer.render(frameAt(i));
                samples += static_cast<double>(renderer.samplesLastFrame());
                steps += static_cast<double>(renderer.rayStepsLastFrame());
                glm::dvec2 halves = renderer.rayStepsByDispatchHalf();
                balance += halves.x + halves.y > 0 ? std::max(halves.x, halves.y) / (0.5 * (halves.x + halves.y)) : 1.0;
            }
            renderer.setCountSamples(false);
            renderer.collectTimings();
            samples /= frames;
            steps /= frames;
            balance /= frames;
            double ms = median(wall);
            const bool gradientVolume = mode == ShadingMode::Phong && !configuration.sixReads && renderer.gradientVolumeSupported();
            double fetchesPerSample = mode != ShadingMode::Phong ? 1.0 : gradientVolume ? 2.0 : 7.0;

            // Accuracy next to speed: pixels of the first frame against the CPU double twin.
            renderer.render(frameAt(0));
            Image image = renderer.readImage();
            // Pixels the volume covers (alpha > 0 on the GPU image): the background agrees trivially and would
            // dilute the error.
            std::mt19937 random(17);
            std::uniform_int_distribution<int> px(0, size.x - 1), py(0, size.y - 1);
            double maxError = 0, sumSquares = 0;
            int sampled = 0;
            for (int attempts = 0; sampled < referencePixels && attempts < 1000 * std::max(referencePixels, 1); ++attempts) {
                glm::ivec2 p(px(random), py(random));
                if (image.at(p.x, p.y).a <= 0.0f) continue;
                ++sampled;
                glm::dvec4 expected = reference::raycastPixel(v, loaded.scene.transferFunction, frameAt(0),
                                                              renderer.resolveStepMm(frame.raycast), p).rgba;
                for (int c = 0; c < 4; ++c) {
                    double e = std::abs(double(image.at(p.x, p.y)[c]) - expected[c]);
                    maxError = std::max(maxError, e);
                    sumSquares += e * e;
                }
            }
            double rms = sampled ? std::sqrt(sumSquares / (4.0 * sampled)) : 0.0;
            table.add({shadingModeName(mode), phongShades, mode != ShadingMode::Phong ? "-" : gradientVolume ? "volume" : "six reads",
                       configuration.emptySpace, configuration.order, ms,
                       *std::min_element(wall.begin(), wall.end()), median(gpu), samples * 1e-6, steps * 1e-6, balance,
                       samples / ms * 1e-3, samples * fetchesPerSample / ms * 1e-3,
                       referencePixels ? nlohmann::json(maxError) : nlohmann::json(),
                       referencePixels ? nlohmann::json(rms) : nlohmann::json()});
        }
    }
    table.print();
    std::printf("(errors: %d random pixels the volume covers, per configuration, against render/reference/raycast_reference, RGBA in [0,1])\n",
                referencePixels);
    writeJson(jsonPath, {{"bench", "raycast"},
                                {"scene", cl.required("scene")},
                                {"volume", loaded.scene.volumePath.string()},
                                {"size", {size.x, size.y}},
                                {"frames", frames},
                                {"renderer", context->info().renderer},
                                {"tables", {table.toJson()}}});
    return 0;
}

}  // namespace curette::bench
