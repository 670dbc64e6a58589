// curette render --scene S --out FILE.png: one frame of a scene, headless (EGL), written atomically.
// --plan prints the frame plan (the passes, in order, with what each reads and writes); without --out it
// renders nothing.
#include "app/command_line.h"
#include "app/commands/commands.h"
#include "app/loaded_scene.h"
#include "base/error.h"
#include "render/renderer.h"

#include <chrono>
#include <cstdio>

namespace curette::commands {

int render(const Arguments& args) {
    CommandLine cl(args, {{"scene", true, "scene file (JSON)"},
                          {"out", true, "output PNG (written atomically)"},
                          {"size", true, "image size WxH (default: the scene's)"},
                          {"shading", true, "solid|phong|lao|cao|dos|ismos (default: the scene's)"},
                          {"azimuth", true, "camera azimuth in degrees (default: the scene's)"},
                          {"elevation", true, "camera elevation in degrees (default: the scene's)"},
                          {"timings", false, "print the GPU time of every pass and the GPU memory of every resource"},
                          {"plan", false, "print the frame plan: each pass in order, what it reads and writes (without --out: only that)"}});
    if (!cl.positional().empty()) throw InputError("<command line>", cl.positional()[0], "no positional arguments for render");
    bool planOnly = cl.flag("plan") && !cl.value("out");
    std::string out = planOnly ? std::string() : cl.required("out");
    if (!planOnly && (out.size() < 4 || out.substr(out.size() - 4) != ".png"))
        throw InputError("<command line>", "--out", "a file name ending in .png", "\"" + out + "\"");
    FrameOverrides overrides;
    if (auto s = cl.value("size")) overrides.size = CommandLine::parseSize("size", *s);
    if (auto s = cl.value("shading")) overrides.shading = parseShadingOption("shading", *s);
    if (auto a = cl.value("azimuth")) overrides.azimuthDeg = CommandLine::parseDouble("azimuth", *a, -360, 360);
    if (auto e = cl.value("elevation")) overrides.elevationDeg = CommandLine::parseDouble("elevation", *e, -89.9, 89.9);

    LoadedScene loaded = loadSceneWithVolume(cl.required("scene"));
    auto context = gl::createHeadlessContext();
    Renderer renderer(*context, loaded.volume, loaded.scene.transferFunction);
    configureRenderer(loaded, renderer);
    FrameDescription frame = initialFrame(loaded.scene, renderer.geometry());
    applyOverrides(overrides, frame);
    if (cl.flag("plan")) {
        std::printf("frame plan: %s shading, %dx%d, %d clip meshes, %s\n%s", shadingModeName(frame.shading), frame.size.x, frame.size.y,
                    renderer.clipMeshes().count(), renderer.hasTubes() ? "tubes" : "no tubes", renderer.plan(frame).describe().c_str());
        if (planOnly) return 0;
    }
    auto start = std::chrono::steady_clock::now();
    renderer.render(frame);
    Image image = renderer.readImage();
    double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    writePng(out, image, glm::vec4(loaded.scene.background));
    std::printf("%s: %dx%d, %s shading, %.1f ms\n", out.c_str(), frame.size.x, frame.size.y, shadingModeName(frame.shading), ms);
    if (cl.flag("timings")) {
        const char* kind = context->info().softwareRenderer ? "wall time, llvmpipe" : "GPU timer";
        for (const FrameTimings::Entry& e : renderer.collectTimings().passes)
            std::printf("  %-28s %10.1f ms (%s)\n", passInfo(e.pass).name, e.ms, kind);
        std::size_t total = 0;
        for (const GpuAllocation& a : renderer.gpuAllocations()) {
            std::printf("  %-40s %-28s %10.2f MiB\n", a.name(), a.formatText().c_str(), static_cast<double>(a.bytes) / 1048576.0);
            total += a.bytes;
        }
        std::printf("  %-40s %-28s %10.2f MiB\n", "total", "", static_cast<double>(total) / 1048576.0);
        if (const AmbientOcclusion* ao = renderer.ambientOcclusion())
            std::printf("  recomputed %.2f %% of %llu voxels in step V\n", 100.0 * ao->lastStats().recomputedFraction(),
                        static_cast<unsigned long long>(ao->lastStats().voxels));
    }
    return 0;
}

}  // namespace curette::commands
