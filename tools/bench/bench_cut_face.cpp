// curette bench cut-face: how rough the cut face of a carve looks in each shading mode, with the cut-face
// rules off (the sample lattice alone) and on (render/model/frame.h CutFaceSettings), next to the time per frame.
// The measure (render/model/cut_face_measure.h) is the RMS of luma minus a small blur over the pixels the carve
// changes; each mode is also given relative to solid shading of the same view and the same rules, which has
// no lighting of its own: what solid shows is the data and the entry depth.
#include "tools/bench/bench_cut_face.h"

#include "tools/bench/report.h"
#include "session/loaded_scene.h"
#include "base/error.h"
#include "plan/removal_field.h"
#include "render/model/cut_face_measure.h"
#include "render/reference/raycast_reference.h"
#include "render/renderer.h"
#include "mesh/surface_normals.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

namespace curette::bench {

namespace {

using Clock = std::chrono::steady_clock;

// A box of homogeneous tissue (value 128 with +-4 of white noise, the noise a scanner leaves in a
// homogeneous region) carved by a sphere through its top face: every structure on its cut face is an
// artefact.
constexpr const char* kUniformScene = R"({
  "volume": {"path": "uniform"},
  "transfer_function": {"name": "uniform tissue", "unit_length_mm": 1.0,
                        "color": [[0, 0.85, 0.72, 0.62], [255, 0.85, 0.72, 0.62]],
                        "opacity": [[0, 0], [90, 0], [110, 0.35], [255, 0.35]]},
  "camera": {"target": [0, 0, 28], "distance_mm": 240, "azimuth_deg": 20, "elevation_deg": 40, "fov_deg": 22},
  "shading": "cao",
  "lights": [{"direction": [0.4, 0.6, 1.0], "color": [1, 1, 1], "intensity": 1.0, "space": "camera"}],
  "image": {"width": 384, "height": 384, "background": [0.06, 0.07, 0.09, 1]},
  "raycast": {"step_mm": 0.5, "jitter_seed": 1},
  "ambient_occlusion": {"rays": "26", "samples": 12, "step_mm": 1.0, "antialiasing_samples": 32},
  "clip_meshes": [{"name": "sphere", "mesh": {"shape": "sphere", "radius_mm": 26}, "position_mm": [4, -3, 44]}]
})";

LoadedScene uniformScene() {
    LoadedScene loaded;
    loaded.scene = parseScene(kUniformScene, "<bench cut-face: uniform>");
    VolumeData& v = loaded.volume;
    v.dims = glm::ivec3(96);
    v.indexToWorld = glm::dmat4(1.0);
    v.indexToWorld[3] = glm::dvec4(-47.5, -47.5, -47.5, 1.0);
    v.format = StorageFormat::UNorm8;
    v.sourceType = ScalarType::UInt8;
    v.valueScale = 255.0;
    v.source = "uniform tissue (bench cut-face)";
    v.voxels.resize(v.voxelCount());
    std::mt19937 random(5);
    std::uniform_int_distribution<int> noise(-4, 4);
    for (std::uint8_t& voxel : v.voxels) voxel = static_cast<std::uint8_t>(128 + noise(random));
    v.minValue = 124;
    v.maxValue = 132;
    return loaded;
}

// The CPU twin's clip normal: the surface normal (mesh/surface_normals.h, what the GPU draws into its normal
// maps) at the point of any of the scene's meshes nearest the world point.
struct TwinMesh {
    const SceneClipMesh* mesh;
    std::vector<glm::vec3> corners;
};

glm::dvec3 nearestSurfaceNormal(const std::vector<TwinMesh>& meshes, glm::dvec3 world) {
    double best = 1e300;
    glm::dvec3 normal(0, 0, 1);
    for (const TwinMesh& m : meshes) {
        glm::dmat4 toWorld = m.mesh->pose.matrix();
        glm::dvec3 local = glm::dvec3(glm::inverse(toWorld) * glm::dvec4(world, 1.0));
        clip::SurfacePoint p = clip::nearestSurfacePoint(*m.mesh->geometry, m.mesh->scale, m.corners, local);
        double d = glm::length(p.point - local);
        if (d < best) {
            best = d;
            normal = glm::normalize(glm::dmat3(toWorld) * p.normal);
        }
    }
    return normal;
}

}  // namespace

int benchCutFace(const CommandLine& cl) {
    bool uniform = cl.flag("uniform");
    std::string scenePath = cl.valueOr("scene", "assets/scenes/head-cut-face.json");
    LoadedScene loaded = uniform ? uniformScene() : loadSceneWithVolume(scenePath);
    if (loaded.scene.clipMeshes.empty())
        throw InputError(scenePath, "clip_meshes", "at least one clip mesh (the bench measures its cut face)", "none");
    glm::ivec2 size = CommandLine::parseSize("size", cl.valueOr("size", "384x384"));
    int frames = CommandLine::parseInt("frames", cl.valueOr("frames", "3"), 1, 1000);
    std::string jsonPath = cl.valueOr("json", "bench-cut-face.json");
    std::string imageDir = cl.valueOr("images", "");
    std::vector<ShadingMode> modeList{ShadingMode::Solid};
    for (ShadingMode mode : parseShadingList("modes", cl.valueOr("modes", "phong,cao,lao,ismos,dos")))
        if (mode != ShadingMode::Solid) modeList.push_back(mode);
    const double sigmaPx = 1.0, maskThreshold = 0.004;
    const int erodePx = 4;

    auto context = gl::createHeadlessContext(gpuChoice(cl));
    Renderer carved(*context, loaded.volume, loaded.scene.transferFunction);
    configureRenderer(loaded, carved);
    // The carved pixels are found with the TF's opacity scaled down a hundredfold, so every ray runs through
    // the whole volume and the colour grows with the tissue it crosses: the carve shows wherever it removes
    // tissue from a ray, even in homogeneous tissue, where solid shading of the real TF looks the same with and
    // without the carve.
    LoadedScene thin = loaded;
    for (auto& point : thin.scene.transferFunction.opacity) point.y *= 0.01;
    Renderer thinCarved(*context, thin.volume, thin.scene.transferFunction);
    configureRenderer(thin, thinCarved);
    thin.scene.clipMeshes.clear();
    Renderer thinWhole(*context, thin.volume, thin.scene.transferFunction);
    configureRenderer(thin, thinWhole);

    FrameDescription base = initialFrame(loaded.scene, carved.geometry());
    base.size = size;
    if (auto d = cl.value("normal-depth")) base.raycast.cutFace.normalDepthMm = CommandLine::parseDouble("normal-depth", *d, 0.01, 100);
    if (auto o = cl.value("normal-opacity")) base.raycast.cutFace.normalOpacity = CommandLine::parseDouble("normal-opacity", *o, 0.01, 1.0);
    glm::vec4 background(loaded.scene.background);
    std::printf("curette bench cut-face: %s, %dx%d, %s\n", uniform ? "uniform tissue (96^3, 1 mm)" : scenePath.c_str(),
                size.x, size.y, context->info().renderer.c_str());

    auto render = [&](Renderer& r, FrameDescription f, double* ms) {
        r.render(f);
        r.finish();
        if (ms) {
            std::vector<double> times;
            for (int i = 0; i < frames; ++i) {
                auto start = Clock::now();
                r.render(f);
                r.finish();
                times.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
            }
            *ms = median(times);
        }
        return r.readImage();
    };
    FrameDescription solidFrame = base;
    solidFrame.shading = ShadingMode::Solid;
    std::vector<bool> mask = carvedPixels(render(thinCarved, solidFrame, nullptr), render(thinWhole, solidFrame, nullptr),
                                          background, maskThreshold, erodePx);
    std::size_t maskPixels = static_cast<std::size_t>(std::count(mask.begin(), mask.end(), true));
    // The face pixels: carved pixels whose colour comes from the tissue just behind a cut face, found as those
    // that phong shows differently when the face normal lights everything behind the face and when it lights
    // nothing. The rest of the carved pixels show what the carve uncovered through transparent tissue (the
    // brain's own surface under a cut through dark bone, say), which no face rule should touch.
    FrameDescription allFace = base, noFace = base;
    allFace.shading = noFace.shading = ShadingMode::Phong;
    allFace.raycast.cutFace.enabled = noFace.raycast.cutFace.enabled = true;
    allFace.raycast.cutFace.normalDepthMm = 100.0;
    allFace.raycast.cutFace.normalOpacity = 0.999;
    noFace.raycast.cutFace.normalDepthMm = 0.01;
    noFace.raycast.cutFace.normalOpacity = 0.01;
    std::vector<bool> faceMask = carvedPixels(render(carved, allFace, nullptr), render(carved, noFace, nullptr), background,
                                              maskThreshold, erodePx);
    for (std::size_t i = 0; i < faceMask.size(); ++i) faceMask[i] = faceMask[i] && mask[i];
    std::size_t facePixels = static_cast<std::size_t>(std::count(faceMask.begin(), faceMask.end(), true));

    Table table("Cut-face roughness: RMS of luma - Gaussian(sigma " + std::to_string(sigmaPx).substr(0, 3) + " px) over the " +
                    std::to_string(maskPixels) + " carved pixels and the " + std::to_string(facePixels) + " face pixels among them",
                {"shading", "cut faces", "HF RMS carved", "/ solid's", "HF RMS face", "/ solid's", "ms/frame (median, ray cast + cached AO)",
                 "max error vs CPU twin", "rms error vs CPU twin"});
    // The CPU double twin (render/reference/raycast_reference) models the same rules for solid and phong,
    // with the meshes' exact inside test (winding number) and their surface normals: on face pixels.
    std::vector<glm::ivec2> twinPixels;
    for (int y = 0, n = 0; y < size.y; ++y)
        for (int x = 0; x < size.x; ++x)
            if (faceMask[static_cast<std::size_t>(y * size.x + x)] && n++ % 97 == 0 && twinPixels.size() < 24) twinPixels.emplace_back(x, y);
    std::vector<plan::PosedMesh> posed;
    for (const SceneClipMesh& m : loaded.scene.clipMeshes) posed.push_back({m.geometry, m.pose, m.scale});
    reference::RaycastOptions twin;
    twin.clipped = plan::insideAnyMesh(posed);
    std::vector<TwinMesh> twinMeshes;
    for (const SceneClipMesh& m : loaded.scene.clipMeshes) twinMeshes.push_back({&m, clip::cornerNormals(*m.geometry, m.scale)});
    twin.clipNormal = [&](glm::dvec3 world) { return nearestSurfaceNormal(twinMeshes, world); };
    nlohmann::json modes = nlohmann::json::object();
    bool laoMatchesCao = true;
    for (bool on : {false, true}) {
        double solidHf = 0, solidFaceHf = 0;
        for (ShadingMode mode : modeList) {
            FrameDescription f = base;
            f.shading = mode;
            f.raycast.cutFace.enabled = on;
            double ms = 0;
            Image image = render(carved, f, &ms);
            double hf = highFrequencyRms(image, background, mask, sigmaPx);
            double faceHf = highFrequencyRms(image, background, faceMask, sigmaPx);
            if (!imageDir.empty())
                writePng(std::filesystem::path(imageDir) / (std::string(shadingModeName(mode)) + (on ? "-on.png" : "-off.png")), image, background);
            if (mode == ShadingMode::Solid) solidHf = hf, solidFaceHf = faceHf;
            if (mode == ShadingMode::Lao) {  // CAO's contract: the same image as full LAO
                FrameDescription c = f;
                c.shading = ShadingMode::Cao;
                laoMatchesCao = laoMatchesCao && render(carved, c, nullptr).pixels == image.pixels;
            }
            nlohmann::json twinMax, twinRms;
            if (mode == ShadingMode::Solid || mode == ShadingMode::Phong) {
                double maxError = 0, sum = 0;
                for (glm::ivec2 p : twinPixels) {
                    glm::dvec4 expected = reference::raycastPixel(loaded.volume, loaded.scene.transferFunction, f,
                                                                  carved.resolveStepMm(f.raycast), p, twin).rgba;
                    for (int c = 0; c < 4; ++c) {
                        double e = std::abs(double(image.at(p.x, p.y)[c]) - expected[c]);
                        maxError = std::max(maxError, e);
                        sum += e * e;
                    }
                }
                twinMax = maxError;
                twinRms = twinPixels.empty() ? 0.0 : std::sqrt(sum / (4.0 * double(twinPixels.size())));
            }
            auto ratio = [](double x, double floor) { return floor > 1e-3 ? nlohmann::json(x / floor) : nlohmann::json(); };
            table.add({shadingModeName(mode), on ? "on" : "off", hf, ratio(hf, solidHf), faceHf, ratio(faceHf, solidFaceHf), ms, twinMax, twinRms});
            modes[std::string(shadingModeName(mode)) + (on ? " on" : " off")] = {{"hf_rms", hf}, {"hf_rms_face", faceHf}, {"ms", ms}};
        }
    }
    table.print();
    std::printf("(HF: high-frequency energy of the composited luma, 0..1 units; a smooth face scores near 0. Cut faces\n"
                " off: the sample lattice alone; on: the first sample on the face with its partial length (every mode,\n"
                " dos in the slab pass), the face's normal behind it up to opacity %.2g or %.2g mm (phong, ismos over phong).\n"
                " lao and cao images identical: %s. Twin: %zu face pixels, RGBA in [0, 1], against the CPU double\n"
                " twin with the same rules, the meshes' winding-number inside test and their surface normals.)\n",
                base.raycast.cutFace.normalOpacity, base.raycast.cutFace.normalDepthMm, laoMatchesCao ? "yes" : "NO", twinPixels.size());
    writeJson(jsonPath, {{"bench", "cut-face"},
                         {"scene", uniform ? "uniform" : scenePath},
                         {"size", {size.x, size.y}},
                         {"frames", frames},
                         {"carved_pixels", maskPixels},
                         {"face_pixels", facePixels},
                         {"blur_sigma_px", sigmaPx},
                         {"lao_equals_cao", laoMatchesCao},
                         {"renderer", context->info().renderer},
                         {"modes", modes},
                         {"tables", {table.toJson()}}});
    return laoMatchesCao ? 0 : 1;
}

}  // namespace curette::bench
