// ISMOS (seed 003): pass 2 against its CPU twin, analytic shadows and transmittance, the model's equations,
// the frame plan and the allocations of the mode.
#include "render/model/ismos_model.h"
#include "render/reference/ismos_reference.h"
#include "mesh/primitives.h"
#include "render/renderer.h"
#include "tests/render/gl_test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

namespace curette {
namespace {

using test::glContext;

FrameDescription frameAt(double distance, double azimuth, double elevation, glm::ivec2 size) {
    FrameDescription f = test::frameLookingAt(glm::dvec3(0.0), distance, azimuth, elevation, size, ShadingMode::Ismos);
    f.camera.fovYDeg = 20;
    f.camera.farMm = 5000;
    return f;
}

TransferFunction blobTf() {
    TransferFunction tf;
    tf.color = {{0, {0.1, 0.2, 0.6}}, {80, {0.9, 0.4, 0.2}}, {160, {1.0, 0.9, 0.7}}, {255, {1, 1, 1}}};
    tf.opacity = {{0, 0}, {40, 0}, {120, 0.3}, {200, 0.8}, {255, 0.9}};
    tf.material = {0.25, 0.7, 0.4, 24.0};
    return tf;
}

std::vector<Pass> passes(const FramePlan& plan) {
    std::vector<Pass> out;
    for (const PlannedPass& p : plan.passes) out.push_back(p.pass);
    return out;
}

// The ISMOS image and the base (phong) image of the same frame: their ratio is pass 2's factor.
struct Rendered {
    Image ismos, base;
    IsmosLayerImages layers;
    std::vector<IsmosLight> lights;
    IsmosSpace space;
    double stepDepth = 0;
};

Rendered renderBoth(Renderer& r, FrameDescription f) {
    Rendered out;
    f.shading = ShadingMode::Ismos;
    r.render(f);
    out.ismos = r.readImage();
    out.layers = r.ismos()->readLayers();
    out.lights = r.ismos()->lights();
    out.space = r.ismosSpaceOf(f);
    out.stepDepth = r.resolveStepMm(f.raycast) / (out.space.farMm - out.space.nearMm);
    f.shading = f.ismos.base;
    r.render(f);
    out.base = r.readImage();
    return out;
}

const std::vector<Light> kTwoLightsOneSpot = {Light{{0.6, 0.4, 0.7}, {1.0, 0.9, 0.8}, true}, Light{{-0.5, 0.6, 0.6}, {0.5, 0.6, 1.0}, true}};

// Pass 2 on the GPU equals its CPU twin on the GPU's own layers, in every variant.
TEST(Ismos, OcclusionPassMatchesCpuTwinOnReadBackLayers) {
    VolumeData v = test::makeVolume({48, 48, 48}, test::centredAffine({48, 48, 48}), ScalarType::Float32, test::blobField);
    Renderer r(glContext(), v, blobTf());
    struct Variant {
        bool partial, fit;
        int layers;
        bool blend;
        bool twoLights;
    };
    for (Variant var : {Variant{false, false, 1, false, false}, Variant{true, false, 4, true, false}, Variant{true, true, 4, true, false},
                        Variant{true, false, 1, false, true}, Variant{true, true, 2, false, true}, Variant{false, false, 4, true, true}}) {
        FrameDescription f = frameAt(220, 30, 20, {64, 64});
        f.ismos.partial = var.partial;
        f.ismos.fit = var.fit;
        f.ismos.layers = var.layers;
        f.ismos.blendLayers = var.blend;
        f.ismos.lightSamples = 8;
        f.ismos.testPoints = 24;
        if (var.twoLights) {
            f.lights = kTwoLightsOneSpot;
            f.ismos.lightShapes = {IsmosLightShape{0.1, 0, {}}, IsmosLightShape{0.3, 4.0, {}}};   // the cone's edge crosses the volume
        }
        Rendered got = renderBoth(r, f);
        int checked = 0, off = 0, shadowed = 0;
        double worst = 0;
        for (int y = 0; y < f.size.y; ++y)
            for (int x = 0; x < f.size.x; ++x) {
                reference::IsmosPixel twin = reference::ismosOcclusionPixel(got.layers, got.lights, f.ismos, got.space, got.stepDepth, {x, y});
                EXPECT_GE(twin.occlusion, 0.0);
                EXPECT_LE(twin.occlusion, 1.0);
                glm::vec4 base = got.base.at(x, y), ismos = got.ismos.at(x, y);
                EXPECT_EQ(base.a, ismos.a);
                for (int c = 0; c < 3; ++c) {
                    double expected = base[c] * twin.factor[c];
                    double e = std::abs(ismos[c] - expected);
                    worst = std::max(worst, e);
                    off += e > 1e-4;
                }
                ++checked;
                shadowed += twin.occlusion > 0.05;
            }
        std::printf("[ twin ] partial %d fit %d layers %d blend %d lights %zu: worst %.2e, %d of %d channel values off by > 1e-4, %d shadowed pixels\n",
                    var.partial, var.fit, var.layers, var.blend, f.lights.size(), worst, off, 3 * checked, shadowed);
        // float vs double: a test point on a pixel border can fall into the neighbour, flipping one path.
        EXPECT_LE(off, 3 * checked / 1000) << "more than 0.1 % of the values differ from the twin";
        EXPECT_GT(shadowed, 20) << "the scene must have shadows for the comparison to mean something";
    }
}

// d = 0: every light sample is the centre, so with full occlusion a pixel is either lit or in shadow.
TEST(Ismos, ZeroDiskRadiusGivesAHardShadow) {
    VolumeData v = test::makeVolume({48, 48, 48}, test::centredAffine({48, 48, 48}), ScalarType::Float32, test::blobField);
    Renderer r(glContext(), v, blobTf());
    FrameDescription f = frameAt(220, 30, 20, {64, 64});
    f.ismos.partial = false;
    f.ismos.diskRadius = 0.0;
    f.ismos.ambient = 0.0;
    Rendered got = renderBoth(r, f);
    int lit = 0, dark = 0, between = 0;
    for (int y = 0; y < f.size.y; ++y)
        for (int x = 0; x < f.size.x; ++x) {
            float b = got.base.at(x, y).g;
            if (b < 0.02f) continue;
            float ratio = got.ismos.at(x, y).g / b;
            if (ratio > 0.999f) ++lit;
            else if (ratio < 1e-3f) ++dark;
            else ++between;
        }
    std::printf("[ hard ] lit %d, shadow %d, between %d\n", lit, dark, between);
    EXPECT_GT(dark, 20);
    EXPECT_GT(lit, 20);
    EXPECT_EQ(between, 0);
    // ... and a disk gives a penumbra.
    f.ismos.diskRadius = 0.4;
    got = renderBoth(r, f);
    between = 0;
    for (int y = 0; y < f.size.y; ++y)
        for (int x = 0; x < f.size.x; ++x) {
            float b = got.base.at(x, y).g;
            if (b < 0.02f) continue;
            float ratio = got.ismos.at(x, y).g / b;
            between += ratio > 1e-3f && ratio < 0.999f;
        }
    EXPECT_GT(between, 10);
}

// An opaque ball in front of an opaque slab, a distant point light: the slab pixels in the ball's analytic
// shadow are dark; those outside the shadow of the ball's height-field column (the ball extruded away from
// the viewer, which is all the image-space model knows) are lit.
TEST(Ismos, OpaqueBallOverSlabCastsItsAnalyticShadow) {
    const glm::dvec3 ball(0, 6, 0);
    const double radius = 7.0, slabFront = -18.0;
    auto field = [&](glm::dvec3 p) {
        if (glm::length(p - ball) < radius) return 250.0;
        if (p.y < slabFront && p.y > -28) return 250.0;
        return 0.0;
    };
    VolumeData v = test::makeVolume({64, 64, 64}, test::centredAffine({64, 64, 64}), ScalarType::Float32, field);
    TransferFunction tf;
    tf.color = {{0, {1, 1, 1}}, {255, {1, 1, 1}}};
    tf.opacity = {{0, 0}, {124, 0}, {126, 1}, {255, 1}};
    tf.material = {0.3, 0.7, 0.0, 8.0};
    Renderer r(glContext(), v, tf);
    FrameDescription f = frameAt(300, 0, 0, {96, 96});   // camera on +y looking at -y
    f.ismos.partial = false;
    f.ismos.diskRadius = 0;
    f.ismos.lightSamples = 1;
    f.ismos.testPoints = 128;
    f.ismos.hemisphereRadius = 60;   // far away: a directional light
    f.ismos.ambient = 0;
    f.ismos.layers = 1;
    glm::dvec3 lightCam = glm::normalize(glm::dvec3(0.5, 0.0, 0.8));
    f.lights = {Light{lightCam, glm::dvec3(1.0), true}};
    f.ismos.base = ShadingMode::Solid;
    Rendered got = renderBoth(r, f);
    glm::dvec3 lightWorld = lightCam.x * f.camera.right() + lightCam.y * f.camera.up() - lightCam.z * f.camera.forward();
    double aspect = 1.0;
    glm::dmat4 inv = glm::inverse(f.camera.projection(aspect) * f.camera.view());
    glm::dvec3 eye = f.camera.position();
    int inShadow = 0, shadowOk = 0, outside = 0, outsideOk = 0, band = 0, oracleChecked = 0, oracleOk = 0;
    // The physical oracle (render/reference/ismos_reference.h) on the same pixels: it must see the analytic
    // shadow exactly, band included (it marches the real volume, not a height field).
    reference::PhysicalSettings physical;
    physical.stepMm = 0.25;
    std::vector<std::vector<glm::dvec3>> oraclePoints;
    for (const IsmosLight& l : got.lights) oraclePoints.push_back(l.samples);
    for (int y = 0; y < f.size.y; ++y)
        for (int x = 0; x < f.size.x; ++x) {
            glm::dvec2 ndc = (glm::dvec2(x, y) + 0.5) / glm::dvec2(f.size) * 2.0 - 1.0;
            ndc.y = -ndc.y;
            glm::dvec4 farPoint = inv * glm::dvec4(ndc, 1.0, 1.0);
            glm::dvec3 dir = glm::normalize(glm::dvec3(farPoint) / farPoint.w - eye);
            // The eye ray must reach the slab without touching the ball (margin 1 mm).
            glm::dvec3 oc = eye - ball;
            double bq = glm::dot(oc, dir), cq = glm::dot(oc, oc) - (radius + 1) * (radius + 1);
            if (bq * bq - cq >= 0) continue;
            double t = (slabFront - eye.y) / dir.y;
            glm::dvec3 s = eye + t * dir;
            if (std::abs(s.x) > 27 || std::abs(s.z) > 27) continue;
            // Distance of the shadow ray from the ball's centre, and from its column along the view axis.
            glm::dvec3 toBall = ball - s;
            double along = glm::dot(toBall, lightWorld);
            double rayDistance = along > 0 ? glm::length(toBall - along * lightWorld) : 1e9;
            // The column: points behind the ball's front surface as the eye sees it (a cone from the eye).
            double columnDistance = 1e9;
            for (double k = 0; s.y + k * lightWorld.y <= ball.y + radius; k += 0.1) {
                glm::dvec3 q = s + k * lightWorld;
                glm::dvec3 ray = glm::normalize(q - eye), toCentre = ball - eye;
                double b = glm::dot(toCentre, ray);
                if (glm::length(q - eye) < b - radius) continue;   // in front of the ball
                columnDistance = std::min(columnDistance, glm::length(toCentre - b * ray));
            }
            double ratio = got.ismos.at(x, y).r / std::max(got.base.at(x, y).r, 1e-6f);
            if ((x + y) % 3 == 0 && (rayDistance < radius - 1.5 || rayDistance > radius + 1.5)) {
                glm::dvec3 pTex((x + 0.5) / f.size.x, (y + 0.5) / f.size.y, got.layers.front[got.layers.index({x, y})].x);
                double occ = reference::physicalOcclusion(v, tf, got.space, r.geometry().worldCenter(), got.lights, oraclePoints, pTex, physical);
                ++oracleChecked;
                oracleOk += rayDistance < radius ? occ > 0.99 : occ < 0.01;
            }
            if (rayDistance < radius - 1.5) {
                ++inShadow;
                shadowOk += ratio < 0.01;
            } else if (columnDistance > radius + 1.5) {
                ++outside;
                outsideOk += ratio > 0.99;
            } else {
                ++band;
            }
        }
    std::printf("[ ball ] shadow %d/%d dark, outside %d/%d lit, %d pixels in the margins and the column's band\n", shadowOk, inShadow,
                outsideOk, outside, band);
    EXPECT_GT(inShadow, 30);
    EXPECT_GT(outside, 300);
    EXPECT_EQ(shadowOk, inShadow);
    EXPECT_EQ(outsideOk, outside);
    std::printf("[ ball ] oracle agrees with the analytic shadow at %d of %d pixels\n", oracleOk, oracleChecked);
    EXPECT_EQ(oracleOk, oracleChecked);
    EXPECT_GT(oracleChecked, 300);
}

// A homogeneous translucent slab in front of an opaque floor, the light behind the viewer: with exact layer
// opacities the floor receives the slab's analytic transmittance (1 - alpha)^(thickness / unit length).
TEST(Ismos, HomogeneousSlabGivesItsAnalyticTransmittance) {
    auto field = [](glm::dvec3 p) {
        if (std::abs(p.y) < 5) return 100.0;
        if (p.y < -20 && p.y > -30) return 250.0;
        return 0.0;
    };
    VolumeData v = test::makeVolume({64, 64, 64}, test::centredAffine({64, 64, 64}), ScalarType::Float32, field);
    TransferFunction tf;
    tf.color = {{0, {1, 1, 1}}, {255, {1, 1, 1}}};
    tf.opacity = {{0, 0}, {79.9, 0}, {80, 0.05}, {200.9, 0.05}, {201, 1}, {255, 1}};
    tf.material = {0.3, 0.7, 0.0, 8.0};
    Renderer r(glContext(), v, tf);
    FrameDescription f = frameAt(300, 0, 0, {48, 48});
    f.raycast.stepMm = 0.25;
    f.ismos.depthBias = 0.001;   // the bias and the test-point spacing (0.15 mm here) shave the slab
    f.ismos.partial = true;
    f.ismos.fit = false;
    f.ismos.layers = 2;
    f.ismos.blendLayers = false;
    f.ismos.opacityThreshold = 0.5;
    f.ismos.diskRadius = 0;
    f.ismos.lightSamples = 1;
    f.ismos.testPoints = 512;
    f.ismos.hemisphereRadius = 60;
    f.ismos.ambient = 0;
    f.ismos.base = ShadingMode::Solid;
    f.lights = {Light{{0, 0, 1}, glm::dvec3(1.0), true}};
    Rendered got = renderBoth(r, f);
    // Voxel centres at +-4.5 hold 100, the next ones 0: trilinear values reach the TF's 80 at |y| = 4.7.
    double expected = std::pow(1.0 - 0.05, 9.4);
    int n = 0;
    for (int y = 18; y < 30; ++y)
        for (int x = 18; x < 30; ++x) {
            double ratio = got.ismos.at(x, y).r / std::max(got.base.at(x, y).r, 1e-6f);
            EXPECT_NEAR(ratio, expected, 0.02) << x << "," << y;
            ++n;
        }
    for (glm::ivec2 q : {glm::ivec2(24, 24), glm::ivec2(24, 29)}) {
        std::size_t i = got.layers.index(q);
        std::printf("[ slab ] pixel %d,%d fronts %g %g backs %g %g alphas %g %g\n", q.x, q.y, got.layers.front[i].x, got.layers.front[i].y,
                    got.layers.back[i].x, got.layers.back[i].y, got.layers.alpha[i].x, got.layers.alpha[i].y);
    }
    std::printf("[ slab ] expected T %.4f, centre pixel %.4f\n", expected, got.ismos.at(24, 24).r / got.base.at(24, 24).r);
    EXPECT_EQ(n, 144);
}

// Pass 1's layers and the fit's beta against their CPU double twin (the same rays and sample lattice).
TEST(Ismos, LayersAndFitMatchTheirCpuTwin) {
    VolumeData v = test::makeVolume({48, 48, 48}, test::centredAffine({48, 48, 48}), ScalarType::Float32, test::blobField);
    TransferFunction tf = blobTf();
    Renderer r(glContext(), v, tf);
    int mismatched = 0, compared = 0, layered = 0;
    double worstBeta = 0;
    for (bool fit : {false, true}) {
        FrameDescription f = frameAt(220, 30, 20, {48, 48});
        f.raycast.jitterSeed = 3;
        f.ismos.fit = fit;
        r.render(f);
        IsmosLayerImages got = r.ismos()->readLayers();
        IsmosSpace space = r.ismosSpaceOf(f);
        double step = r.resolveStepMm(f.raycast);
        for (int y = 0; y < 48; y += 2)
            for (int x = 0; x < 48; x += 2) {
                reference::IsmosLayersPixel twin = reference::ismosLayersPixel(v, tf, f, step, space, {x, y});
                std::size_t i = got.index({x, y});
                bool same = true;
                for (int k = 0; k < 4; ++k) {
                    same = same && std::abs(got.front[i][k] - twin.front[k]) < 1e-4 && std::abs(got.alpha[i][k] - twin.alpha[k]) < 2e-3;   // the baked TF table
                    if (!fit) same = same && (twin.back[k] < -1e29 ? got.back[i][k] < -1e29f : std::abs(got.back[i][k] - twin.back[k]) < 1e-4);
                }
                if (fit) {
                    double e = std::abs(got.beta[i] - twin.beta) / std::max(twin.beta, 1e-3);
                    worstBeta = std::max(worstBeta, e);
                    same = same && e < 1e-2;
                }
                mismatched += !same;
                if (!same)
                    std::printf("  %d,%d fit %d: gpu front %g %g alpha %g %g back %g beta %g | cpu front %g %g alpha %g %g back %g beta %g\n", x, y, fit,
                                got.front[i].x, got.front[i].y, got.alpha[i].x, got.alpha[i].y, fit ? 0.0f : got.back[i].x, fit ? got.beta[i] : 0.0f,
                                twin.front.x, twin.front.y, twin.alpha.x, twin.alpha.y, twin.back.x, twin.beta);
                layered += twin.front.x != -1.0;
                ++compared;
            }
    }
    std::printf("[ layers ] %d of %d pixels differ (%d with layers), worst relative beta error %.2e\n", mismatched, compared, layered, worstBeta);
    EXPECT_GT(layered, 100);
    // Float vs double flips a sample at the TF's zero-opacity edge (a layer starts a step earlier) or at the
    // early-termination threshold (one more sample: beta moves by ~20 %); no more than 5 % of the layered pixels.
    EXPECT_LE(mismatched, layered / 20);
}

// Clip meshes: pass 1 skips clipped samples, so the walls of a cut get shadows with nothing precomputed. A
// crater cut into the flat face of an opaque cube, lit at 45 degrees: its rim shadows part of its floor.
TEST(Ismos, CutWallsGetShadows) {
    VolumeData cube = test::makeVolume({48, 48, 48}, test::centredAffine({48, 48, 48}), ScalarType::Float32,
                                       [](glm::dvec3 p) { return std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}) < 18 ? 250.0 : 0.0; });
    TransferFunction tf;
    tf.color = {{0, {1, 1, 1}}, {255, {1, 1, 1}}};
    tf.opacity = {{0, 0}, {124, 0}, {126, 1}, {255, 1}};
    tf.material = {0.3, 0.7, 0.0, 8.0};
    Renderer r(glContext(), cube, tf);
    FrameDescription f = frameAt(200, 0, 0, {64, 64});
    f.ismos.partial = false;
    f.ismos.diskRadius = 0;
    f.ismos.lightSamples = 1;
    f.ismos.testPoints = 96;
    f.ismos.hemisphereRadius = 60;
    f.ismos.ambient = 0;
    f.ismos.base = ShadingMode::Solid;
    f.lights = {Light{{0.7, 0.0, 0.7}, glm::dvec3(1.0), true}};
    auto shadowed = [&] {
        Rendered got = renderBoth(r, f);
        int n = 0;
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x) n += got.base.at(x, y).r > 0.1f && got.ismos.at(x, y).r < 0.01f * got.base.at(x, y).r;
        return n;
    };
    int flat = shadowed();
    r.clipMeshes().add(std::make_shared<const clip::TriangleMesh>(clip::makeSphere(11.0, 3)), glm::dvec3(1), clip::RigidPose{glm::dvec3(0, 18, 0), glm::dquat(1, 0, 0, 0)}, "crater");
    int crater = shadowed();
    std::printf("[ clip ] shadowed pixels: %d on the flat face, %d with the crater\n", flat, crater);
    EXPECT_EQ(flat, 0);
    EXPECT_GT(crater, 15);
}

// Eq. 8-10: sampled T(z) = exp(-beta z^2) gives back beta; eq. 12 is the mean extinction over the step.
TEST(Ismos, GaussianTransmittanceReturnsItsBeta) {
    for (double beta : {0.3, 2.0, 7.5}) {
        TransmittanceFit fit;
        for (int i = 1; i <= 200; ++i) {
            double z = 0.2 + 0.6 * i / 200.0;
            fit.add(z, std::exp(-beta * z * z));
        }
        EXPECT_NEAR(fit.beta(), beta, 1e-9 * beta);
        double z = 0.6, dz = 0.01;
        EXPECT_NEAR(fittedOpacity(beta, z, dz), (beta * z * z - beta * (z - dz) * (z - dz)) / dz, 1e-12);
    }
}

// Eq. 13's example: 3 of 4 samples of L0 and 2 of 5 of L1 occluded give Occ = 5/9 (not the mean of 3/4 and
// 2/5). An opaque wall covers x > 0.6 in front of P; samples to its side are blocked, those above are not.
TEST(Ismos, TwoLightsPoolTheirSamplesAsEquation13) {
    IsmosLayerImages layers;
    layers.size = {64, 64};
    std::size_t n = 64 * 64;
    layers.front.assign(n, glm::vec4(-1));
    layers.alpha.assign(n, glm::vec4(0));
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            bool wall = (x + 0.5) / 64.0 > 0.6;
            layers.front[layers.index({x, y})] = glm::vec4(wall ? 0.9f : 0.2f, -1, -1, -1);
            layers.alpha[layers.index({x, y})] = glm::vec4(1, 0, 0, 0);
        }
    IsmosLight l0, l1;
    l0.samples = {{1.5, 0.3, 1.0}, {1.5, 0.5, 1.0}, {1.5, 0.7, 1.0}, {0.5, 0.5, 2.0}};
    l1.samples = {{1.5, 0.4, 1.0}, {1.5, 0.6, 1.0}, {0.5, 0.5, 2.0}, {-0.5, 0.5, 1.0}, {0.3, 0.2, 1.5}};
    IsmosSettings s;
    s.partial = false;
    s.layers = 1;
    s.testPoints = 64;
    s.ambient = 0;
    IsmosSpace space;
    space.boxMm = glm::dvec3(1.0);
    glm::ivec2 p(32, 32);   // x = 0.508: left of the wall
    reference::IsmosPixel got = reference::ismosOcclusionPixel(layers, {l0, l1}, s, space, 0.0, p);
    EXPECT_NEAR(got.occlusion, 5.0 / 9.0, 1e-12);
    EXPECT_NEAR(got.factor.x, 4.0 / 9.0, 1e-12);
}

// Eq. 16: a pixel outside the spotlight's cone is exactly C_p I_L I_amb.
TEST(Ismos, OutsideTheSpotConeExactlyAmbient) {
    VolumeData v = test::makeVolume({48, 48, 48}, test::centredAffine({48, 48, 48}), ScalarType::Float32, test::blobField);
    Renderer r(glContext(), v, blobTf());
    FrameDescription f = frameAt(220, 30, 20, {48, 48});
    f.ismos.ambient = 0.35;
    f.ismos.lightShapes = {IsmosLightShape{0.2, 3.0, glm::dvec3(20, 20, 20)}};   // a narrow cone aimed at a corner
    Rendered got = renderBoth(r, f);
    int outside = 0, inside = 0;
    for (int y = 0; y < f.size.y; ++y)
        for (int x = 0; x < f.size.x; ++x) {
            if (got.layers.front[got.layers.index({x, y})].x == -1.0f) continue;
            glm::dvec3 p((x + 0.5) / f.size.x, (y + 0.5) / f.size.y, got.layers.front[got.layers.index({x, y})].x);
            if (insideSpot(got.lights[0], p)) {
                ++inside;
                continue;
            }
            ++outside;
            for (int c = 0; c < 3; ++c) EXPECT_EQ(got.ismos.at(x, y)[c], got.base.at(x, y)[c] * 0.35f) << x << "," << y;
        }
    EXPECT_GT(outside, 100);
    std::printf("[ spot ] %d pixels outside the cone, %d inside\n", outside, inside);
}

// Nothing is precomputed: a TF change or a moved light plans the two ISMOS passes and nothing else; the light
// samples are rebuilt only when a light or the camera moves.
TEST(Ismos, TfChangeOrLightMovePlansOnlyTheIsmosPasses) {
    PlanInputs in;
    in.shading = ShadingMode::Ismos;
    EXPECT_EQ(passes(planFrame(in)), (std::vector<Pass>{Pass::IsmosRayCast, Pass::IsmosOcclusion}));
    VolumeData v = test::makeVolume({32, 32, 32}, test::centredAffine({32, 32, 32}), ScalarType::Float32, test::blobField);
    Renderer r(glContext(), v, blobTf());
    FrameDescription f = frameAt(200, 10, 10, {32, 32});
    f.ismos.lightSamples = 4;
    f.ismos.testPoints = 8;
    r.render(f);
    EXPECT_EQ(r.ismos()->lightRebuilds(), 1);
    EXPECT_TRUE(r.showing(f));
    r.setTransferFunction(test::rampTransferFunction(50, 150, 0.4));
    EXPECT_EQ(passes(r.plan(f)), (std::vector<Pass>{Pass::IsmosRayCast, Pass::IsmosOcclusion}));
    r.render(f);
    EXPECT_EQ(r.ismos()->lightRebuilds(), 1) << "a TF change keeps the light samples";
    f.lights[0].direction = glm::dvec3(-0.4, 0.2, 1.0);
    EXPECT_FALSE(r.showing(f));
    EXPECT_EQ(passes(r.plan(f)), (std::vector<Pass>{Pass::IsmosRayCast, Pass::IsmosOcclusion}));
    r.render(f);
    EXPECT_EQ(r.ismos()->lightRebuilds(), 2);
    f.camera.azimuthDeg += 5;
    r.render(f);
    EXPECT_EQ(r.ismos()->lightRebuilds(), 3);
    EXPECT_EQ(r.ambientOcclusion(), nullptr) << "ismos allocates no AO volumes";
}

// A mode allocates only what it uses: phong nothing of ISMOS; full occlusion no backs and no fit; the exact
// variant the backs; the fit variant beta.
TEST(Ismos, AllocatesOnlyWhatTheVariantUses) {
    VolumeData v = test::makeVolume({32, 32, 32}, test::centredAffine({32, 32, 32}), ScalarType::Float32, test::blobField);
    auto names = [](const Renderer& r) {
        std::set<Resource> out;
        for (const GpuAllocation& a : r.gpuAllocations()) out.insert(a.resource);
        return out;
    };
    Renderer r(glContext(), v, blobTf());
    FrameDescription f = frameAt(200, 10, 10, {32, 32});
    f.shading = ShadingMode::Phong;
    r.render(f);
    EXPECT_EQ(names(r).count(Resource::IsmosLayers), 0u);
    f.shading = ShadingMode::Ismos;
    f.ismos.partial = false;
    r.render(f);
    std::set<Resource> full = names(r);
    EXPECT_EQ(full.count(Resource::IsmosLayers), 1u);
    EXPECT_EQ(full.count(Resource::IsmosLightSamples), 1u);
    EXPECT_EQ(full.count(Resource::IsmosLayerBacks), 0u);
    EXPECT_EQ(full.count(Resource::IsmosFit), 0u);
    f.ismos.partial = true;
    f.ismos.fit = false;
    r.render(f);
    EXPECT_EQ(names(r).count(Resource::IsmosLayerBacks), 1u);
    EXPECT_EQ(names(r).count(Resource::IsmosFit), 0u);
    f.ismos.fit = true;
    r.render(f);
    EXPECT_EQ(names(r).count(Resource::IsmosLayerBacks), 0u);
    EXPECT_EQ(names(r).count(Resource::IsmosFit), 1u);
    EXPECT_EQ(names(r).count(Resource::PrecomputedAo), 0u);
}


// A straight capped tube along x through `centre` (as test_tubes.cpp builds it).
TubeVertices tubeAlongX(glm::dvec3 centre, double length, double radius) {
    TubeVertices v;
    const int sides = 16;
    for (int r = 0; r <= 1; ++r)
        for (int s = 0; s < sides; ++s) {
            double a = 2 * std::numbers::pi * s / sides;
            glm::dvec3 n(0, std::cos(a), std::sin(a));
            v.positions.emplace_back(glm::vec3(centre + glm::dvec3((r - 0.5) * length, 0, 0) + radius * n));
            v.directions.emplace_back(glm::vec3(n));
            v.colors.emplace_back(0.9f, 0.8f, 0.3f, 1.0f);
        }
    for (int s = 0; s < sides; ++s) {
        std::uint32_t a = static_cast<std::uint32_t>(s), b = static_cast<std::uint32_t>((s + 1) % sides);
        v.indices.insert(v.indices.end(), {a, b, b + sides, a, b + sides, a + sides});
    }
    return v;
}

// The tube scenes' TF (opaque above 125: the slab and the ball) and frame (full occlusion of a hard light from
// straight above, two layers, no ambient floor).
TransferFunction tubeSceneTransferFunction() {
    TransferFunction tf;
    tf.color = {{0, {1, 1, 1}}, {255, {1, 1, 1}}};
    tf.opacity = {{0, 0}, {124, 0}, {126, 1}, {255, 1}};
    tf.material = {0.3, 0.7, 0.0, 8.0};
    return tf;
}

FrameDescription tubeSceneFrame() {
    FrameDescription f = frameAt(300, 0, 0, {64, 64});
    f.ismos.partial = false;
    f.ismos.diskRadius = 0;
    f.ismos.lightSamples = 1;
    f.ismos.testPoints = 128;
    f.ismos.hemisphereRadius = 60;
    f.ismos.ambient = 0;
    f.ismos.layers = 2;
    f.ismos.blendLayers = false;
    return f;
}

// Tubes are an opaque layer of pass 1: a tube in front of a slab shadows it, a ball in front of a tube
// shadows the tube (the plan: G-buffer, ISMOS 1, composite, ISMOS 2).
TEST(Ismos, TubesShadowTheVolumeAndTheVolumeShadowsTubes) {
    TransferFunction tf = tubeSceneTransferFunction();
    auto frame = tubeSceneFrame;
    TubeShading shading;
    int darkened = 0;
    {
        // Tube shadows volume: the slab behind it, light from above.
        VolumeData slab = test::makeVolume({48, 48, 48}, test::centredAffine({48, 48, 48}), ScalarType::Float32,
                                           [](glm::dvec3 p) { return p.y < -14 && p.y > -22 ? 250.0 : 0.0; });
        Renderer r(glContext(), slab, tf);
        FrameDescription f = frame();
        f.lights = {Light{{0.0, 0.5, 0.8}, glm::dvec3(1.0), true}};
        r.render(f);
        Image without = r.readImage();
        r.setTubes(tubeAlongX(glm::dvec3(0), 30, 3), shading);
        EXPECT_EQ(passes(r.plan(f)), (std::vector<Pass>{Pass::TubeGBuffer, Pass::IsmosRayCast, Pass::Composite, Pass::IsmosOcclusion}));
        r.render(f);
        Image with = r.readImage();
        std::vector<float> tubeDepth = r.gbuffer().readDepth();
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x) {
                if (tubeDepth[static_cast<std::size_t>(y * 64 + x)] > 0) continue;   // the tube itself
                darkened += without.at(x, y).r > 0.1f && with.at(x, y).r < 0.01f;
            }
        std::printf("[ tubes ] %d slab pixels in the tube's shadow\n", darkened);
        EXPECT_GT(darkened, 20);
    }
    {
        // Volume shadows tube: a ball between the light and the tube.
        auto ballField = [](glm::dvec3 p) { return glm::length(p - glm::dvec3(0, 6, 0)) < 6 ? 250.0 : 0.0; };
        VolumeData ball = test::makeVolume({48, 48, 48}, test::centredAffine({48, 48, 48}), ScalarType::Float32, ballField);
        VolumeData empty = test::makeVolume({48, 48, 48}, test::centredAffine({48, 48, 48}), ScalarType::Float32, [](glm::dvec3) { return 0.0; });
        FrameDescription f = frame();
        f.lights = {Light{{0.5, 0.0, 0.8}, glm::dvec3(1.0), true}};
        auto render = [&](const VolumeData& v) {
            Renderer r(glContext(), v, tf);
            r.setTubes(tubeAlongX(glm::dvec3(0, -10, 0), 40, 3), shading);
            r.render(f);
            return std::make_pair(r.readImage(), r.gbuffer().readDepth());
        };
        auto [withBall, depth] = render(ball);
        auto [withoutBall, depth2] = render(empty);
        int shadowedTube = 0, tubePixels = 0;
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x) {
                if (depth[static_cast<std::size_t>(y * 64 + x)] <= 0 || withBall.at(x, y).a < 0.99f) continue;
                if (withBall.at(x, y).r == withBall.at(x, y).r && withoutBall.at(x, y).r > 0.05f) ++tubePixels;
                shadowedTube += withoutBall.at(x, y).r > 0.05f && withBall.at(x, y).r < 0.01f;
            }
        std::printf("[ tubes ] %d of %d visible tube pixels in the ball's shadow\n", shadowedTube, tubePixels);
        EXPECT_GT(shadowedTube, 8);
        EXPECT_LT(shadowedTube, tubePixels);
    }
}

// The occluders' hierarchy finds the same first crossing as testing every triangle on its own, for random
// segments through two tubes (some miss, some graze, some run along a tube).
TEST(Ismos, OccluderTrianglesFindTheFirstCrossingLikeTestingEveryTriangle) {
    TubeVertices tubes = tubeAlongX(glm::dvec3(0, 0, 0), 30, 3);
    TubeVertices second = tubeAlongX(glm::dvec3(2, 7, -4), 24, 2);
    std::uint32_t offset = static_cast<std::uint32_t>(tubes.positions.size());
    tubes.positions.insert(tubes.positions.end(), second.positions.begin(), second.positions.end());
    for (std::uint32_t i : second.indices) tubes.indices.push_back(i + offset);
    reference::OccluderTriangles all(tubes);
    ASSERT_EQ(all.size(), tubes.indices.size() / 3);
    std::vector<reference::OccluderTriangles> single;
    for (std::size_t t = 0; t < tubes.indices.size(); t += 3) {
        TubeVertices one;
        one.positions = tubes.positions;
        one.indices = {tubes.indices[t], tubes.indices[t + 1], tubes.indices[t + 2]};
        single.emplace_back(one);
    }
    std::mt19937 random(5);
    std::uniform_real_distribution<double> u(-20, 20);
    int hits = 0;
    for (int i = 0; i < 2000; ++i) {
        glm::dvec3 a(u(random), u(random), u(random)), b(u(random), u(random), u(random));
        if (i % 5 == 0) b = a + glm::dvec3(40, 0.01 * u(random), 0);   // along the tubes
        double brute = -1;
        for (const reference::OccluderTriangles& o : single) {
            double t = o.firstHit(a, b);
            if (t >= 0 && (brute < 0 || t < brute)) brute = t;
        }
        double got = all.firstHit(a, b);
        ASSERT_EQ(got, brute) << "segment " << i;
        hits += brute >= 0;
    }
    std::printf("[ occluders ] %d of 2000 segments cross a tube\n", hits);
    EXPECT_GT(hits, 200);
    EXPECT_LT(hits, 1800);
}

// The tube scenes of TubesShadowTheVolumeAndTheVolumeShadowsTubes through the physical reference: its rays
// stop at tube triangles, so the slab pixels the GPU shows in the tube's shadow are occluded there too (and
// not without the triangles), and the tube pixels the ball shadows on the GPU are occluded by the real ball.
// Pass 1's layers with tubes equal their CPU twin, whose ray stops at the triangles.
TEST(Ismos, PhysicalReferenceAndLayerTwinStopAtTubes) {
    TransferFunction tf = tubeSceneTransferFunction();
    auto frame = tubeSceneFrame;
    TubeShading shading;
    shading.thicknessMm = 6.0;   // the tubes' diameter (sceneTubeShading)
    reference::PhysicalSettings physical;
    physical.stepMm = 0.5;
    {
        VolumeData slab = test::makeVolume({48, 48, 48}, test::centredAffine({48, 48, 48}), ScalarType::Float32,
                                           [](glm::dvec3 p) { return p.y < -14 && p.y > -22 ? 250.0 : 0.0; });
        Renderer r(glContext(), slab, tf);
        FrameDescription f = frame();
        f.lights = {Light{{0.0, 0.5, 0.8}, glm::dvec3(1.0), true}};
        f.ismos.partial = true;   // the exact layers' backs, for the twin
        TubeVertices tube = tubeAlongX(glm::dvec3(0), 30, 3);
        reference::OccluderTriangles occluders(tube);
        r.setTubes(tube, shading);
        r.render(f);
        Image with = r.readImage();
        IsmosLayerImages layers = r.ismos()->readLayers();
        std::vector<float> tubeDepth = r.gbuffer().readDepth();
        IsmosSpace space = r.ismosSpaceOf(f);
        std::vector<IsmosLight> lights = r.ismos()->lights();
        std::vector<std::vector<glm::dvec3>> points;
        for (const IsmosLight& l : lights) points.push_back(l.samples);
        double step = r.resolveStepMm(f.raycast);
        physical.startOffsetMm = f.ismos.depthBias * space.boxMm.z;
        int tubeShadow = 0, agree = 0, slabPixels = 0, twinOff = 0, tubePixels = 0, missed = 0, overShadowed = 0;
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x) {
                std::size_t i = layers.index({x, y});
                reference::IsmosLayersPixel twin = reference::ismosLayersPixel(slab, tf, f, step, space, {x, y}, &occluders, shading.thicknessMm);
                bool same = true;
                // A tube layer's back: the GPU's chord is the diameter times |n . forward| of the G-buffer's
                // smooth normal, the twin's the chord through the 16-sided tube's triangles (within 0.3 mm).
                double backTolerance = tubeDepth[i] > 0 ? 0.3 / (space.farMm - space.nearMm) : 1e-3;
                for (int k = 0; k < 2; ++k)
                    same = same && std::abs(layers.front[i][k] - twin.front[k]) < 1e-3 && std::abs(layers.alpha[i][k] - twin.alpha[k]) < 2e-3 &&
                           (twin.back[k] < -1e29 ? layers.back[i][k] < -1e29f : std::abs(layers.back[i][k] - twin.back[k]) < backTolerance);
                twinOff += !same;
                bool onTube = tubeDepth[i] > 0;
                tubePixels += onTube;
                if (onTube || layers.front[i].x == -1.0f) continue;
                glm::dvec3 p((x + 0.5) / 64.0, (y + 0.5) / 64.0, layers.front[i].x);
                physical.tubes = &occluders;
                double occ = reference::physicalOcclusion(slab, tf, space, r.geometry().worldCenter(), lights, points, p, physical);
                physical.tubes = nullptr;
                double without = reference::physicalOcclusion(slab, tf, space, r.geometry().worldCenter(), lights, points, p, physical);
                EXPECT_LT(without, 0.01) << x << "," << y << ": nothing but the tube is above the slab";
                bool dark = with.at(x, y).r < 0.01f;
                ++slabPixels;
                tubeShadow += occ > 0.99;
                agree += dark == (occ > 0.5);
                missed += occ > 0.99 && !dark;
                overShadowed += dark && occ < 0.5;
            }
        std::printf("[ tubes ] reference: %d of %d slab pixels in the tube's shadow (the GPU lit at %d of them, darkened %d it lights), "
                    "GPU agrees at %d; layer twin off at %d of 4096 (%d tube pixels)\n",
                    tubeShadow, slabPixels, missed, overShadowed, agree, twinOff, tubePixels);
        EXPECT_GT(tubeShadow, 20);
        // The image-space tube is a layer as thick as the tube's chord, not a height-field column to the back of
        // the box, whose shadow held a band beside the tube's own where paths pass behind the tube (seen: 36
        // such pixels with the column, 12 with a layer of the full diameter, 4 with the chord).
        EXPECT_LE(missed, tubeShadow / 20) << "the GPU lit pixels the traced tube shadows";
        EXPECT_LE(overShadowed, tubeShadow / 10) << "the GPU darkened pixels whose paths pass behind the tube";
        EXPECT_GE(agree, slabPixels * 9 / 10) << "the image-space shadow and the traced one disagree";
        EXPECT_GT(tubePixels, 50);
        EXPECT_LE(twinOff, tubePixels / 50) << "pass 1 stops at the G-buffer's tube, the twin at the triangles: the same surface";
    }
    {
        auto ballField = [](glm::dvec3 p) { return glm::length(p - glm::dvec3(0, 6, 0)) < 6 ? 250.0 : 0.0; };
        VolumeData ball = test::makeVolume({48, 48, 48}, test::centredAffine({48, 48, 48}), ScalarType::Float32, ballField);
        Renderer r(glContext(), ball, tf);
        FrameDescription f = frame();
        f.lights = {Light{{0.5, 0.0, 0.8}, glm::dvec3(1.0), true}};
        TubeVertices tube = tubeAlongX(glm::dvec3(0, -10, 0), 40, 3);
        reference::OccluderTriangles occluders(tube);
        r.setTubes(tube, shading);
        r.render(f);
        Image with = r.readImage();
        IsmosLayerImages layers = r.ismos()->readLayers();
        std::vector<float> tubeDepth = r.gbuffer().readDepth();
        IsmosSpace space = r.ismosSpaceOf(f);
        std::vector<IsmosLight> lights = r.ismos()->lights();
        std::vector<std::vector<glm::dvec3>> points;
        for (const IsmosLight& l : lights) points.push_back(l.samples);
        physical.startOffsetMm = f.ismos.depthBias * space.boxMm.z;
        physical.tubes = &occluders;
        int shadowedGpu = 0, shadowedBoth = 0;
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x) {
                std::size_t i = layers.index({x, y});
                if (tubeDepth[i] <= 0 || layers.front[i].x == -1.0f || with.at(x, y).a < 0.99f) continue;
                if (!(with.at(x, y).r < 0.01f)) continue;
                ++shadowedGpu;
                glm::dvec3 p((x + 0.5) / 64.0, (y + 0.5) / 64.0, layers.front[i].x);
                shadowedBoth += reference::physicalOcclusion(ball, tf, space, r.geometry().worldCenter(), lights, points, p, physical) > 0.99;
            }
        std::printf("[ tubes ] %d tube pixels in the ball's shadow on the GPU, %d of them in the reference\n", shadowedGpu, shadowedBoth);
        EXPECT_GT(shadowedGpu, 8);
        EXPECT_GE(shadowedBoth, shadowedGpu * 9 / 10);
    }
}

}  // namespace
}  // namespace curette
