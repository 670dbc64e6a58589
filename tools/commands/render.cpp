// curette render --scene S --out FILE.png: one frame of a scene, headless (EGL), written atomically.
// --plan prints the frame plan (the passes, in order, with what each reads and writes); without --out it
// renders nothing. --stereo side-by-side|anaglyph renders an off-axis stereo pair (render/model/stereo.h);
// --turntable N writes N frames around the scene's vertical axis into the folder --out names, and an MP4 of
// them when ffmpeg is on PATH (tools/movie.h). --show-meshes (or the scene's "clip_mesh_display": {"show": true})
// draws the clip meshes over the image (render/clip_mesh_overlay.h; not in stereo): the renderer's image is
// unchanged, the PNG gets the overlay. --slices DIR writes the axial, coronal and sagittal slice views
// through --crosshair (render/model/slice_view.h, the viewer's slice panel's), with the removed region as
// `curette report` computes it; without --out only those. --xr-views F renders the two eyes a head-mounted
// display located (tools/tracked_views_file.h; render/model/tracked_view.h) as `view --xr` renders them,
// composed as --stereo says: a frame of an XR session again, headless.
#include "session/carve_report.h"
#include "session/scene_slices.h"
#include "scene/volume_statistics.h"
#include "tools/command_line.h"
#include "tools/commands/commands.h"
#include "session/loaded_scene.h"
#include "tools/movie.h"
#include "tools/tracked_views_file.h"
#include "base/error.h"
#include "base/progress.h"
#include "render/clip_mesh_overlay.h"
#include "render/renderer.h"
#include "render/stereo_render.h"

#include <chrono>
#include <cstdio>

namespace curette::commands {

namespace {

// The clip meshes drawn over the mono picture, and how.
struct MeshOverlay {
    explicit MeshOverlay(const ClipMeshDisplay& d) : display(d) {}
    ClipMeshOverlay overlay;
    ClipMeshDisplay display;
};

// The picture of one frame: mono (with the meshes over it when `meshes`), or the stereo pair composed.
Image renderPicture(Renderer& renderer, const FrameDescription& frame, StereoMode stereo, double eyeSeparationMm, glm::vec4 background,
                    MeshOverlay* meshes) {
    if (stereo == StereoMode::Off) {
        renderer.render(frame);
        if (meshes)
            return meshes->overlay.drawOver(renderer.outputTexture(), renderer.outputSize(), renderer.clipMeshes(), frame, meshes->display, -1);
        return renderer.readImage();
    }
    StereoPair pair = renderStereoPair(renderer, frame, eyeSeparationMm);
    return composeStereo(stereo, pair.left, pair.right, background);
}

// "x,y,z": a point in RAS mm.
glm::dvec3 parsePoint(const std::string& option, const std::string& text) {
    glm::dvec3 p(0.0);
    std::size_t at = 0;
    for (int a = 0; a < 3; ++a) {
        std::size_t comma = text.find(',', at);
        if ((a < 2) != (comma != std::string::npos))
            throw InputError("<command line>", "--" + option, "three numbers x,y,z (RAS mm)", "\"" + text + "\"");
        p[a] = CommandLine::parseDouble(option, text.substr(at, a < 2 ? comma - at : std::string::npos), -1e6, 1e6);
        at = comma + 1;
    }
    return p;
}

// --slices: the three slice views of the scene's state, with the removed region of its clip meshes.
void writeSlices(const LoadedScene& loaded, Renderer& renderer, const std::filesystem::path& dir, std::optional<glm::dvec3> crosshair) {
    InteractionState state = InteractionState::fromScene(loaded.scene);
    CarveReporter reporter(loaded, VolumeGeometry{loaded.volume.dims, loaded.volume.indexToWorld}, programVersion());
    reporter.compute(renderer.clipMeshes(), state);
    std::vector<std::uint8_t> removed = reporter.removedRegion();
    SliceOverlays overlays = sceneSliceOverlays(loaded, state, &removed, -1);
    glm::dvec3 at = crosshair ? *crosshair : defaultCrosshair(loaded.volume, state);
    GreyWindow window = defaultGreyWindow(computeStatistics(loaded.volume));
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throw SystemError(dir.string() + ": cannot create the output folder (" + ec.message() + ")");
    for (SliceAxis axis : kSliceAxes) {
        SliceImage slice = renderSlice(loaded.volume, axis, at, window, overlays);
        std::filesystem::path file = dir / (std::string(sliceAxisName(axis)) + ".png");
        writePng(file, slice.image, glm::vec4(0, 0, 0, 1));
        std::printf("%s: %dx%d, %.3g mm pixels\n", file.c_str(), slice.image.width, slice.image.height, slice.plane.pixelMm);
    }
    std::printf("slices through the crosshair %.2f,%.2f,%.2f (RAS mm), window %.6g..%.6g\n", at.x, at.y, at.z, window.lo, window.hi);
}

int render(const CommandLine& cl) {
    if (!cl.positional().empty()) throw InputError("<command line>", cl.positional()[0], "no positional arguments for render");
    std::optional<int> turntable;
    if (auto n = cl.value("turntable")) turntable = CommandLine::parseInt("turntable", *n, 1, 100000);
    std::optional<std::string> slicesDir = cl.value("slices");
    std::optional<glm::dvec3> crosshair;
    if (auto c = cl.value("crosshair")) {
        if (!slicesDir) throw InputError("<command line>", "--crosshair", "together with --slices DIR");
        crosshair = parsePoint("crosshair", *c);
    }
    bool planOnly = cl.flag("plan") && !cl.value("out") && !slicesDir;
    bool slicesOnly = slicesDir && !cl.value("out");
    std::string out = planOnly || slicesOnly ? std::string() : cl.required("out");
    if (slicesOnly && (turntable || cl.value("stereo")))
        throw InputError("<command line>", turntable ? "--turntable" : "--stereo", "together with --out (with --slices alone only the slices are written)");
    bool pngName = out.size() >= 4 && out.substr(out.size() - 4) == ".png";
    if (!planOnly && !slicesOnly && !turntable && !pngName) throw InputError("<command line>", "--out", "a file name ending in .png", "\"" + out + "\"");
    if (turntable && pngName)
        throw InputError("<command line>", "--out", "with --turntable a folder for the frames (frame_000000.png, ...), not a .png", "\"" + out + "\"");
    if (cl.value("fps") && !turntable) throw InputError("<command line>", "--fps", "together with --turntable N (the movie's frame rate)");
    double fps = CommandLine::parseDouble("fps", cl.valueOr("fps", "30"), 0.1, 1000);
    StereoMode stereo = StereoMode::Off;
    if (auto s = cl.value("stereo")) {
        std::optional<StereoMode> mode = parseStereoMode(*s);
        if (!mode || *mode == StereoMode::Off) throw InputError("<command line>", "--stereo", "side-by-side or anaglyph", "\"" + *s + "\"");
        stereo = *mode;
    }
    if (cl.value("eye-separation") && stereo == StereoMode::Off)
        throw InputError("<command line>", "--eye-separation", "together with --stereo side-by-side|anaglyph");
    double eyeSeparationMm = CommandLine::parseDouble("eye-separation", cl.valueOr("eye-separation", "65"), 0, 1000);
    std::optional<std::string> xrViews = cl.value("xr-views");
    if (xrViews) {
        if (stereo == StereoMode::Off) throw InputError("<command line>", "--xr-views", "together with --stereo side-by-side|anaglyph");
        for (const char* option : {"turntable", "size", "azimuth", "elevation", "eye-separation"})
            if (cl.value(option))
                throw InputError("<command line>", std::string("--") + option, "not with --xr-views (the views give the eyes, their poses and sizes)");
    }
    FrameOverrides overrides;
    if (auto s = cl.value("size")) overrides.size = CommandLine::parseSize("size", *s);
    if (auto s = cl.value("shading")) overrides.shading = parseShadingOption("shading", *s);
    if (auto a = cl.value("azimuth")) overrides.azimuthDeg = CommandLine::parseDouble("azimuth", *a, -360, 360);
    if (auto e = cl.value("elevation")) overrides.elevationDeg = CommandLine::parseDouble("elevation", *e, -89.9, 89.9);
    gl::GpuChoice gpu = gpuChoice(cl);

    LoadedScene loaded = loadSceneWithVolume(cl.required("scene"));
    auto context = gl::createHeadlessContext(gpu);
    Renderer renderer(*context, loaded.volume, loaded.scene.transferFunction);
    configureRenderer(loaded, renderer);
    FrameDescription frame = initialFrame(loaded.scene, renderer.geometry());
    applyOverrides(overrides, frame);
    if (cl.flag("plan")) {
        std::printf("frame plan: %s shading, %dx%d, %d clip meshes, %s\n%s", shadingModeName(frame.shading), frame.size.x, frame.size.y,
                    renderer.clipMeshes().count(), renderer.hasTubes() ? "tubes" : "no tubes", renderer.plan(frame).describe().c_str());
        if (planOnly) return 0;
    }
    if (slicesOnly) {
        writeSlices(loaded, renderer, *slicesDir, crosshair);
        return 0;
    }
    const glm::vec4 background(loaded.scene.background);
    bool showMeshes = cl.flag("show-meshes") || loaded.scene.clipMeshDisplay.show.value_or(false);
    if (showMeshes && stereo != StereoMode::Off) {
        if (cl.flag("show-meshes")) throw InputError("<command line>", "--show-meshes", "a mono image (the meshes are not drawn in stereo)", "--stereo");
        showMeshes = false;   // the scene's "show": stereo pictures have no overlay
    }
    std::optional<MeshOverlay> meshOverlay;
    if (showMeshes) meshOverlay.emplace(loaded.scene.clipMeshDisplay.display);
    if (xrViews) {
        TrackedViewsFile views = readTrackedViews(*xrViews);
        RoomAnchor anchor = viewsAnchor(views, renderer.geometry());
        std::array<Image, 2> eyes;
        for (std::size_t eye = 0; eye < 2; ++eye)
            eyes[eye] = renderTrackedEye(renderer, trackedEye(frame, views.views[eye], anchor, views.recommendedSize));
        if (stereo == StereoMode::Anaglyph && (eyes[0].width != eyes[1].width || eyes[0].height != eyes[1].height))
            throw InputError(*xrViews, "views", "eyes of one size for an anaglyph (use --stereo side-by-side)");
        writePng(out, composeStereo(stereo, eyes[0], eyes[1], background), background);
        std::printf("%s: eyes %dx%d and %dx%d from %s, %s shading\n", out.c_str(), eyes[0].width, eyes[0].height, eyes[1].width, eyes[1].height,
                    xrViews->c_str(), shadingModeName(frame.shading));
        return 0;
    }
    if (stereo != StereoMode::Off) {
        StereoRig rig = stereoRig(frame, eyeSeparationMm);
        std::printf("stereo %s: eyes %.1f mm apart, off-axis (parallel axes), zero parallax at %.1f mm, %d extra columns per eye\n",
                    stereoModeName(stereo), eyeSeparationMm, rig.convergenceMm, 2 * rig.marginColumns);
    }
    auto start = std::chrono::steady_clock::now();
    if (turntable) {
        // The camera turns about the world's superior axis (+z, the orbit camera's azimuth) through its target.
        std::filesystem::path dir = out;
        std::error_code ec;
        std::filesystem::create_directories(dir, ec);
        if (ec) throw SystemError(dir.string() + ": cannot create the output folder (" + ec.message() + ")");
        Progress progress("turntable", *turntable);
        std::vector<std::string> frames;
        for (int i = 0; i < *turntable; ++i) {
            FrameDescription f = frame;
            f.camera.azimuthDeg = turntableAzimuthDeg(frame.camera.azimuthDeg, i, *turntable);
            frames.push_back(movieFrameName(static_cast<std::size_t>(i)));
            writePng(dir / frames.back(), renderPicture(renderer, f, stereo, eyeSeparationMm, background, meshOverlay ? &*meshOverlay : nullptr), background);
            progress.update(i + 1);
        }
        progress.finish();
        double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        std::printf("%s: %d frames %s .. %s, %dx%d, %s shading, %.1f ms per frame\n", dir.c_str(), *turntable, movieFrameName(0).c_str(),
                    movieFrameName(static_cast<std::size_t>(*turntable - 1)).c_str(), frame.size.x, frame.size.y, shadingModeName(frame.shading),
                    ms / *turntable);
        std::filesystem::path mp4 = dir / "turntable.mp4";
        if (encodeMovie(dir, frames, fps, mp4)) std::printf("%s: %d frames at %g fps\n", mp4.c_str(), *turntable, fps);
        else std::printf("no ffmpeg on PATH: the frames only (apt-get install ffmpeg makes %s too)\n", mp4.c_str());
    } else {
        Image image = renderPicture(renderer, frame, stereo, eyeSeparationMm, background, meshOverlay ? &*meshOverlay : nullptr);
        double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        writePng(out, image, background);
        std::printf("%s: %dx%d, %s shading, %.1f ms\n", out.c_str(), image.width, image.height, shadingModeName(frame.shading), ms);
    }
    if (cl.flag("timings")) {
        const char* kind = context->info().softwareRenderer ? "wall time, llvmpipe" : "GPU timer";
        for (const FrameTimings::Entry& e : renderer.collectTimings().passes)
            std::printf("  %-28s %10.1f ms (%s)\n", passInfo(e.pass).name, e.ms, kind);
        // Bytes per voxel of every resource whose size grows with the volume (with the fold's spare texels).
        const double voxels = static_cast<double>(renderer.volumeLayout().voxelCount());
        std::size_t total = 0, perVoxel = 0;
        for (const GpuAllocation& a : renderer.gpuAllocations()) {
            std::printf("  %-40s %-34s %10.2f MiB", a.name(), a.formatText().c_str(), static_cast<double>(a.bytes) / 1048576.0);
            if (resourceInfo(a.resource).volumeSized) std::printf(" %8.3f B/voxel", static_cast<double>(a.bytes) / voxels), perVoxel += a.bytes;
            std::printf("\n");
            total += a.bytes;
        }
        std::printf("  %-40s %-34s %10.2f MiB %8.3f B/voxel (volume-sized)\n", "total", "", static_cast<double>(total) / 1048576.0,
                    static_cast<double>(perVoxel) / voxels);
        std::printf("  volume layout: %s\n", renderer.volumeLayout().describe().c_str());
        if (const AmbientOcclusion* ao = renderer.ambientOcclusion())
            std::printf("  recomputed %.2f %% of %llu voxels in step V\n", 100.0 * ao->lastStats().recomputedFraction(),
                        static_cast<unsigned long long>(ao->lastStats().voxels));
    }
    if (slicesDir) writeSlices(loaded, renderer, *slicesDir, crosshair);   // after the frame, so its timings are its own
    return 0;
}

}  // namespace

Command renderCommand() {
    return {{"render", "--scene S --out F.png", "render one frame headless (EGL) and write a PNG; --stereo an off-axis pair, --turntable N frames around the vertical axis and an MP4 (ffmpeg)",
             withGpuOption({{"scene", true, "scene file (JSON)"},
              {"out", true, "output PNG (written atomically); with --turntable a folder"},
              {"size", true, "image size WxH (default: the scene's; with --stereo, of each eye)", "WxH"},
              {"shading", true, "solid|phong|lao|cao|dos|ismos (default: the scene's)", "MODE"},
              {"azimuth", true, "camera azimuth in degrees (default: the scene's)"},
              {"elevation", true, "camera elevation in degrees (default: the scene's)"},
              {"stereo", true, "side-by-side|anaglyph: an off-axis stereo pair (side-by-side: 2W x H)", "side-by-side|anaglyph"},
              {"eye-separation", true, "stereo eye separation in mm (default 65: orthostereo, render/model/stereo.h)"},
              {"xr-views", true, "with --stereo: the two eyes a head-mounted display located (JSON, docs/commands.md), rendered as view --xr renders them", "F.json"},
              {"turntable", true, "N frames turning the camera once about the vertical axis, into the --out folder"},
              {"fps", true, "with --turntable: frames per second of the MP4 (default 30)"},
              {"timings", false, "print the GPU time of every pass and the GPU memory of every resource"},
              {"plan", false, "print the frame plan: each pass in order, what it reads and writes (without --out: only that)"},
              {"show-meshes", false, "draw the clip meshes over the image (translucent, outlined; not with --stereo): the scene's \"clip_mesh_display\" says how"},
              {"slices", true, "write axial.png, coronal.png, sagittal.png (slice views with the removed region, labels, meshes) into DIR (without --out: only those)", "DIR"},
              {"crosshair", true, "with --slices: the point the slices pass through, RAS mm (default: the clip meshes' centre, else the volume's)", "X,Y,Z"}})},
            &render};
}

}  // namespace curette::commands
