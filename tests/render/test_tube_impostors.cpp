// Impostor tubes (render/model/tube_impostors.h, shaders/tube_impostor.comp): the G-buffer they write against the
// CPU twin (reference::firstImpostorHit) and an analytic cylinder; against the triangle tubes of the same
// streamlines (the facets of the prism bound the difference); and a mesh that clips tubes clips them as it
// clips the triangles.
#include "render/renderer.h"
#include "render/passes/tube_set.h"
#include "tests/render/gl_test_support.h"
#include "mesh/primitives.h"
#include "render/model/tube_geometry.h"
#include "render/reference/camera_ray.h"
#include "render/reference/tube_impostor_reference.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

namespace curette {
namespace {

using test::glContext;

VolumeData emptyVolume() {
    glm::ivec3 dims(16);
    return test::makeVolume(dims, test::centredAffine(dims), ScalarType::UInt8, [](glm::dvec3) { return 0.0; });
}

TransferFunction clearTransferFunction() {
    TransferFunction tf;
    tf.color = {{0, glm::dvec3(1.0)}};
    tf.opacity = {{0, 0.0}, {255, 0.0}};
    return tf;
}

// A polyline through `points` (no smoothing: the impostor points are these points).
Tractogram polyline(std::vector<std::vector<glm::dvec3>> lines) {
    Tractogram t;
    t.source = "polyline";
    for (const auto& line : lines) {
        for (glm::dvec3 p : line) t.points.emplace_back(glm::vec3(p));
        t.offsets.push_back(static_cast<std::uint32_t>(t.points.size()));
    }
    return t;
}

TubeSettings plainSettings(double radius, bool caps) {
    TubeSettings s;
    s.radiusMm = radius;
    s.caps = caps;
    s.smoothing = TubeSettings::Smoothing::None;
    s.coloring = TubeSettings::Coloring::Direction;
    return s;
}

FrameDescription viewFrom(double azimuth, double elevation, glm::ivec2 size) {
    FrameDescription f;
    f.camera.fit(glm::dvec3(0), 12.0);
    f.camera.azimuthDeg = azimuth;
    f.camera.elevationDeg = elevation;
    f.size = size;
    f.shading = ShadingMode::Phong;
    f.lights = {Light{{0.3, 0.5, 1.0}, glm::dvec3(1.0), true}};
    return f;
}

struct GBufferImage {
    std::vector<float> depth;
    std::vector<glm::vec4> color, normal;
};

GBufferImage renderGBuffer(Renderer& renderer, const FrameDescription& frame) {
    renderer.render(frame);
    return {renderer.gbuffer().readDepth(), renderer.gbuffer().readColor(), renderer.gbuffer().readNormal()};
}

// Every pixel of the G-buffer against the CPU twin: the same pixels covered (but for a ray grazing the
// silhouette within float rounding), the view depth, normal and colour of each.
void expectMatchesTwin(const TubeImpostors& impostors, const FrameDescription& frame, const GBufferImage& g, const char* what) {
    SCOPED_TRACE(what);
    int covered = 0, grazingMismatches = 0;
    double depthError = 0, normalError = 0, colorError = 0;
    for (int y = 0; y < frame.size.y; ++y)
        for (int x = 0; x < frame.size.x; ++x) {
            std::size_t i = static_cast<std::size_t>(y * frame.size.x + x);
            auto [eye, direction] = reference::cameraRay(frame, {x, y});
            std::optional<reference::ImpostorHit> hit = reference::firstImpostorHit(impostors, eye, direction);
            bool gpu = g.depth[i] > 0;
            if (gpu != hit.has_value()) {
                // Allowed only where the ray passes within 1e-4 of a radius of the surface's edge: the twin with
                // the radius 1e-4 larger and smaller must disagree about this ray.
                TubeImpostors wider = impostors, narrower = impostors;
                for (auto& b : wider.bundles) b.radiusMm *= 1.0001;
                for (auto& b : narrower.bundles) b.radiusMm *= 0.9999;
                bool grazing = reference::firstImpostorHit(wider, eye, direction).has_value() !=
                               reference::firstImpostorHit(narrower, eye, direction).has_value();
                EXPECT_TRUE(grazing) << "pixel " << x << ", " << y << ": GPU " << gpu << ", CPU " << hit.has_value();
                grazingMismatches += grazing;
                continue;
            }
            if (!gpu) continue;
            ++covered;
            double viewDepth = hit->t * glm::dot(direction, frame.camera.forward());
            depthError = std::max(depthError, std::abs(double(g.depth[i]) - viewDepth));
            normalError = std::max(normalError, glm::distance(glm::dvec3(g.normal[i]), hit->normal));
            colorError = std::max(colorError, glm::distance(glm::dvec3(g.color[i]), hit->color));
            EXPECT_EQ(g.normal[i].w, 1.0f) << "kind: tube";
        }
    std::printf("[ impostor  ] %s: %d pixels, depth %.2e mm, normal %.2e, colour %.2e, %d grazing mismatches\n", what, covered, depthError,
                normalError, colorError, grazingMismatches);
    EXPECT_GT(covered, 200);
    EXPECT_LE(grazingMismatches, 3);
    EXPECT_LT(depthError, 2e-3);
    EXPECT_LT(normalError, 5e-3);
    EXPECT_LT(colorError, 2e-3);   // the G-buffer is RGBA16F
}

// A straight streamline across the view: at the centre pixel the surface is the cylinder's nearest point, one
// radius in front of its axis, facing the eye; and every pixel matches the twin.
TEST(TubeImpostors, TheGBufferIsTheExactCylinder) {
    glContext();
    Renderer renderer(glContext(), emptyVolume(), clearTransferFunction());
    const double radius = 1.2;
    TubeImpostors impostors =
        sweepTubeImpostors(polyline({{{-9, 0, 0}, {-3, 0, 0}, {3, 0, 0}, {9, 0, 0}}}), plainSettings(radius, false));
    renderer.setTubeImpostors(impostors, TubeShading{});
    FrameDescription frame = viewFrom(0, 0, {63, 63});
    GBufferImage g = renderGBuffer(renderer, frame);
    std::size_t centre = 31 * 63 + 31;
    ASSERT_GT(g.depth[centre], 0.0f);
    EXPECT_NEAR(g.depth[centre], frame.camera.distanceMm - radius, 1e-3);
    EXPECT_NEAR(glm::dot(glm::dvec3(g.normal[centre]), -frame.camera.forward()), 1.0, 1e-4);
    expectMatchesTwin(impostors, frame, g, "straight");
}

// Bent streamlines seen from an angle, with joints, open ends, caps and two radii: every pixel matches the twin
// (a gap at a bend would show as pixels the twin covers and the GPU does not).
TEST(TubeImpostors, BendsJointsAndCapsMatchTheCpuTwin) {
    glContext();
    Renderer renderer(glContext(), emptyVolume(), clearTransferFunction());
    TubeImpostors impostors =
        sweepTubeImpostors(polyline({{{-8, -2, 0}, {-2, 1, 1}, {0, -3, 2}, {4, 2, -1}, {8, 0, 3}}, {{-6, 5, -4}, {0, 6, 4}, {6, 4, -5}}}),
                           plainSettings(0.9, false));
    impostors.append(sweepTubeImpostors(polyline({{{-5, -6, -5}, {-1, -4, 6}, {5, -7, 0}}}), plainSettings(1.5, true)));
    renderer.setTubeImpostors(impostors, TubeShading{});
    for (auto [azimuth, elevation] : {std::pair{20.0, 15.0}, std::pair{75.0, -40.0}, std::pair{170.0, 80.0}}) {
        FrameDescription frame = viewFrom(azimuth, elevation, {72, 64});
        expectMatchesTwin(impostors, frame, renderGBuffer(renderer, frame), ("azimuth " + std::to_string(int(azimuth))).c_str());
    }
}

// One long segment from behind the eye to far in front of it, passing 3.5 mm beside the eye: its capsule has no
// one rectangle in front of the eye, so it is bounded piece by piece, and every pixel still matches the twin
// (the quads left such a segment out whole).
TEST(TubeImpostors, ASegmentPassingBesideTheEyeIsDrawn) {
    glContext();
    Renderer renderer(glContext(), emptyVolume(), clearTransferFunction());
    FrameDescription frame = viewFrom(20, 10, {64, 64});
    frame.camera.distanceMm = 30.0;
    const glm::dvec3 eye = frame.camera.position(), forward = frame.camera.forward(), side = frame.camera.right();
    const glm::dvec3 from = eye - 10.0 * forward + 3.5 * side, to = eye + 40.0 * forward + 3.5 * side;
    TubeImpostors impostors = sweepTubeImpostors(polyline({{from, to}}), plainSettings(1.0, true));
    ASSERT_EQ(impostors.points.size(), 2u);
    renderer.setTubeImpostors(impostors, TubeShading{});
    expectMatchesTwin(impostors, frame, renderGBuffer(renderer, frame), "beside the eye");
}

// Two bundles on the same points in two colours: at every pixel both lie at exactly the same depth, and the
// G-buffer shows the one drawn first, as a depth-tested draw keeps the first of equal depths (the compute pass
// picks the lowest point index among the nearest).
TEST(TubeImpostors, OfTwoSurfacesAtTheSameDepthTheFirstShows) {
    glContext();
    Renderer renderer(glContext(), emptyVolume(), clearTransferFunction());
    TubeImpostors shape = sweepTubeImpostors(polyline({{{-8, -2, 0}, {-2, 1, 1}, {0, -3, 2}, {4, 2, -1}, {8, 0, 3}}}), plainSettings(1.1, true));
    auto coloured = [&](std::uint32_t rgb) {
        TubeImpostors t = shape;
        for (TubeImpostorPoint& p : t.points) p.colorAndFlags = (p.colorAndFlags & 0xFF000000u) | rgb;
        return t;
    };
    for (bool greenFirst : {true, false}) {
        TubeImpostors both = coloured(greenFirst ? 0x00FF00u : 0x0000FFu);
        both.append(coloured(greenFirst ? 0x0000FFu : 0x00FF00u));
        renderer.setTubeImpostors(both, TubeShading{});
        FrameDescription frame = viewFrom(30, 20, {72, 64});
        GBufferImage g = renderGBuffer(renderer, frame);
        int covered = 0, first = 0;
        for (std::size_t i = 0; i < g.depth.size(); ++i)
            if (g.depth[i] > 0) ++covered, first += greenFirst ? g.color[i].g == 1.0f && g.color[i].r == 0.0f : g.color[i].r == 1.0f && g.color[i].g == 0.0f;
        EXPECT_GT(covered, 200);
        EXPECT_EQ(first, covered) << (greenFirst ? "green" : "red") << " drawn first";
    }
}

// Impostors against the triangle tubes of the same points (a 12-sided prism, caps): where both cover a pixel
// facing the eye, the prism lies behind the cylinder by at most its sagitta r (1 - cos(pi / sides)) along the
// face normal, which is within pi / sides of the cylinder's; but for the slivers between a cap's polygon and
// its disc (and silhouettes over another tube), where the triangles show what lies behind: at most 5 % of the
// pixels. There the images differ too; elsewhere by the smooth vertex normals against the exact ones.
TEST(TubeImpostors, MatchTheTriangleTubesWithinTheirFacets) {
    glContext();
    Renderer renderer(glContext(), emptyVolume(), clearTransferFunction());
    TubeSettings settings = plainSettings(1.0, true);
    settings.sides = 12;
    settings.smoothing = TubeSettings::Smoothing::CatmullRom;
    settings.stepMm = 0.5;
    Tractogram tracts = polyline({{{-8, -2, 0}, {-3, 1, 1}, {2, -1, 2}, {8, 1, 0}}, {{-6, 4, -3}, {0, 5, 2}, {6, 3, -4}}});
    FrameDescription frame = viewFrom(25, 20, {96, 96});
    renderer.setTubes(buildTubes(tracts, settings), TubeShading{});
    GBufferImage triangles = renderGBuffer(renderer, frame);
    Image triangleImage = renderer.readImage();
    renderer.setTubeImpostors(sweepTubeImpostors(tracts, settings), TubeShading{});
    GBufferImage impostors = renderGBuffer(renderer, frame);
    Image impostorImage = renderer.readImage();
    const double sagitta = settings.radiusMm * (1 - std::cos(std::numbers::pi / settings.sides));
    int both = 0, onlyOne = 0, facing = 0, beyondFacets = 0, colourApart = 0;
    double colorDifference = 0;
    for (int y = 0; y < frame.size.y; ++y)
        for (int x = 0; x < frame.size.x; ++x) {
            std::size_t i = static_cast<std::size_t>(y * frame.size.x + x);
            bool t = triangles.depth[i] > 0, m = impostors.depth[i] > 0;
            if (t != m) ++onlyOne;
            if (!t || !m) continue;
            ++both;
            auto [eye, direction] = reference::cameraRay(frame, {x, y});
            double cosine = std::abs(glm::dot(glm::dvec3(impostors.normal[i]), direction));
            if (cosine < 0.5) continue;
            ++facing;
            double behind = (double(triangles.depth[i]) - double(impostors.depth[i])) / glm::dot(direction, frame.camera.forward());
            EXPECT_GE(behind, -1e-3) << "the prism lies inside the cylinder: pixel " << x << ", " << y;
            double faceAngle = std::min(std::acos(cosine) + std::numbers::pi / settings.sides, 1.4);
            beyondFacets += behind > sagitta / std::cos(faceAngle) + 0.01;
            double c = 0;
            for (int ch = 0; ch < 3; ++ch) c = std::max(c, double(std::abs(triangleImage.at(x, y)[ch] - impostorImage.at(x, y)[ch])));
            colorDifference = std::max(colorDifference, c);
            colourApart += c > 0.1;
        }
    std::printf("[ impostor  ] against 12-sided triangle tubes: %d pixels both (%d facing), %d only one; %d facing pixels beyond the facet "
                "bound, %d more than 0.1 apart in colour (largest %.3f)\n",
                both, facing, onlyOne, beyondFacets, colourApart, colorDifference);
    EXPECT_GT(facing, 300);
    EXPECT_LE(beyondFacets, facing / 20);
    EXPECT_LE(colourApart, facing / 20);
    EXPECT_LT(onlyOne, both / 20) << "coverage differs along silhouettes only";
}

// A mesh set to clip tubes removes impostor pixels where it removes triangle-tube pixels; one that does not
// leaves them whole. Where the front of the tube is clipped, the inner wall behind shows, as with triangles.
TEST(TubeImpostors, AClipMeshRemovesTheirPixelsAsItDoesTriangleTubes) {
    glContext();
    Renderer renderer(glContext(), emptyVolume(), clearTransferFunction());
    TubeSettings settings = plainSettings(1.5, true);
    settings.sides = 24;
    Tractogram tracts = polyline({{{-12, 0, 0}, {-4, 0, 0}, {4, 0, 0}, {12, 0, 0}}});
    FrameDescription frame = viewFrom(0, 0, {48, 48});
    frame.camera.fit(glm::dvec3(0), 16.0);
    frame.camera.azimuthDeg = 0, frame.camera.elevationDeg = 0;
    auto tubePixels = [&]() {
        renderer.render(frame);
        std::vector<float> depth = renderer.gbuffer().readDepth();
        std::vector<bool> covered(depth.size());
        for (std::size_t i = 0; i < depth.size(); ++i) covered[i] = depth[i] > 0;
        return covered;
    };
    auto count = [](const std::vector<bool>& c) { return static_cast<int>(std::count(c.begin(), c.end(), true)); };
    clip::ClipMeshSet& clip = renderer.clipMeshes();
    clip.add(std::make_shared<const clip::TriangleMesh>(clip::makeSphere(5.0, 3)), glm::dvec3(1), {}, "sphere");
    std::vector<bool> cutTriangles, cutImpostors, fullImpostors;
    for (bool impostor : {false, true}) {
        clip.setClipsTubes(0, false);
        if (impostor) renderer.setTubeImpostors(sweepTubeImpostors(tracts, settings), TubeShading{});
        else renderer.setTubes(buildTubes(tracts, settings), TubeShading{});
        std::vector<bool> full = tubePixels();
        clip.setClipsTubes(0, true);
        std::vector<bool> cut = tubePixels();
        EXPECT_LT(count(cut), count(full) - 20) << (impostor ? "impostors" : "triangles");
        EXPECT_GT(count(cut), count(full) / 3) << (impostor ? "impostors" : "triangles");
        (impostor ? cutImpostors : cutTriangles) = cut;
        if (impostor) fullImpostors = full;
    }
    int differ = 0;
    for (std::size_t i = 0; i < cutTriangles.size(); ++i) differ += cutTriangles[i] != cutImpostors[i];
    std::printf("[ impostor  ] clipped: triangles %d pixels, impostors %d, %d differ (of %d unclipped)\n", count(cutTriangles),
                count(cutImpostors), differ, count(fullImpostors));
    EXPECT_LE(differ, count(fullImpostors) / 20) << "the same pixels clipped, but for the prism's silhouette";
}

// A set larger than a buffer texture's limit is drawn in windows, each bound at an aligned offset at or below its
// first point: forced down to 40 points, the windows draw the G-buffer one window draws.
TEST(TubeImpostors, WindowsOfFewPointsDrawWhatOneWindowDraws) {
    glContext();
    Renderer renderer(glContext(), emptyVolume(), clearTransferFunction());
    std::mt19937 random(8);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<std::vector<glm::dvec3>> lines;
    for (int s = 0; s < 60; ++s) {
        glm::dvec3 p = 8.0 * glm::dvec3(u(random), u(random), u(random)), step(u(random), u(random), u(random));
        lines.emplace_back();
        for (int i = 0; i < 5 + s % 20; ++i, p += 0.8 * step + 0.3 * glm::dvec3(u(random), u(random), u(random))) lines.back().push_back(p);
    }
    TubeImpostors impostors = sweepTubeImpostors(polyline(lines), plainSettings(0.5, false));
    impostors.append(sweepTubeImpostors(polyline({{{-9, -9, 0}, {0, -6, 1}, {9, -9, 2}}}), plainSettings(1.2, true)));
    ASSERT_GT(impostors.points.size(), 10u * 40u);
    FrameDescription frame = viewFrom(30, 25, {64, 64});
    TubeSet one(impostors), windows(impostors, 40);
    GBuffer a, b;
    one.drawGBuffer(frame, renderer.clipMeshes(), a);
    windows.drawGBuffer(frame, renderer.clipMeshes(), b);
    std::vector<float> depthA = a.readDepth(), depthB = b.readDepth();
    int covered = 0;
    for (float d : depthA) covered += d > 0;
    EXPECT_GT(covered, 400);
    EXPECT_EQ(depthA, depthB);
    EXPECT_TRUE(a.readColor() == b.readColor());
    EXPECT_TRUE(a.readNormal() == b.readNormal());
}

}  // namespace
}  // namespace curette
