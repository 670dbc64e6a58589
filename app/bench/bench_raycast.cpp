// curette bench raycast: ray-casting speed at a fixed size while the camera orbits, with the error of a
// sample of pixels against the CPU double reference next to each timing.
#include "app/bench/bench_raycast.h"

#include "app/bench/report.h"
#include "app/loaded_scene.h"
#include "base/error.h"
#include "render/reference/raycast_reference.h"
#include "render/renderer.h"

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
                       {"shading", "skip empty", "ms/frame (median)", "ms/frame (min)", "GPU ms (median)",
                        "Msamples/frame", "Msamples/s", "Mtexel fetches/s", "max error vs CPU", "rms error vs CPU"});
    for (ShadingMode mode : {ShadingMode::Solid, ShadingMode::Phong}) {
        for (bool skip : {true, false}) {
            FrameDescription frame = base;
            frame.shading = mode;
            frame.raycast.skipEmptySpace = skip;
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
            double samples = 0;
            for (int i = 0; i < frames; ++i) {
                renderer.render(frameAt(i));
                samples += static_cast<double>(renderer.samplesLastFrame());
            }
            renderer.setCountSamples(false);
            renderer.collectTimings();
            samples /= frames;
            double ms = median(wall);
            double fetchesPerSample = mode == ShadingMode::Phong ? 7.0 : 1.0;

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
            table.add({shadingModeName(mode), skip, ms, *std::min_element(wall.begin(), wall.end()), median(gpu),
                       samples * 1e-6, samples / ms * 1e-3, samples * fetchesPerSample / ms * 1e-3,
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
