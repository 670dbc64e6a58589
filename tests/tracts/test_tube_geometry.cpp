// Tube and illuminated-line geometry on hard inputs: no NaN anywhere, unit normals, orthonormal frames,
// zero twist (parallel transport), watertight tubes with caps, colour by direction.
#include "render/model/tube_geometry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <random>

namespace curette {
namespace {

Tractogram tractogram(const std::vector<std::vector<glm::vec3>>& lines) {
    Tractogram t;
    t.source = "test";
    for (const auto& line : lines) {
        t.points.insert(t.points.end(), line.begin(), line.end());
        t.offsets.push_back(static_cast<std::uint32_t>(t.points.size()));
    }
    return t;
}

void expectFinite(const TubeVertices& v) {
    for (std::size_t i = 0; i < v.positions.size(); ++i) {
        for (int a = 0; a < 3; ++a) {
            ASSERT_TRUE(std::isfinite(v.positions[i][a])) << i;
            ASSERT_TRUE(std::isfinite(v.directions[i][a])) << i;
        }
        ASSERT_NEAR(glm::length(v.directions[i]), 1.0f, 1e-4f) << "unit normal " << i;
    }
}

// Every edge of a closed tube (with caps) is shared by exactly two triangles in opposite directions.
void expectWatertight(const TubeVertices& v) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
    // Cap rims duplicate ring positions (with other normals): weld by position.
    std::map<std::tuple<float, float, float>, std::uint32_t> weld;
    std::vector<std::uint32_t> id(v.positions.size());
    for (std::size_t i = 0; i < v.positions.size(); ++i)
        id[i] = weld.emplace(std::tuple{v.positions[i].x, v.positions[i].y, v.positions[i].z}, static_cast<std::uint32_t>(weld.size())).first->second;
    for (std::size_t t = 0; t < v.indices.size(); t += 3)
        for (int e = 0; e < 3; ++e) ++directed[{id[v.indices[t + e]], id[v.indices[t + (e + 1) % 3]]}];
    for (const auto& [edge, count] : directed) {
        ASSERT_EQ(count, 1) << "edge used twice in one direction";
        ASSERT_EQ(directed.count({edge.second, edge.first}), 1u) << "open edge";
    }
}

TEST(TubeGeometry, HardInputsStayFiniteAndWatertight) {
    std::vector<std::vector<glm::vec3>> lines = {
        {{0, 0, 0}, {0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {1, 0, 0}, {2, 1, 0}},  // duplicates, zero-length segments
        {{0, 0, 0}, {5, 0, 0}, {5, 0.001f, 0}, {0, 0.002f, 0}},              // a hairpin (near 180-degree turn)
        {{0, 0, 0}, {3, 0, 0}, {0, 0, 0}},                                   // an exact reversal A -> B -> A
        {{7, 7, 7}},                                                         // one point
        {{0, 0, 0}, {0, 0, 10}},                                             // two points, straight along z
        {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}, {4, 4, 4}},             // straight diagonal
    };
    for (auto smoothing : {TubeSettings::Smoothing::None, TubeSettings::Smoothing::CatmullRom}) {
        TubeSettings s;
        s.smoothing = smoothing;
        TubeBuildStats stats;
        TubeVertices v = buildTubes(tractogram(lines), s, &stats);
        expectFinite(v);
        // Closed surfaces, one streamline at a time (the exact reversal's tube lies on top of itself, so
        // welding by position cannot tell its two halves apart; finiteness covers it).
        for (std::size_t line : {0u, 1u, 4u, 5u}) expectWatertight(buildTubes(tractogram({lines[line]}), s));
        EXPECT_EQ(stats.skippedSinglePoint, 1u);
        EXPECT_GE(stats.duplicatePointsRemoved, 3u);
        TubeVertices l = buildIlluminatedLines(tractogram(lines), s);
        expectFinite(l);
        EXPECT_TRUE(l.lines);
        EXPECT_EQ(l.indices.size() % 2, 0u);
    }
}

// Parallel transport: frames stay orthonormal and never twist about the tangent. Between consecutive rings
// the normal's rotation about the tangent (after removing the tangent's own turn) must be ~0; for a planar
// curve the normal must stay out of plane or in plane throughout (no flip at inflections).
TEST(TubeGeometry, FramesAreOrthonormalAndDoNotTwist) {
    std::vector<glm::vec3> helix, wave;
    for (int i = 0; i <= 200; ++i) {
        double a = 0.1 * i;
        helix.emplace_back(5 * std::cos(a), 5 * std::sin(a), 0.5 * a);
        wave.emplace_back(0.2f * static_cast<float>(i), 2 * std::sin(0.3 * i), 0.0f);  // planar, with inflections
    }
    Tractogram t = tractogram({helix, wave});
    TubeSettings s;
    for (std::size_t line = 0; line < 2; ++line) {
        SweptCurve c = sweepCurve(t, line, s);
        double maxTwist = 0;
        for (std::size_t i = 0; i < c.points.size(); ++i) {
            ASSERT_NEAR(glm::length(c.tangents[i]), 1.0, 1e-9);
            ASSERT_NEAR(glm::length(c.normals[i]), 1.0, 1e-9);
            ASSERT_NEAR(glm::dot(c.tangents[i], c.normals[i]), 0.0, 1e-9);
            if (i == 0) continue;
            // Transport the previous normal by the minimal rotation taking t[i-1] to t[i]; the difference to
            // the actual normal is the twist.
            glm::dvec3 a = c.tangents[i - 1], b = c.tangents[i];
            glm::dvec3 axis = glm::cross(a, b);
            double sine = glm::length(axis), cosine = glm::dot(a, b);
            glm::dvec3 n = c.normals[i - 1];
            if (sine > 1e-12) {
                axis /= sine;
                n = n * cosine + glm::cross(axis, n) * sine + axis * glm::dot(axis, n) * (1 - cosine);
            }
            maxTwist = std::max(maxTwist, std::acos(std::clamp(glm::dot(n, c.normals[i]), -1.0, 1.0)));
        }
        // Double reflection approximates the rotation-minimising frame to third order in the step: far
        // below a degree per ring at these curvatures.
        EXPECT_LT(maxTwist, 1e-3) << "line " << line;
        if (line == 1) {
            // The wave lies in z = 0: a rotation-minimising frame starting out of plane stays out of plane
            // (normal.z keeps its sign and magnitude), with no flip at the inflections.
            double z0 = c.normals[0].z;
            for (const glm::dvec3& nrm : c.normals) ASSERT_NEAR(std::abs(nrm.z), std::abs(z0), 1e-6);
        }
    }
}

TEST(TubeGeometry, StraightLinesKeepAStableFrameAndDirectionColour) {
    Tractogram t = tractogram({{{0, 0, 0}, {0, 5, 0}, {0, 10, 0}, {0, 15, 0}}});
    TubeSettings s;
    SweptCurve c = sweepCurve(t, 0, s);
    for (const glm::dvec3& n : c.normals) ASSERT_NEAR(glm::length(n - c.normals[0]), 0.0, 1e-12);
    TubeVertices v = buildTubes(t, s);
    for (const glm::vec4& color : v.colors) ASSERT_EQ(glm::vec3(color), glm::vec3(0, 1, 0)) << "|tangent| as RGB";
    // Every ring vertex lies at the radius from the axis.
    for (std::size_t i = 0; i < v.positions.size(); ++i) {
        double r = glm::length(glm::dvec2(v.positions[i].x, v.positions[i].z));
        if (std::abs(glm::dot(glm::dvec3(v.directions[i]), glm::dvec3(0, 1, 0))) < 0.5) {
            EXPECT_NEAR(r, s.radiusMm, 1e-6);
        }
    }
}

// Seed 004 eq. 3.12-3.15 for known configurations.
// Impostor points are the rings' centres and colours (RGB8, rounded), with the segment flags marking each
// streamline's first and last point; a one-point streamline has none; appending renumbers the bundles.
TEST(TubeImpostors, PointsAreTheRingsWithSegmentFlags) {
    Tractogram t = tractogram({{{0, 0, 0}, {3, 1, 0}, {6, 0, 2}, {9, 3, 1}}, {{1, 1, 1}}, {{0, 5, 0}, {0, 5, 4}}});
    TubeSettings s;
    s.radiusMm = 0.7;
    s.caps = false;
    s.stepMm = 0.8;
    TubeRings rings = sweepTubeRings(t, s);
    TubeBuildStats stats;
    TubeImpostors impostors = sweepTubeImpostors(t, s, &stats);
    EXPECT_EQ(stats.skippedSinglePoint, 1u);
    EXPECT_EQ(impostors.streamlines, 2u);
    ASSERT_EQ(impostors.points.size(), rings.rings.size());
    ASSERT_EQ(impostors.bundles.size(), 1u);
    EXPECT_EQ(impostors.bundles[0].pointCount, rings.rings.size());
    EXPECT_EQ(impostors.bundles[0].radiusMm, 0.7);
    EXPECT_FALSE(impostors.bundles[0].caps);
    for (const TubeStreamline& line : rings.streamlines)
        for (std::uint32_t i = 0; i < line.ringCount; ++i) {
            const TubeRing& ring = rings.rings[line.firstRing + i];
            const TubeImpostorPoint& p = impostors.points[line.firstRing + i];
            EXPECT_EQ(p.position, glm::vec3(ring.point));
            EXPECT_LE(glm::distance(unpackImpostorColor(p.colorAndFlags), glm::vec3(ring.color)), 0.5f * std::sqrt(3.0f) / 255.0f + 1e-6f);
            EXPECT_EQ((p.colorAndFlags & kImpostorSegmentStarts) != 0, i + 1 < line.ringCount);
            EXPECT_EQ((p.colorAndFlags & kImpostorSegmentEnds) != 0, i > 0);
        }
    for (const glm::vec3& p : t.points) {
        EXPECT_TRUE(glm::all(glm::greaterThanEqual(glm::dvec3(p), impostors.boundsMin + 0.7 - 1e-9)) || p == glm::vec3(1, 1, 1));
        EXPECT_TRUE(glm::all(glm::lessThanEqual(glm::dvec3(p), impostors.boundsMax - 0.7 + 1e-9)) || p == glm::vec3(1, 1, 1));
    }
    TubeImpostors twice = impostors;
    twice.append(impostors);
    ASSERT_EQ(twice.bundles.size(), 2u);
    EXPECT_EQ(twice.bundles[1].firstPoint, impostors.points.size());
    EXPECT_EQ(twice.streamlines, 4u);
    EXPECT_EQ(twice.bytes(), 2 * 16 * impostors.points.size());
}

TEST(IlluminatedLines, OracleMatchesTheEquations) {
    TransferFunction::Material m{0.1, 0.6, 0.3, 20};
    glm::dvec3 albedo(1, 0.5, 0.25);
    // A headlit line across the view (L = V perpendicular to T): L.N = 1, full diffuse, and the mirror
    // direction points at the viewer: V.R = 1, the full highlight.
    glm::dvec3 c = illuminatedLineColor(albedo, {1, 0, 0}, {0, 1, 0}, {0, 1, 0}, m, 2.0);
    EXPECT_NEAR(c.r, albedo.r * (0.1 + 0.6) + 0.3, 1e-12);
    // A line pointing at the eye and the light (L = V parallel to T): no diffuse, no highlight.
    c = illuminatedLineColor(albedo, {1, 0, 0}, {1, 0, 0}, {1, 0, 0}, m, 2.0);
    EXPECT_NEAR(c.g, albedo.g * 0.1, 1e-12);
    // Light along the line, viewer across it: L.N = 0, ambient only.
    c = illuminatedLineColor(albedo, {1, 0, 0}, {1, 0, 0}, {0, 1, 0}, m, 2.0);
    EXPECT_NEAR(c.g, albedo.g * 0.1, 1e-12);
    // L = V at 53 degrees to the tangent: the best normal reflects L into 2 (L.N)^2 - 1 = 0.28 of V:
    // V.R = 0.8 * 0.8 - 0.6 * 0.6.
    c = illuminatedLineColor(albedo, {1, 0, 0}, {0.6, 0.8, 0}, {0.6, 0.8, 0}, m, 2.0);
    EXPECT_NEAR(c.b, albedo.b * (0.1 + 0.6 * 0.64) + 0.3 * std::pow(0.28, 20), 1e-12);
    // Light and viewer on opposite sides of the normal plane (L.T = 0.9, V.T = -0.9): V.R = 0.19 + 0.81 = 1.
    c = illuminatedLineColor(albedo, {1, 0, 0}, {0.9, std::sqrt(0.19), 0}, {-0.9, 0, std::sqrt(0.19)}, m, 2.0);
    EXPECT_NEAR(c.b, albedo.b * (0.1 + 0.6 * 0.19) + 0.3, 1e-9);  // 20 * the rounding of sqrt(0.19)^2
    // The diffuse exponent p of eq. 3.15 darkens oblique light: (L.N)^4 instead of (L.N)^2.
    c = illuminatedLineColor(albedo, {1, 0, 0}, {0.6, 0.8, 0}, {0.6, 0.8, 0}, m, 4.0);
    EXPECT_NEAR(c.b, albedo.b * (0.1 + 0.6 * 0.4096) + 0.3 * std::pow(0.28, 20), 1e-12);
}

}  // namespace
}  // namespace curette
