// curette bench ismos: image-space multidirectional occlusion shading (seed 003). Table A in the layout of
// the paper's Table 1 (local illumination, one light and two, full occlusion, partial occlusion on one layer
// and on four, with exact layer opacities and with the fit's alpha_app): ms per frame and the slowdown over
// LI beside the paper's (its head data set: compare ratios, not fps). Table B: the occlusion's error against
// the physical reference (rays through the real volume to many stratified points of the same light disks,
// cut by clip meshes, stopped by tube triangles) and the final colour's error against the colour that
// reference gives (eq. 3 and 15 with its occlusion), next to the time, over N, N_R, the layer count and fit vs
// exact, and the hard cases (among them synthetic tubes and a synthetic thin bright shell behind clear tissue).
#include "tools/bench/bench_ismos.h"

#include "tools/bench/report.h"
#include "session/loaded_scene.h"
#include "mesh/primitives.h"
#include "render/reference/ismos_reference.h"
#include "render/renderer.h"
#include "render/model/tube_geometry.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <random>

namespace curette::bench {

namespace {

using Clock = std::chrono::steady_clock;

// The paper's Table 1, head data set (256 x 256 x 225), fps.
struct PaperRow {
    const char* configuration;
    double fps;
};
constexpr PaperRow kPaperHead[] = {{"LI", 22.2},           {"1 L, FO", 19.6},          {"1 L, PO, 1", 16.1},     {"1 L, PO, m", 10.2},
                                   {"1 L, PO, 1, a_app", 11.0}, {"1 L, PO, m, a_app", 8.3}, {"2 Ls, FO", 18.1},       {"2 Ls, PO, 1", 15.3},
                                   {"2 Ls, PO, m", 8.1},   {"2 Ls, PO, 1, a_app", 8.9}, {"2 Ls, PO, m, a_app", 6.9}};

struct Result {
    double ms = 0, occlusionMs = 0;
};

// What full occlusion adds to LI, ms.
struct Overheads {
    double oneLight = 0, twoLights = 0;
};

// The two tables' shared state: the head scene, its renderer, the base frame (ISMOS, two lights) and, for
// Table B, the reference's settings, its cache and the table the rows go to.
struct IsmosBench {
    LoadedScene& loaded;
    Renderer& renderer;
    FrameDescription base;
    FrameDescription one;  // base with its first light only
    int frames = 0, referencePixels = 0, referencePoints = 0;
    reference::PhysicalSettings physical;
    std::map<std::tuple<int, int, float, int>, double> referenceCache;   // (x, y, z, set-up id) -> Occ
    Table tableB;
    int id = 1;  // the reference cache's set-up of the next hard case (0: the head lit as `one`)

    IsmosBench(LoadedScene& scene, Renderer& r, const FrameDescription& frame, int frameCount, int pixels, int points)
        : loaded(scene), renderer(r), base(frame), one(frame), frames(frameCount), referencePixels(pixels), referencePoints(points),
          tableB("ISMOS occlusion and colour vs the physical reference (" + std::to_string(points) +
                     " stratified points per disk; colour: C_p I_L max(1 - Occ_ref, I_amb), C_p the pass-1 colour)",
                 {"configuration", "pixels", "ms/frame", "RMS", "max", "share > 0.1", "RMS / mean shadow", "RMS vs same-N reference",
                  "colour RMS", "colour max", "colour share > 0.1"}) {
        one.lights.resize(1);
    }

    // A target is a renderer with its volume and TF and the pixels the reference is computed at (pixels with
    // a layer, picked at random with a fixed seed).
    struct Target {
        Renderer* renderer;
        const VolumeData* volume;
        const TransferFunction* tf;
        std::vector<glm::ivec2> pixels;
    };

    Result measure(Renderer& r, const FrameDescription& frame) const;
    std::vector<glm::ivec2> layeredPixels(Renderer& r, FrameDescription f, unsigned seed, const std::function<bool(glm::ivec2)>& accept) const;
    Target headTarget(const FrameDescription& f, unsigned seed, const std::function<bool(glm::ivec2)>& accept = {}) {
        return Target{&renderer, &loaded.volume, &loaded.scene.transferFunction, layeredPixels(renderer, f, seed, accept)};
    }
    void evaluate(const std::string& name, Target& target, const FrameDescription& f, int setupId, bool sameN);

    Overheads tableA(nlohmann::json& tables);
    void sweeps(Target& head);
    void hardLights(Target& head);
    void colouredLights(Target& head);
    void spotlight(Target& head);
    void occludersOutsideTheScreen();
    void clipMeshCutWalls(Target& head);
    void tubes();
    void thinShell(gl::Context& context);
};

Result IsmosBench::measure(Renderer& r, const FrameDescription& frame) const {
    std::vector<double> wall, occlusion;
    for (int f = -1; f < frames; ++f) {
        FrameDescription current = frame;
        current.camera.azimuthDeg += 2.0 * (f + 1);   // a moving camera: every frame rebuilds everything
        r.collectTimings();
        auto start = Clock::now();
        r.render(current);
        r.finish();
        double ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
        FrameTimings t = r.collectTimings();
        if (f < 0) continue;
        wall.push_back(ms);
        occlusion.push_back(t.ms(Pass::IsmosOcclusion));
    }
    return Result{median(wall), median(occlusion)};
}

// ---- Table A: the paper's Table 1 layout.
Overheads IsmosBench::tableA(nlohmann::json& tables) {
    const IsmosSettings& s0 = base.ismos;
    char setup[200];
    std::snprintf(setup, sizeof setup, "N %d, N_R %d, R %.2f, d %.2f, I_amb %.2f, alpha_th %.2f", s0.lightSamples, s0.testPoints,
                  s0.hemisphereRadius, s0.diskRadius, s0.ambient, s0.opacityThreshold);
    Table table(std::string("Seed 003 Table 1 layout (") + setup + ")",
                {"configuration", "ms/frame", "pass 2 ms", "slowdown over LI", "paper slowdown (head, GTX 295)", "paper fps"});
    FrameDescription li = base;
    li.shading = ShadingMode::Phong;
    li.lights.resize(1);
    Result liResult = measure(renderer, li);
    table.add({"LI (phong)", liResult.ms, 0.0, 1.0, 1.0, kPaperHead[0].fps});
    // Phong with two lights costs more than with one: the 2-light rows are measured against LI with both.
    FrameDescription li2 = base;
    li2.shading = ShadingMode::Phong;
    li2.lights.resize(2);
    Result li2Result = measure(renderer, li2);
    table.add({"LI (phong), 2 lights", li2Result.ms, 0.0, 1.0, 1.0, nlohmann::json()});
    struct Config {
        bool partial, fit;
        int layers;
    };
    const Config configs[] = {{false, false, 1}, {true, false, 1}, {true, false, 4}, {true, true, 1}, {true, true, 4}};
    double overhead1 = 0, overhead2 = 0;
    int row = 1;
    for (int lights = 1; lights <= 2; ++lights)
        for (Config c : configs) {
            FrameDescription f = base;
            f.lights.resize(static_cast<std::size_t>(lights));
            f.ismos.partial = c.partial;
            f.ismos.fit = c.fit;
            f.ismos.layers = c.layers;
            f.ismos.blendLayers = c.layers > 1;
            Result r = measure(renderer, f);
            const PaperRow& paper = kPaperHead[row++];
            double liMs = lights == 1 ? liResult.ms : li2Result.ms;
            table.add({paper.configuration, r.ms, r.occlusionMs, r.ms / liMs, kPaperHead[0].fps / paper.fps, paper.fps});
            if (!c.partial) (lights == 1 ? overhead1 : overhead2) = r.ms - liMs;
        }
    table.print();
    std::printf("full occlusion adds %.0f ms (1 light, LI %.0f ms) and %.0f ms (2 lights, LI %.0f ms); the paper: 13.8 and 25.6 ms on "
                "45 ms (head: 22.2 -> 19.6 and 18.1 fps)\n",
                overhead1, liResult.ms, overhead2, li2Result.ms);
    tables.push_back(table.toJson());
    return {overhead1, overhead2};
}

std::vector<glm::ivec2> IsmosBench::layeredPixels(Renderer& r, FrameDescription f, unsigned seed,
                                                  const std::function<bool(glm::ivec2)>& accept) const {
    const int count = referencePixels;
    f.ismos.layers = 4;
    r.render(f);
    IsmosLayerImages layers = r.ismos()->readLayers();
    std::vector<glm::ivec2> out;
    std::mt19937 random(seed);
    std::uniform_int_distribution<int> px(0, f.size.x - 1), py(0, f.size.y - 1);
    for (int attempts = 0; static_cast<int>(out.size()) < count && attempts < 200000; ++attempts) {
        glm::ivec2 p(px(random), py(random));
        if (layers.front[layers.index(p)].x != -1.0f && (!accept || accept(p))) out.push_back(p);
    }
    return out;
}

// Per pixel the shaded layers and their weights, as pass 2 chooses them (ismos_occlusion.comp).
std::vector<std::pair<double, double>> shadedLayers(const IsmosLayerImages& l, const IsmosSettings& s, glm::ivec2 p) {
    std::vector<std::pair<double, double>> out;   // (z, weight)
    const glm::vec4& f = l.front[l.index(p)];
    const glm::vec4& a = l.alpha[l.index(p)];
    int n = std::clamp(s.layers, 1, 4);
    double before = 1;
    for (int k = 0; k < n; ++k) {
        if (f[k] == -1.0f) break;
        if (n == 1) return std::vector<std::pair<double, double>>{{f[k], 1.0}};
        if (s.blendLayers) {
            out.emplace_back(f[k], a[k] * before);
            before *= 1.0 - a[k];
        } else if (a[k] >= s.opacityThreshold) {
            out.emplace_back(f[k], 1.0);
            break;
        }
    }
    return out;
}

// One row of Table B: the GPU's occlusion (pass 2's CPU twin on the GPU's own layers, equal to the GPU to
// float precision: Ismos.OcclusionPassMatchesCpuTwinOnReadBackLayers) and the GPU's final colour against the
// reference at the target's pixels; `setupId` keys the reference cache (same lights, camera and scene).
void IsmosBench::evaluate(const std::string& name, Target& target, const FrameDescription& f, int setupId, bool sameN) {
    Renderer& r = *target.renderer;
    Result timing = measure(r, f);
    r.ismos()->capturePass1Colour(true);
    r.render(f);
    Image image = r.readImage();
    std::vector<glm::vec4> pass1 = r.ismos()->pass1Colour();
    r.ismos()->capturePass1Colour(false);
    IsmosLayerImages layers = r.ismos()->readLayers();
    const std::vector<IsmosLight>& lights = r.ismos()->lights();
    IsmosSpace sp = r.ismosSpaceOf(f);
    glm::dvec3 centre = r.geometry().worldCenter();
    double stepDepth = r.resolveStepMm(f.raycast) / (sp.farMm - sp.nearMm);
    std::vector<std::vector<glm::dvec3>> many, own;
    for (const IsmosLight& l : lights) {
        many.push_back(diskSamples(l.centre, l.normal, l.diskRadius, referencePoints));
        own.push_back(l.samples);
    }
    double sum = 0, worst = 0, strength = 0, sumSame = 0, colourSum = 0, colourWorst = 0;
    int over = 0, colourOver = 0, n = 0;
    for (glm::ivec2 p : target.pixels) {
        reference::IsmosPixel got = reference::ismosOcclusionPixel(layers, lights, f.ismos, sp, stepDepth, p);
        if (!got.shaded) continue;
        double expected = 0, expectedSame = 0, weights = 0;
        glm::dvec2 xy = (glm::dvec2(p) + 0.5) / glm::dvec2(f.size);
        for (auto [z, w] : shadedLayers(layers, f.ismos, p)) {
            auto key = std::make_tuple(p.x, p.y, static_cast<float>(z), setupId);
            auto found = referenceCache.find(key);
            if (found == referenceCache.end())
                found = referenceCache.emplace(key, reference::physicalOcclusion(*target.volume, *target.tf, sp, centre, lights, many,
                                                                                 glm::dvec3(xy, z), physical)).first;
            expected += w * found->second;
            if (sameN)
                expectedSame += w * reference::physicalOcclusion(*target.volume, *target.tf, sp, centre, lights, own, glm::dvec3(xy, z), physical);
            weights += w;
        }
        if (weights <= 0) continue;
        expected /= weights;
        expectedSame /= weights;
        double e = std::abs(got.occlusion - expected);
        sum += e * e;
        worst = std::max(worst, e);
        over += e > 0.1;
        strength += expected;
        sumSame += (got.occlusion - expectedSame) * (got.occlusion - expectedSame);
        // Eq. 3 and 15 with the reference's occlusion, against the colour pass 2 wrote.
        std::size_t i = static_cast<std::size_t>(p.y) * static_cast<std::size_t>(f.size.x) + static_cast<std::size_t>(p.x);
        glm::dvec3 reference = glm::dvec3(pass1[i]) * got.light * std::max(1.0 - expected, f.ismos.ambient);
        double pixelWorst = 0;
        for (int c = 0; c < 3; ++c) {
            double ec = std::abs(static_cast<double>(image.pixels[i][c]) - reference[c]);
            colourSum += ec * ec;
            pixelWorst = std::max(pixelWorst, ec);
        }
        colourWorst = std::max(colourWorst, pixelWorst);
        colourOver += pixelWorst > 0.1;
        ++n;
    }
    double rms = n ? std::sqrt(sum / n) : 0;
    tableB.add({name, n, timing.ms, rms, worst, n ? double(over) / n : 0.0, strength > 0 ? rms / (strength / n) : 0.0,
                sameN && n ? nlohmann::json(std::sqrt(sumSame / n)) : nlohmann::json(), n ? std::sqrt(colourSum / (3.0 * n)) : 0.0,
                colourWorst, n ? double(colourOver) / n : 0.0});
    std::fflush(stdout);
}

// N, N_R, the layer count with the fit and exact, and full occlusion, on the head lit as `one`.
void IsmosBench::sweeps(Target& head) {
    for (int n : {1, 4, 16, 64}) {
        FrameDescription f = one;
        f.ismos.lightSamples = n;
        evaluate("N " + std::to_string(n), head, f, 0, true);
    }
    for (int nr : {8, 16, 32, 64}) {
        FrameDescription f = one;
        f.ismos.testPoints = nr;
        evaluate("N_R " + std::to_string(nr), head, f, 0, false);
    }
    for (int layers = 1; layers <= 4; ++layers)
        for (bool fit : {false, true}) {
            FrameDescription f = one;
            f.ismos.layers = layers;
            f.ismos.fit = fit;
            evaluate("layers " + std::to_string(layers) + (fit ? ", fit (alpha_app)" : ", exact"), head, f, 0, false);
        }
    FrameDescription f = one;
    f.ismos.partial = false;
    evaluate("full occlusion", head, f, 0, false);
}

double rad(double deg) { return glm::radians(deg); }

// Hard cases (the list: grazing, overhead, behind, d = 0, a disk larger than the box, a thin bright
// shell behind clear tissue, 2-4 coloured lights, spotlight cone edges, occluders outside the screen,
// clip-mesh cut walls, tubes), one row each. These: where the light is, and its disk.
void IsmosBench::hardLights(Target& head) {
    auto withLight = [&](glm::dvec3 cameraDirection) {
        FrameDescription f = one;
        f.lights[0].direction = cameraDirection;
        f.lights[0].cameraSpace = true;
        f.ismos.lightShapes.clear();
        return f;
    };
    evaluate("hard: grazing light, phi 5 deg", head, withLight({std::cos(rad(5)), 0, std::sin(rad(5))}), id++, false);
    evaluate("hard: grazing light, phi 15 deg", head, withLight({std::cos(rad(15)), 0, std::sin(rad(15))}), id++, false);
    {
        FrameDescription f = withLight({0, 0, 1});
        f.ismos.diskRadius = 1.5;
        f.ismos.hemisphereRadius = 1.5;
        evaluate("hard: light overhead, AO set-up (R 1.5, d 1.5)", head, f, id++, false);
    }
    {
        FrameDescription f = withLight({0.3, 0.2, -1.0});
        f.ismos.sphere = true;
        evaluate("hard: light behind the volume (sphere)", head, f, id++, false);
    }
    {
        FrameDescription f = one;
        f.ismos.lightShapes.clear();
        f.ismos.diskRadius = 0;
        evaluate("hard: d = 0 (hard shadow)", head, f, id++, false);
    }
    FrameDescription f = one;
    f.ismos.lightShapes.clear();
    f.ismos.diskRadius = 2.5;
    evaluate("hard: disk larger than the box (d 2.5)", head, f, id++, false);
}

void IsmosBench::colouredLights(Target& head) {
    // Coloured lights over a solid base (eq. 15 tints by the light's colour there), no spot.
    const Light coloured[] = {Light{{0.7, 0.5, 0.6}, {1.0, 0.85, 0.6}, true}, Light{{-0.6, 0.6, 0.5}, {0.4, 0.6, 1.0}, true},
                              Light{{0.0, -0.7, 0.7}, {0.3, 1.0, 0.3}, true}, Light{{0.0, 0.9, 0.4}, {1.0, 0.3, 0.3}, true}};
    for (int count = 2; count <= 4; ++count) {
        FrameDescription f = base;
        f.lights.assign(coloured, coloured + count);
        f.ismos.lightShapes.clear();
        f.ismos.base = ShadingMode::Solid;
        evaluate("hard: " + std::to_string(count) + " coloured lights (solid base)", head, f, id++, false);
    }
    FrameDescription f = base;
    f.ismos.lightShapes.clear();
    f.lights.push_back(Light{{0.0, -0.7, 0.7}, {0.3, 1.0, 0.3}, true});
    f.lights.push_back(Light{{0.0, 0.9, 0.4}, {1.0, 0.3, 0.3}, true});
    evaluate("hard: 4 coloured lights (phong base)", head, f, id++, false);
}

void IsmosBench::spotlight(Target& head) {
    // The pixels within 3 degrees of the cone's edge, as seen from the light's centre.
    FrameDescription f = one;
    f.ismos.lightShapes = {IsmosLightShape{-1, 10.0, {}}};
    renderer.render(f);
    IsmosLight light = renderer.ismos()->lights().at(0);
    IsmosLayerImages layers = renderer.ismos()->readLayers();
    Target edges = headTarget(f, 12, [&](glm::ivec2 p) {
        glm::dvec3 tex((p.x + 0.5) / f.size.x, (p.y + 0.5) / f.size.y, layers.front[layers.index(p)].x);
        glm::dvec3 a = glm::normalize(tex - light.centre), b = glm::normalize(light.spotTarget - light.centre);
        return std::abs(std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0)) - std::acos(light.cosOmega)) < rad(3.0);
    });
    evaluate("hard: spotlight, 10 deg cone (all pixels)", head, f, id, false);
    evaluate("hard: spotlight, 10 deg cone (within 3 deg of its edge)", edges, f, id++, false);
}

void IsmosBench::occludersOutsideTheScreen() {
    FrameDescription f = one;
    f.camera.distanceMm *= 0.6;   // zoomed in: part of the head, and of its occluders, leaves the image
    Target zoomed = headTarget(f, 13);
    evaluate("hard: occluders outside the screen (zoom 1/0.6)", zoomed, f, id++, false);
}

void IsmosBench::clipMeshCutWalls(Target& head) {
    // A sphere cut into the head on the camera's side: its walls are shadowed with nothing precomputed.
    // The reference clips analytically; the GPU through the clip maps (a map pixel apart at the cut).
    glm::dvec3 centre = renderer.geometry().worldCenter();
    glm::dvec3 cut = centre - 0.5 * renderer.geometry().boundingRadiusMm() * one.camera.forward();
    double radius = 0.35 * renderer.geometry().boundingRadiusMm();
    renderer.clipMeshes().add(std::make_shared<const clip::TriangleMesh>(clip::makeSphere(radius, 4)), glm::dvec3(1.0),
                              clip::RigidPose{cut, glm::dquat(1, 0, 0, 0)}, "cut");
    physical.insideClip = [cut, radius](glm::dvec3 w) { return glm::length(w - cut) < radius; };
    evaluate("hard: clip-mesh cut walls (sphere)", head, one, id++, false);
    physical.insideClip = {};
    renderer.clipMeshes().clear();
}

// Synthetic streamlines, four across the face in front of the head and two beside it (as seen from `one`).
Tractogram syntheticTracts(const Renderer& renderer, const FrameDescription& one) {
    glm::dvec3 centre = renderer.geometry().worldCenter();
    double R = renderer.geometry().boundingRadiusMm();
    glm::dvec3 right = one.camera.right(), up = one.camera.up(), forward = one.camera.forward();
    Tractogram tracts;
    auto streamline = [&](glm::dvec3 from, glm::dvec3 to) {
        for (int i = 0; i <= 32; ++i) tracts.points.push_back(glm::vec3(from + (to - from) * (i / 32.0)));
        tracts.offsets.push_back(static_cast<std::uint32_t>(tracts.points.size()));
    };
    for (double u : {-0.3, -0.1, 0.1, 0.3}) {
        glm::dvec3 c = centre - 0.7 * R * forward + u * R * up;
        streamline(c - 0.6 * R * right, c + 0.6 * R * right);
    }
    for (double s : {-0.75, 0.75}) {
        glm::dvec3 c = centre + s * R * right;
        streamline(c - 0.5 * R * up, c + 0.5 * R * up);
    }
    return tracts;
}

void IsmosBench::tubes() {
    // Tubes lit from the side, so tubes shadow the volume and the volume shadows tubes. The reference's rays
    // stop at their triangles; the rows split the pixels on the tubes from the volume pixels in their shadow.
    glm::dvec3 centre = renderer.geometry().worldCenter();
    Tractogram tracts = syntheticTracts(renderer, one);
    TubeSettings settings;
    settings.radiusMm = 2.0;
    settings.sides = 8;
    settings.smoothing = TubeSettings::Smoothing::None;
    settings.coloring = TubeSettings::Coloring::Uniform;
    TubeVertices tubes = buildTubes(tracts, settings);
    TubeShading shading = loaded.scene.tubeShading;
    shading.thicknessMm = 2.0 * settings.radiusMm;
    renderer.setTubes(tubes, shading);
    reference::OccluderTriangles occluders(tubes);
    physical.tubes = &occluders;
    FrameDescription f = one;
    renderer.render(f);
    std::vector<float> tubeDepth = renderer.gbuffer().readDepth();
    IsmosSpace sp = renderer.ismosSpaceOf(f);
    IsmosLayerImages layers = renderer.ismos()->readLayers();
    glm::dvec3 lightCentre = reference::lightPointWorld(sp, centre, renderer.ismos()->lights().at(0).centre);
    auto onTube = [&](glm::ivec2 p) { return tubeDepth[static_cast<std::size_t>(p.y) * static_cast<std::size_t>(f.size.x) + static_cast<std::size_t>(p.x)] > 0; };
    // A volume pixel "in a tube's shadow" by geometry, not by what the GPU drew: the path from its shaded
    // point to the light's centre passes within two tube radii plus the penumbra's width of a tube.
    double halfAngle = std::atan(f.ismos.diskRadius / f.ismos.hemisphereRadius);
    auto inTubeShadow = [&](glm::ivec2 p) {
        if (onTube(p)) return false;
        glm::dvec3 w = sp.toWorld({(p.x + 0.5) / f.size.x, (p.y + 0.5) / f.size.y, layers.front[layers.index(p)].x});
        glm::dvec3 d = glm::normalize(lightCentre - w);
        for (std::size_t s = 0; s + 1 < tracts.offsets.size(); ++s) {
            glm::dvec3 a(tracts.points[tracts.offsets[s]]), b(tracts.points[tracts.offsets[s + 1] - 1]);
            // Closest approach of the line w + t d (t > 0) and the segment a b.
            glm::dvec3 e = b - a, r0 = w - a;
            double dd = glm::dot(d, e), ee = glm::dot(e, e), denom = ee - dd * dd;
            double sParam = denom > 1e-12 ? std::clamp((glm::dot(r0, e) - dd * glm::dot(r0, d)) / denom, 0.0, 1.0) : 0.0;
            glm::dvec3 q = a + sParam * e;
            double t = std::max(glm::dot(q - w, d), 0.0);
            if (glm::length(w + t * d - q) < 2.0 * settings.radiusMm + t * std::tan(halfAngle)) return true;
        }
        return false;
    };
    Target onTubes = headTarget(f, 14, onTube);
    Target shadowed = headTarget(f, 15, inTubeShadow);
    evaluate("hard: tubes, pixels on the tubes (the volume shadows them)", onTubes, f, id, false);
    evaluate("hard: tubes, volume pixels in their shadow", shadowed, f, id, false);
    // The test points' spacing (1/N_R of the path, ~10 mm here, more than a tube's 4 mm, the paper's Fig.
    // 4a) against the layers' own error: a tube is a layer as thick as its chord (ismos_layers.glsl), the
    // tissue's layers are what the ray caster saw of them.
    FrameDescription dense = f;
    dense.ismos.testPoints = 256;
    evaluate("hard: tubes, volume pixels in their shadow, N_R 256", shadowed, dense, id++, false);
    physical.tubes = nullptr;
    renderer.clearTubes();
}

void IsmosBench::thinShell(gl::Context& context) {
    // A thin bright shell behind clear tissue, the transmittance fit's worst case: a 10 mm slab of clear
    // tissue (0.01 per unit length) in front, a 3.5 mm gap, then a 1.5 mm shell of radius 13.5 mm
    // (0.95), on a 64^3 grid of 1 mm voxels, seen and lit as the head. Along a pixel through the shell
    // T(z) stays near 1 and then drops at once: exp(-beta z^2) puts opacity where there is none.
    FrameDescription f = one;
    f.camera.target = glm::dvec3(0.0);
    f.camera.distanceMm = 280.0;
    f.camera.fovYDeg = 20.0;
    glm::dvec3 towardsCamera = -f.camera.forward();
    const glm::ivec3 dims(64);
    std::vector<std::uint8_t> voxels(static_cast<std::size_t>(dims.x) * dims.y * dims.z);
    glm::dmat4 affine(1.0);
    affine[3] = glm::dvec4(glm::dvec3(-31.5), 1.0);
    std::size_t index = 0;
    for (int k = 0; k < dims.z; ++k)
        for (int j = 0; j < dims.y; ++j)
            for (int i = 0; i < dims.x; ++i, ++index) {
                glm::dvec3 p(affine * glm::dvec4(i, j, k, 1.0));
                double r = glm::length(p), s = glm::dot(p, towardsCamera);
                voxels[index] = r > 12.0 && r < 13.5 ? 250 : s > 17.0 && s < 27.0 ? 60 : 0;
            }
    VolumeData shell = buildVolume("<thin shell behind clear tissue>", dims, ScalarType::UInt8, voxels.data(), false, 1.0, 0.0, affine);
    TransferFunction tf;
    tf.name = "thin shell";
    tf.color = {{0, {0.5, 0.6, 0.7}}, {100, {0.5, 0.6, 0.7}}, {200, {1, 1, 1}}, {255, {1, 1, 1}}};
    tf.opacity = {{0, 0}, {40, 0}, {45, 0.01}, {150, 0.01}, {200, 0.95}, {255, 0.95}};
    tf.material = loaded.scene.transferFunction.material;
    Renderer shellRenderer(context, shell, tf);
    reference::PhysicalSettings saved = physical;
    physical.stepMm = shellRenderer.resolveStepMm(f.raycast);
    physical.startOffsetMm = f.ismos.depthBias * shellRenderer.ismosSpaceOf(f).boxMm.z;
    Target target{&shellRenderer, &shell, &tf, layeredPixels(shellRenderer, f, 16, {})};
    for (bool fit : {true, false}) {
        FrameDescription g = f;
        g.ismos.fit = fit;
        evaluate(std::string("hard: thin bright shell behind clear tissue, ") + (fit ? "fit (alpha_app)" : "exact"), target, g, id, false);
    }
    ++id;
    physical = saved;
}

// The head's renderer, its own tubes left out (the tube rows bring their own), and the frame both tables
// start from: ISMOS with at least two lights (the second mirrors the first).
FrameDescription ismosBase(const LoadedScene& loaded, Renderer& renderer, glm::ivec2 size) {
    configureRenderer(loaded, renderer);
    renderer.clearTubes();
    FrameDescription base = initialFrame(loaded.scene, renderer.geometry());
    base.size = size;
    base.shading = ShadingMode::Ismos;
    if (base.lights.size() < 2) {
        Light mirrored = base.lights.empty() ? Light{} : base.lights[0];
        mirrored.direction.x = -mirrored.direction.x;
        base.lights.push_back(mirrored);
    }
    return base;
}

}  // namespace

int benchIsmos(const CommandLine& cl) {
    LoadedScene loaded = loadSceneWithVolume(cl.required("scene"));
    glm::ivec2 size = CommandLine::parseSize("size", cl.valueOr("size", "256x256"));
    int frames = CommandLine::parseInt("frames", cl.valueOr("frames", "3"), 1, 1000);
    int referencePixels = CommandLine::parseInt("reference-pixels", cl.valueOr("reference-pixels", "150"), 0, 100000);
    int referencePoints = CommandLine::parseInt("reference-points", cl.valueOr("reference-points", "64"), 1, 4096);
    std::string jsonPath = cl.valueOr("json", "bench-ismos.json");

    auto context = gl::createHeadlessContext(gpuChoice(cl));
    Renderer renderer(*context, loaded.volume, loaded.scene.transferFunction);
    FrameDescription base = ismosBase(loaded, renderer, size);
    const VolumeData& v = loaded.volume;
    std::printf("curette bench ismos: %s (%dx%dx%d), %dx%d, %d frames per configuration, %s\n", loaded.scene.volumePath.c_str(), v.dims.x,
                v.dims.y, v.dims.z, size.x, size.y, frames, context->info().renderer.c_str());

    IsmosBench bench(loaded, renderer, base, frames, referencePixels, referencePoints);
    nlohmann::json tables = nlohmann::json::array();
    const Overheads overheads = bench.tableA(tables);

    // ---- Table B: error against the physical reference.
    IsmosBench::Target head = bench.headTarget(base, 11);
    IsmosSpace space = renderer.ismosSpaceOf(base);
    bench.physical.stepMm = renderer.resolveStepMm(base.raycast);
    bench.physical.startOffsetMm = base.ismos.depthBias * space.boxMm.z;
    bench.sweeps(head);
    bench.hardLights(head);
    bench.colouredLights(head);
    bench.spotlight(head);
    bench.occludersOutsideTheScreen();
    bench.clipMeshCutWalls(head);
    bench.tubes();
    bench.thinShell(*context);
    bench.tableB.print();
    tables.push_back(bench.tableB.toJson());
    writeJson(jsonPath, {{"bench", "ismos"}, {"scene", cl.required("scene")}, {"size", {size.x, size.y}}, {"frames", frames},
                         {"renderer", context->info().renderer}, {"overhead_ms", {{"1 light FO", overheads.oneLight}, {"2 lights FO", overheads.twoLights}}},
                         {"tables", tables}});
    return 0;
}

}  // namespace curette::bench
