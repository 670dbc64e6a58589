// Tubes with the volume (seed 000 Fig. 2): one test per interaction, on small synthetic scenes. The camera
// sits on +y looking along -y (azimuth 0), so "in front" means larger y.
#include "render/renderer.h"
#include "tests/render/gl_test_support.h"
#include "mesh/primitives.h"
#include "render/lighting.h"
#include "render/model/tube_geometry.h"
#include "render/model/volume_geometry.h"
#include "render/reference/camera_ray.h"
#include "render/reference/raycast_reference.h"
#include "render/reference/volume_sampler.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>

namespace curette {
namespace {

using test::straightTube;

using test::glContext;

TubeVertices merge(TubeVertices a, const TubeVertices& b) {
    std::uint32_t offset = static_cast<std::uint32_t>(a.positions.size());
    a.positions.insert(a.positions.end(), b.positions.begin(), b.positions.end());
    a.directions.insert(a.directions.end(), b.directions.begin(), b.directions.end());
    a.colors.insert(a.colors.end(), b.colors.begin(), b.colors.end());
    for (std::uint32_t i : b.indices) a.indices.push_back(i + offset);
    return a;
}

FrameDescription frontFrame(ShadingMode mode) {
    FrameDescription f;
    f.camera.fit(glm::dvec3(0), 16.0);
    f.camera.azimuthDeg = 0;
    f.camera.elevationDeg = 0;
    f.size = {48, 48};
    f.shading = mode;
    f.dos.coneAngleDeg = 45;
    f.lights = {Light{{0.0, 0.0, 1.0}, glm::dvec3(1.0), true}};
    return f;
}

TransferFunction whiteTransferFunction(double slabAlpha, double denseAlpha) {
    TransferFunction tf;
    tf.color = {{0, glm::dvec3(1.0)}};
    tf.opacity = {{0, 0.0}, {50, 0.0}, {60, slabAlpha}, {200, slabAlpha}, {250, denseAlpha}};
    return tf;
}

// The G-buffer and the ray-cast image share one pixel grid with row 0 at the top (pixel_ray.glsl): a tube
// above the camera's target appears in the upper half of the image, in every mode that draws tubes. (The
// G-buffer was rasterised with GL's row 0 at the bottom, so tubes away from the image centre were mirrored
// vertically: in a scene looking at an off-centre target they floated above the head.)
TEST(Tubes, ATubeAboveTheTargetIsInTheUpperHalfOfTheImage) {
    glm::ivec3 dims(32);
    VolumeData volume = test::makeVolume(dims, test::centredAffine(dims), ScalarType::UInt8, [](glm::dvec3) { return 0.0; });
    Renderer renderer(glContext(), volume, whiteTransferFunction(0.15, 0.15));
    renderer.setTubes(straightTube(glm::dvec3(0, 0, 8), glm::dvec3(1, 0, 0), 12.0, 1.5, glm::vec4(1, 0, 0, 1)), TubeShading{});
    for (ShadingMode mode : {ShadingMode::Solid, ShadingMode::Phong, ShadingMode::Dos}) {
        renderer.render(frontFrame(mode));
        Image image = renderer.readImage();
        std::vector<float> depth = renderer.gbuffer().readDepth();
        int upper = 0, lower = 0;
        for (int y = 0; y < 48; ++y)
            for (int x = 0; x < 48; ++x) {
                bool tube = image.at(x, y).a > 0.5f && image.at(x, y).r > 2.0f * image.at(x, y).g;
                (y < 24 ? upper : lower) += tube;
                EXPECT_EQ(tube, depth[static_cast<std::size_t>(y * 48 + x)] > 0) << shadingModeName(mode) << " pixel " << x << ", " << y;
            }
        EXPECT_GT(upper, 20) << shadingModeName(mode);
        EXPECT_EQ(lower, 0) << shadingModeName(mode) << ": the tube is mirrored below the centre";
    }
}

// Geometry to volume (Fig. 2 c): a tube in front of a uniform slab darkens a disc of the slab behind it,
// and only there.
TEST(Tubes, TubeDarkensTheVolumeBehindItAndOnlyThere) {
    glContext();
    glm::ivec3 dims(32);
    VolumeData volume = test::makeVolume(dims, test::centredAffine(dims), ScalarType::UInt8,
                                         [](glm::dvec3 p) { return p.y < -4.0 ? 60.0 : 0.0; });
    Renderer renderer(glContext(), volume, whiteTransferFunction(0.15, 0.15));
    FrameDescription frame = frontFrame(ShadingMode::Dos);
    renderer.setTubes(straightTube(glm::dvec3(0, 6, 0), glm::dvec3(0, 0, 1), 4.0, 1.5, glm::vec4(1)), TubeShading{});
    renderer.render(frame);
    Image with = renderer.readImage();
    std::vector<float> depth = renderer.gbuffer().readDepth();
    renderer.clearTubes();
    renderer.render(frame);
    Image without = renderer.readImage();
    int darkened = 0, far = 0;
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 48; ++x) {
            std::size_t i = static_cast<std::size_t>(y * 48 + x);
            if (depth[i] > 0) continue;  // the tube itself
            double r = glm::length(glm::dvec2(x + 0.5 - 24, y + 0.5 - 24));
            float a = without.at(x, y).r, b = with.at(x, y).r;
            if (r > 18) {
                ASSERT_NEAR(a, b, 1e-6) << "the slab far from the tube is untouched";
                ++far;
            } else if (b < a - 1e-3f) {
                ++darkened;
            }
        }
    EXPECT_GT(far, 200);
    EXPECT_GT(darkened, 10) << "the tube's shadow must darken the slab around it";
}

// Volume to geometry (Fig. 2 d): a dense layer in front of a tube darkens it (its partial occlusion);
// removing the layer with a clip mesh restores exactly what the tube receives without the layer (a curved
// tube also occludes part of its own cone near its silhouette, so that is not 1).
TEST(Tubes, DenseLayerInFrontDarkensTheTubeAndClippingItRestores) {
    glContext();
    glm::ivec3 dims(32);
    // A broad dense layer at y in [4, 6] (between the eye and the tube at y = -2), a little off the tube's
    // line of sight so its shadow, not its own colour, is what the tube receives.
    auto layer = [](bool present) {
        return [present](glm::dvec3 p) { return present && std::abs(p.y - 5.0) < 1.0 && p.x > 1.0 ? 250.0 : 0.0; };
    };
    FrameDescription frame = frontFrame(ShadingMode::Dos);
    frame.dos.coneAngleDeg = 60;
    TubeVertices tube = straightTube(glm::dvec3(0, -2, 0), glm::dvec3(0, 0, 1), 12.0, 2.0, glm::vec4(1));
    auto partialAtTube = [&](Renderer& renderer) {
        renderer.render(frame);
        std::vector<float> depth = renderer.gbuffer().readDepth();
        std::vector<float> partial(depth.size());
        glGetTextureImage(renderer.gbuffer().partialOcclusion(), 0, GL_RED, GL_FLOAT, static_cast<GLsizei>(partial.size() * 4), partial.data());
        double sum = 0;
        int n = 0;
        for (std::size_t i = 0; i < depth.size(); ++i)
            if (depth[i] > 0) sum += partial[i], ++n;
        return n ? sum / n : -1.0;
    };
    VolumeData empty = test::makeVolume(dims, test::centredAffine(dims), ScalarType::UInt8, layer(false));
    Renderer withoutLayer(glContext(), empty, whiteTransferFunction(0.0, 0.9));
    withoutLayer.setTubes(tube, TubeShading{});
    double unshadowed = partialAtTube(withoutLayer);

    VolumeData dense = test::makeVolume(dims, test::centredAffine(dims), ScalarType::UInt8, layer(true));
    Renderer renderer(glContext(), dense, whiteTransferFunction(0.0, 0.9));
    renderer.setTubes(tube, TubeShading{});
    double shadowed = partialAtTube(renderer);
    // A box that removes the layer entirely.
    clip::ClipMeshSet& clip = renderer.clipMeshes();
    clip.add(std::make_shared<const clip::TriangleMesh>(clip::makeBox(glm::dvec3(40, 4, 40))), glm::dvec3(1),
             clip::RigidPose{glm::dvec3(0, 5, 0), {}}, "remove layer");
    double restored = partialAtTube(renderer);
    EXPECT_LT(shadowed, unshadowed - 0.02) << "the layer must shadow the tube";
    EXPECT_NEAR(restored, unshadowed, 1e-6) << "with the layer clipped away the tube receives what it does without it";
}

// A tube's shadow on the volume does not depend on the slice distance: its opacity is an extinction over
// its depth (dos_slice.comp), not an injection per slice behind its surface. The shadow, summed over the
// image (the cone blur spreads it differently for each d but keeps its sum), is the same for d and d / 2.
TEST(Tubes, ATubesShadowIsTheSameForHalfTheSliceDistance) {
    glm::ivec3 dims(32);
    VolumeData volume = test::makeVolume(dims, test::centredAffine(dims), ScalarType::UInt8,
                                         [](glm::dvec3 p) { return p.y < 2.0 ? 60.0 : 0.0; });
    TubeVertices tube = straightTube(glm::dvec3(0, 6, 0), glm::dvec3(0, 0, 1), 6.0, 1.5, glm::vec4(1));
    TubeShading shading;
    shading.geometryOpacity = 0.3;   // far from saturating, so extra slices would show
    shading.thicknessMm = 3.0;
    auto shadowSum = [&](double d) {
        Renderer renderer(glContext(), volume, whiteTransferFunction(0.15, 0.15));
        FrameDescription frame = frontFrame(ShadingMode::Dos);
        frame.dos.sliceDistanceMm = d;
        renderer.render(frame);
        Image without = renderer.readImage();
        renderer.setTubes(tube, shading);
        renderer.render(frame);
        Image with = renderer.readImage();
        std::vector<float> depth = renderer.gbuffer().readDepth();
        double sum = 0;
        for (std::size_t i = 0; i < depth.size(); ++i)
            if (depth[i] == 0) sum += without.pixels[i].r - with.pixels[i].r;  // the slab, where the tube is not
        return sum;
    };
    double full = shadowSum(1.0), half = shadowSum(0.5);
    std::printf("[ tubes ] shadow summed over the image: d = 1 mm %.4f, d = 0.5 mm %.4f\n", full, half);
    ASSERT_GT(full, 0.5) << "the tube must shadow the slab";
    EXPECT_NEAR(half / full, 1.0, 0.1);
}

// The occlusion a tube receives (the partial occlusion buffer) is continuous along a tube that runs in
// depth: interpolated between the slices around its surface (seed 000 eq. 3), not constant within a slice
// and jumping at the next.
TEST(Tubes, PartialOcclusionIsContinuousAlongATubeTiltedInDepth) {
    glm::ivec3 dims(32);
    VolumeData volume = test::makeVolume(dims, test::centredAffine(dims), ScalarType::UInt8, [](glm::dvec3) { return 60.0; });
    const double alphaUnit = 0.05, d = 2.0;
    Renderer renderer(glContext(), volume, whiteTransferFunction(alphaUnit, alphaUnit));
    renderer.setTubes(straightTube(glm::dvec3(0, 0, 0), glm::dvec3(1, -0.6, 0), 24.0, 0.8, glm::vec4(1)), TubeShading{});
    FrameDescription frame = frontFrame(ShadingMode::Dos);
    frame.dos.sliceDistanceMm = d;
    frame.dos.gridSize = 1;
    frame.size = {96, 96};
    renderer.render(frame);
    std::vector<float> depth = renderer.gbuffer().readDepth();
    std::vector<float> partial(depth.size());
    glGetTextureImage(renderer.gbuffer().partialOcclusion(), 0, GL_RED, GL_FLOAT, static_cast<GLsizei>(partial.size() * 4), partial.data());
    // Along the row through the tube's axis, sorted by depth.
    std::vector<std::pair<float, float>> row;
    for (int x = 0; x < frame.size.x; ++x) {
        std::size_t i = static_cast<std::size_t>(48 * frame.size.x + x);
        if (depth[i] > 0) row.emplace_back(depth[i], partial[i]);
    }
    std::sort(row.begin(), row.end());
    ASSERT_GT(row.size(), 40u);
    ASSERT_GT(row.back().first - row.front().first, 4 * d) << "the tube must cross several slices in depth";
    const double perSlice = 1.0 - std::pow(1.0 - alphaUnit, d);  // what one slice of the medium takes away
    double largestJump = 0;
    for (std::size_t i = 1; i < row.size(); ++i) {
        EXPECT_LE(row[i].second, row[i - 1].second + 1e-6) << "deeper receives no more light";
        largestJump = std::max(largestJump, double(row[i - 1].second - row[i].second));
    }
    std::printf("[ tubes ] partial occlusion along the tube: largest step %.4f, one slice takes %.4f\n", largestJump, perSlice * row.front().second);
    EXPECT_LT(largestJump, 0.5 * perSlice * row.front().second) << "a staircase jumps by a whole slice's attenuation";
}

// Geometry to geometry (Fig. 2 b): a tube crossing in front of another darkens it nearby (vicinity term).
TEST(Tubes, TubeInFrontDarkensTheTubeBehindNearby) {
    glContext();
    glm::ivec3 dims(16);
    VolumeData volume = test::makeVolume(dims, test::centredAffine(dims), ScalarType::UInt8, [](glm::dvec3) { return 0.0; });
    Renderer renderer(glContext(), volume, whiteTransferFunction(0.0, 0.0));
    FrameDescription frame = frontFrame(ShadingMode::Dos);
    TubeShading shading;
    shading.vicinityDistanceMm = 6.0;
    TubeVertices back = straightTube(glm::dvec3(0, -3, 0), glm::dvec3(1, 0, 0), 60.0, 1.2, glm::vec4(1));
    TubeVertices front = straightTube(glm::dvec3(0, 3, 0), glm::dvec3(0, 0, 1), 24.0, 1.2, glm::vec4(1));
    renderer.setTubes(back, shading);
    renderer.render(frame);
    Image alone = renderer.readImage();
    std::vector<float> depthAlone = renderer.gbuffer().readDepth();
    renderer.setTubes(merge(back, front), shading);
    renderer.render(frame);
    Image crossed = renderer.readImage();
    std::vector<float> depthCrossed = renderer.gbuffer().readDepth();
    int darker = 0, farUnchanged = 0;
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 48; ++x) {
            std::size_t i = static_cast<std::size_t>(y * 48 + x);
            if (depthAlone[i] <= 0 || std::abs(depthCrossed[i] - depthAlone[i]) > 1e-4f) continue;  // back tube, still visible
            double dx = std::abs(x + 0.5 - 24);
            if (dx < 8 && crossed.at(x, y).r < alone.at(x, y).r - 1e-3f) ++darker;
            if (dx > 20) {
                EXPECT_NEAR(crossed.at(x, y).r, alone.at(x, y).r, 1e-5);
                ++farUnchanged;
            }
        }
    EXPECT_GT(darker, 4) << "the front tube must darken the back tube beside it";
    EXPECT_GT(farUnchanged, 0);
}

// Clip meshes clip tubes only when set to.
TEST(Tubes, ClipMeshCutsTubesOnlyWhenAskedTo) {
    glContext();
    glm::ivec3 dims(16);
    VolumeData volume = test::makeVolume(dims, test::centredAffine(dims), ScalarType::UInt8, [](glm::dvec3) { return 0.0; });
    Renderer renderer(glContext(), volume, whiteTransferFunction(0.0, 0.0));
    FrameDescription frame = frontFrame(ShadingMode::Phong);
    renderer.setTubes(straightTube(glm::dvec3(0), glm::dvec3(1, 0, 0), 24.0, 1.5, glm::vec4(1)), TubeShading{});
    auto tubePixels = [&]() {
        renderer.render(frame);
        int n = 0;
        for (float d : renderer.gbuffer().readDepth()) n += d > 0;
        return n;
    };
    int full = tubePixels();
    clip::ClipMeshSet& clip = renderer.clipMeshes();
    clip.add(std::make_shared<const clip::TriangleMesh>(clip::makeSphere(5.0, 3)), glm::dvec3(1), {}, "sphere");
    EXPECT_EQ(tubePixels(), full) << "a mesh that does not clip tubes leaves them whole";
    clip.setClipsTubes(0, true);
    int cut = tubePixels();
    EXPECT_LT(cut, full - 20);
    EXPECT_GT(cut, full / 3);
}

// The illuminated-lines shader (shaders/illuminated_lines.glsl via the compositor) mirrors its CPU oracle,
// seed 004 eq. 3.12-3.15 (render/model/tube_geometry.cpp), at every pixel a line covers.
TEST(Tubes, IlluminatedLinesMatchTheirCpuOracle) {
    glContext();
    glm::ivec3 dims(16);
    VolumeData volume = test::makeVolume(dims, test::centredAffine(dims), ScalarType::UInt8, [](glm::dvec3) { return 0.0; });
    Renderer renderer(glContext(), volume, whiteTransferFunction(0.0, 0.0));
    FrameDescription frame = frontFrame(ShadingMode::Phong);  // no occlusion terms: the pure line lighting
    frame.lights = {Light{{0.5, 0.3, 0.8}, glm::dvec3(1.0), true}};
    Tractogram t;
    t.points = {{-12, 0, -6}, {12, 0, 6}, {-8, 2, 9}, {9, -1, -8}};
    t.offsets = {0, 2, 4};
    TubeSettings settings;
    settings.smoothing = TubeSettings::Smoothing::None;
    settings.coloring = TubeSettings::Coloring::Uniform;
    settings.uniformColor = glm::dvec3(0.8, 0.6, 0.4);
    TubeShading shading;
    renderer.setTubes(buildIlluminatedLines(t, settings), shading);
    renderer.render(frame);
    Image image = renderer.readImage();
    std::vector<float> depth = renderer.gbuffer().readDepth();
    glm::dvec3 toLight = worldLightDirection(frame.lights[0], frame.camera);
    glm::dmat4 inverseViewProjection = glm::inverse(frame.camera.projection(1.0) * frame.camera.view());
    int checked = 0;
    double worst = 0;
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 48; ++x) {
            if (depth[static_cast<std::size_t>(y * 48 + x)] <= 0) continue;
            glm::dvec2 ndc = (glm::dvec2(x, y) + 0.5) / 48.0 * 2.0 - 1.0;
            ndc.y = -ndc.y;
            glm::dvec4 far = inverseViewProjection * glm::dvec4(ndc, 1, 1);
            glm::dvec3 toViewer = -glm::normalize(glm::dvec3(far) / far.w - frame.camera.position());
            // Which line covers the pixel: the one whose direction the G-buffer stores is unknown here, so
            // accept the closer of the two oracle values.
            double best = 1e9;
            for (int line = 0; line < 2; ++line) {
                glm::dvec3 tangent = glm::normalize(glm::dvec3(t.points[static_cast<std::size_t>(2 * line + 1)] - t.points[static_cast<std::size_t>(2 * line)]));
                glm::dvec3 expected = illuminatedLineColor(settings.uniformColor, tangent, toLight, toViewer, shading.material, shading.lineDiffuseExponent);
                best = std::min(best, glm::length(glm::dvec3(image.at(x, y)) - expected));
            }
            worst = std::max(worst, best);
            ++checked;
        }
    // The G-buffer stores colour and tangent as half floats (11-bit mantissa): ~1e-3 per channel.
    EXPECT_GT(checked, 30);
    EXPECT_LT(worst, 5e-3);
}

// A 24^3 slab (y < -2) behind the origin and a renderer for it with a cheap LAO (K = 6, M = 4), for cao
// frames with tubes in front of it.
struct CaoSlab {
    glm::ivec3 dims{24};
    VolumeData volume;
    std::unique_ptr<Renderer> renderer;
    CaoSlab() {
        glContext();
        volume = test::makeVolume(dims, test::centredAffine(dims), ScalarType::UInt8, [](glm::dvec3 p) { return p.y < -2.0 ? 60.0 : 0.0; });
        renderer = std::make_unique<Renderer>(glContext(), volume, whiteTransferFunction(0.15, 0.15));
        LaoSettings lao;
        parseLaoPattern("6", lao.directions);
        lao.samples = 4;
        renderer->setLaoSettings(lao);
    }
};

// In cao shading tubes are drawn by the ray cast (no slab pass): the volume shadows a tube through V_AO at its
// surface, and a tube changes no pixel it does not cover (its shadow on the volume is dos's, through the slab
// pass). (While every mode drew tubes through the slab pass, a tube darkened the cao slab around it.)
TEST(Tubes, InCaoTheVolumeShadowsTheTubesAndTheTubesChangeOnlyTheirPixels) {
    CaoSlab slab;
    // A slab dense enough to shadow what lies against it.
    slab.renderer = std::make_unique<Renderer>(glContext(), slab.volume, whiteTransferFunction(0.7, 0.7));
    LaoSettings lao;
    parseLaoPattern("6", lao.directions);
    lao.samples = 4;
    slab.renderer->setLaoSettings(lao);
    Renderer& renderer = *slab.renderer;
    FrameDescription frame = frontFrame(ShadingMode::Cao);
    frame.camera.fit(glm::dvec3(0), 12.0);
    renderer.render(frame);
    Image without = renderer.readImage();
    // One tube against the slab (y < -2), one in the open in front of it.
    TubeVertices tubes = merge(straightTube(glm::dvec3(-4, -2.2, 0), glm::dvec3(0, 0, 1), 8.0, 1.2, glm::vec4(1)),
                               straightTube(glm::dvec3(4, 6, 0), glm::dvec3(0, 0, 1), 8.0, 1.2, glm::vec4(1)));
    renderer.setTubes(tubes, TubeShading{});
    renderer.render(frame);
    ASSERT_FALSE(renderer.lastPlan().runs(Pass::SlabPass));
    Image with = renderer.readImage();
    std::vector<float> depth = renderer.gbuffer().readDepth();
    // The open tube is 8 mm nearer the eye than the one against the slab.
    // Compared: the pixels within 0.5 mm of each tube's nearest point (the one against the slab is out of it there).
    float nearest = 1e30f, nearestOnSlab = 1e30f;
    for (float d : depth)
        if (d > 0) nearest = std::min(nearest, d);
    for (float d : depth)
        if (d >= nearest + 4.0f) nearestOnSlab = std::min(nearestOnSlab, d);
    int elsewhere = 0;
    double onSlab = 0, inOpen = 0;
    int nSlab = 0, nOpen = 0;
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 48; ++x) {
            std::size_t i = static_cast<std::size_t>(y * 48 + x);
            if (depth[i] <= 0) {
                ASSERT_EQ(with.pixels[i], without.pixels[i]) << "pixel " << x << ", " << y << " has no tube";
                ++elsewhere;
            } else if (depth[i] < nearest + 0.5f || (depth[i] >= nearestOnSlab && depth[i] < nearestOnSlab + 0.5f)) {
                bool open = depth[i] < nearest + 4.0f;
                (open ? inOpen : onSlab) += with.pixels[i].r;
                ++(open ? nOpen : nSlab);
            }
        }
    ASSERT_GT(nSlab, 10);
    ASSERT_GT(nOpen, 10);
    EXPECT_GT(elsewhere, 1000);
    std::printf("[ tubes ] cao: mean red of the tube against the slab %.4f, in the open %.4f\n", onSlab / nSlab, inOpen / nOpen);
    EXPECT_LT(onSlab / nSlab, 0.95 * inOpen / nOpen) << "the slab must shadow the tube lying against it";
}

// Tubes that cover no pixel (here: behind the camera) leave a CAO frame bit for bit as it is without tubes:
// the frame plan leaves the tube passes out and the ray caster runs as before.
TEST(Tubes, TubesThatCoverNoPixelLeaveACaoImageUnchanged) {
    CaoSlab slab;
    Renderer& renderer = *slab.renderer;
    FrameDescription frame = frontFrame(ShadingMode::Cao);
    renderer.render(frame);
    Image without = renderer.readImage();
    glm::dvec3 behindCamera = frame.camera.position() - 50.0 * frame.camera.forward();
    renderer.setTubes(straightTube(behindCamera, glm::dvec3(0, 0, 1), 4.0, 1.2, glm::vec4(1)), TubeShading{});
    EXPECT_FALSE(renderer.plan(frame).runs(Pass::TubeGBuffer));
    renderer.render(frame);
    Image with = renderer.readImage();
    ASSERT_EQ(with.pixels.size(), without.pixels.size());
    EXPECT_EQ(std::memcmp(with.pixels.data(), without.pixels.data(), with.pixels.size() * sizeof(glm::vec4)), 0);
}

// La is the ambient light of dos shading (seed 001 Algorithm 1); lao/cao take their ambient from V_AO, so with
// tubes in view (drawn by the ray cast) a CAO frame does not change with La. (The slab pass, which drew cao's
// tubes before, used to multiply V_AO by La, so a CAO scene changed brightness when tubes were added.)
TEST(Tubes, AmbientRadianceOfDosDoesNotScaleCaoWithTubes) {
    CaoSlab slab;
    Renderer& renderer = *slab.renderer;
    renderer.setTubes(straightTube(glm::dvec3(0, 5, 0), glm::dvec3(0, 0, 1), 4.0, 1.2, glm::vec4(1)), TubeShading{});
    FrameDescription frame = frontFrame(ShadingMode::Cao);
    frame.dos.ambientRadiance = 1.0;
    renderer.render(frame);
    ASSERT_TRUE(renderer.lastPlan().runs(Pass::TubeGBuffer));
    Image one = renderer.readImage();
    frame.dos.ambientRadiance = 3.0;
    renderer.render(frame);
    Image three = renderer.readImage();
    EXPECT_EQ(std::memcmp(one.pixels.data(), three.pixels.data(), one.pixels.size() * sizeof(glm::vec4)), 0);
    double sum = 0;
    for (const glm::vec4& p : one.pixels) sum += p.r;
    EXPECT_GT(sum, 1.0) << "the frame must show something";
    // In dos shading La does scale the volume's light.
    frame.shading = ShadingMode::Dos;
    renderer.render(frame);
    Image dosThree = renderer.readImage();
    frame.dos.ambientRadiance = 1.0;
    renderer.render(frame);
    Image dosOne = renderer.readImage();
    EXPECT_NE(std::memcmp(dosOne.pixels.data(), dosThree.pixels.data(), dosOne.pixels.size() * sizeof(glm::vec4)), 0);
}

// Tubes in the ray cast (solid, phong, lao, cao: shaders/tube_surface.glsl) against the CPU twin at every pixel
// of a small scene: reference::raycastPixel with the tube surface the G-buffer holds (read back: the raster is not
// what is compared) and, in lao/cao, V_AO read back and sampled trilinearly. The scene has a tube inside faint
// tissue against a dense layer (V_AO below 1 at its surface) with more tissue in front of part of it, and one in
// the open; a second light from the side. Float32 storage, as in Raycast.MatchesCpuReferenceFloatVolumeSolidAndPhong,
// whose bound (5e-4 per channel: float against double along the ray and the baked TF) this keeps on tube pixels.
TEST(Tubes, RayCastTubesMatchTheCpuReference) {
    glContext();
    glm::ivec3 dims(24);
    VolumeData volume = test::makeVolume(dims, test::centredAffine(dims), ScalarType::Float32, [](glm::dvec3 p) {
        if (p.y < -5.0) return 250.0;
        if (p.y < 0.0) return 60.0;
        if (p.y > 2.0 && p.y < 5.0 && p.x > 0.0) return 120.0;
        return 0.0;
    });
    TransferFunction tf = whiteTransferFunction(0.06, 0.9);
    tf.color = {{0, {0.9, 0.8, 0.7}}, {120, {0.6, 0.7, 0.9}}, {255, {1.0, 1.0, 1.0}}};
    Renderer renderer(glContext(), volume, tf);
    LaoSettings lao;
    parseLaoPattern("6", lao.directions);
    lao.samples = 4;
    renderer.setLaoSettings(lao);
    TubeShading shading;
    renderer.setTubes(merge(straightTube(glm::dvec3(0, -2.5, 0), glm::dvec3(1, 0, 0.3), 18.0, 1.5, glm::vec4(1.0, 0.5, 0.2, 1)),
                            straightTube(glm::dvec3(-3, 7, 2), glm::dvec3(0.2, 0, 1), 14.0, 1.0, glm::vec4(0.3, 0.9, 0.4, 1))),
                      shading);
    for (ShadingMode mode : {ShadingMode::Solid, ShadingMode::Phong, ShadingMode::Lao, ShadingMode::Cao}) {
        SCOPED_TRACE(shadingModeName(mode));
        FrameDescription frame = frontFrame(mode);
        frame.camera.fit(glm::dvec3(0), 14.0);
        frame.camera.elevationDeg = 15;
        frame.lights.push_back(Light{{0.7, 0.5, 0.5}, glm::dvec3(0.6, 0.6, 0.5), true});
        renderer.render(frame);
        ASSERT_TRUE(renderer.lastPlan().runs(Pass::TubeGBuffer));
        ASSERT_FALSE(renderer.lastPlan().runs(Pass::SlabPass));
        Image image = renderer.readImage();
        std::vector<float> depth = renderer.gbuffer().readDepth();
        std::vector<glm::vec4> color = renderer.gbuffer().readColor(), normal = renderer.gbuffer().readNormal();
        reference::Grid ambient;
        reference::RaycastOptions options;
        options.tubeShading = shading;
        options.ambientScale = lao.ambientScale;
        if (usesAmbientOcclusion(mode)) {
            ambient.dims = dims;
            for (std::uint16_t a : renderer.ambientOcclusion()->readAmbient()) ambient.values.push_back(a / 65535.0);
            options.ambient = [&](glm::dvec3 tex) { return ambient.sample(tex, reference::Wrap::ClampToEdge); };
        }
        double step = renderer.resolveStepMm(frame.raycast), maxError = 0, maxOnTubes = 0, maxElsewhere = 0, sum = 0, leastTubeAmbient = 1;
        int tubePixels = 0, tubesBehindTissue = 0;
        VolumeGeometry g{volume.dims, volume.indexToWorld};
        for (int y = 0; y < frame.size.y; ++y)
            for (int x = 0; x < frame.size.x; ++x) {
                std::size_t i = static_cast<std::size_t>(y * frame.size.x + x);
                options.tube.reset();
                if (depth[i] > 0) {
                    options.tube = reference::TubeSurface{depth[i], glm::dvec3(color[i]), glm::dvec3(normal[i]), normal[i].w == 2.0f};
                    ++tubePixels;
                }
                reference::RaycastResult r = reference::raycastPixel(volume, tf, frame, step, {x, y}, options);
                if (depth[i] > 0 && r.samples > 0) ++tubesBehindTissue;
                if (depth[i] > 0 && options.ambient) {
                    auto [eye, direction] = reference::cameraRay(frame, {x, y});
                    glm::dvec3 surface = eye + depth[i] / glm::dot(direction, frame.camera.forward()) * direction;
                    leastTubeAmbient = std::min(leastTubeAmbient, options.ambient(glm::dvec3(g.worldToTexture() * glm::dvec4(surface, 1.0))));
                }
                glm::dvec4 got(image.pixels[i]);
                for (int ch = 0; ch < 4; ++ch) {
                    double e = std::abs(got[ch] - r.rgba[ch]);
                    maxError = std::max(maxError, e);
                    (depth[i] > 0 ? maxOnTubes : maxElsewhere) = std::max(depth[i] > 0 ? maxOnTubes : maxElsewhere, e);
                    sum += e * e;
                }
            }
        double rms = std::sqrt(sum / (4.0 * frame.size.x * frame.size.y));
        std::printf("[ reference ] %s with tubes: max %.2e (tube pixels %.2e, others %.2e) rms %.2e over %d pixels (%d tube pixels, %d behind "
                    "tissue, least V_AO at a tube %.3f)\n",
                    shadingModeName(mode), maxError, maxOnTubes, maxElsewhere, rms, frame.size.x * frame.size.y, tubePixels, tubesBehindTissue,
                    leastTubeAmbient);
        EXPECT_GT(tubePixels, 150);
        EXPECT_GT(tubesBehindTissue, 40) << "the test must see tubes through tissue";
        if (usesAmbientOcclusion(mode)) {
            EXPECT_LT(leastTubeAmbient, 0.9) << "the test must see V_AO shade a tube";
        }
        EXPECT_LT(maxOnTubes, 5e-4) << "rms " << rms;
        // The volume's own pixels: lao/cao double the colour (ambientScale), and with it the baked TF's error at
        // the field's steps (measured 4.9e-4 against 3.5e-4 in solid and phong).
        EXPECT_LT(maxElsewhere, usesAmbientOcclusion(mode) ? 1e-3 : 5e-4) << "rms " << rms;
        RecordProperty(std::string("max_error_") + shadingModeName(mode), std::to_string(maxError));
    }
}

// A scene allocates only what it uses: no AO volumes, G-buffer or slab buffers for phong without tubes;
// AO volumes only once lao/cao runs; the G-buffer and slab buffers only with tubes or dos.
TEST(Tubes, AScenesAllocatesOnlyWhatItUses) {
    glContext();
    glm::ivec3 dims(16);
    VolumeData volume = test::makeVolume(dims, test::centredAffine(dims), ScalarType::UInt8, [](glm::dvec3 p) { return p.x > 0 ? 100.0 : 0.0; });
    auto names = [](const Renderer& r) {
        std::string all;
        for (const GpuAllocation& a : r.gpuAllocations()) all += std::string(a.name()) + ";";
        return all;
    };
    Renderer renderer(glContext(), volume, whiteTransferFunction(0.2, 0.2));
    FrameDescription frame = frontFrame(ShadingMode::Phong);
    renderer.render(frame);
    std::string phong = names(renderer);
    EXPECT_EQ(phong.find("V_AO"), std::string::npos) << phong;
    EXPECT_EQ(phong.find("G-buffer"), std::string::npos);
    EXPECT_EQ(phong.find("DOS"), std::string::npos);
    EXPECT_EQ(phong.find("clip maps"), std::string::npos) << "no clip meshes, no maps";
    frame.shading = ShadingMode::Cao;
    renderer.render(frame);
    std::string cao = names(renderer);
    EXPECT_NE(cao.find("V_AO"), std::string::npos);
    EXPECT_NE(cao.find("V_PAO"), std::string::npos);
    EXPECT_EQ(cao.find("G-buffer"), std::string::npos);
    Renderer dos(glContext(), volume, whiteTransferFunction(0.2, 0.2));
    frame.shading = ShadingMode::Dos;
    dos.render(frame);
    std::string dosNames = names(dos);
    EXPECT_NE(dosNames.find("DOS occlusion"), std::string::npos);
    EXPECT_EQ(dosNames.find("V_AO"), std::string::npos);
    EXPECT_EQ(dosNames.find("G-buffer"), std::string::npos);
    dos.setTubes(straightTube(glm::dvec3(0), glm::dvec3(0, 0, 1), 4.0, 1.0, glm::vec4(1)), TubeShading{});
    dos.render(frame);
    EXPECT_NE(names(dos).find("G-buffer"), std::string::npos);
}

}  // namespace
}  // namespace curette
