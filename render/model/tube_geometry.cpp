#include "render/model/tube_geometry.h"

#include "base/error.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace curette {

namespace {

// Centripetal Catmull-Rom (alpha = 1/2; Yuksel et al. 2011): no cusps or self-intersections within a span,
// unlike the uniform parameterisation, for unevenly spaced tractography points.
glm::dvec3 catmullRom(glm::dvec3 p0, glm::dvec3 p1, glm::dvec3 p2, glm::dvec3 p3, double u) {
    auto knot = [](double t, glm::dvec3 a, glm::dvec3 b) { return t + std::max(std::sqrt(glm::length(b - a)), 1e-6); };
    double t0 = 0, t1 = knot(t0, p0, p1), t2 = knot(t1, p1, p2), t3 = knot(t2, p2, p3);
    double t = t1 + u * (t2 - t1);
    glm::dvec3 a1 = (t1 - t) / (t1 - t0) * p0 + (t - t0) / (t1 - t0) * p1;
    glm::dvec3 a2 = (t2 - t) / (t2 - t1) * p1 + (t - t1) / (t2 - t1) * p2;
    glm::dvec3 a3 = (t3 - t) / (t3 - t2) * p2 + (t - t2) / (t3 - t2) * p3;
    glm::dvec3 b1 = (t2 - t) / (t2 - t0) * a1 + (t - t0) / (t2 - t0) * a2;
    glm::dvec3 b2 = (t3 - t) / (t3 - t1) * a2 + (t - t1) / (t3 - t1) * a3;
    return (t2 - t) / (t2 - t1) * b1 + (t - t1) / (t2 - t1) * b2;
}

// Any unit vector perpendicular to t (t unit): cross with the world axis least aligned with t.
glm::dvec3 perpendicular(glm::dvec3 t) {
    glm::dvec3 a = std::abs(t.x) < 0.57 ? glm::dvec3(1, 0, 0) : std::abs(t.y) < 0.57 ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, 1);
    return glm::normalize(glm::cross(t, a));
}

}  // namespace

SweptCurve sweepCurve(const Tractogram& tracts, std::size_t s, const TubeSettings& settings, std::size_t* duplicatesRemoved) {
    SweptCurve curve;
    // Drop consecutive points closer than a micrometre (duplicates, zero-length segments).
    std::vector<glm::dvec3> clean;
    for (std::uint32_t i = tracts.offsets[s]; i < tracts.offsets[s + 1]; ++i) {
        glm::dvec3 p(tracts.points[i]);
        if (!clean.empty() && glm::distance(clean.back(), p) < 1e-3) {
            if (duplicatesRemoved) ++*duplicatesRemoved;
            continue;
        }
        clean.push_back(p);
    }
    if (clean.size() < 2) {
        curve.points = clean;
        return curve;
    }
    // Smooth and resample at (about) stepMm along each span.
    if (settings.smoothing == TubeSettings::Smoothing::CatmullRom && clean.size() > 2 && settings.stepMm > 0) {
        std::size_t n = clean.size();
        for (std::size_t i = 0; i + 1 < n; ++i) {
            glm::dvec3 p0 = i > 0 ? clean[i - 1] : 2.0 * clean[i] - clean[i + 1];
            glm::dvec3 p3 = i + 2 < n ? clean[i + 2] : 2.0 * clean[i + 1] - clean[i];
            int steps = std::max(1, static_cast<int>(std::ceil(glm::distance(clean[i], clean[i + 1]) / settings.stepMm)));
            for (int k = 0; k < steps; ++k) {
                glm::dvec3 q = catmullRom(p0, clean[i], clean[i + 1], p3, double(k) / steps);
                if (curve.points.empty() || glm::distance(curve.points.back(), q) >= 1e-3) curve.points.push_back(q);
            }
        }
        if (glm::distance(curve.points.back(), clean.back()) >= 1e-3) curve.points.push_back(clean.back());
    } else {
        curve.points = clean;
    }
    if (curve.points.size() < 2) {
        // A degenerate spline (everything collapsed): fall back to the cleaned polyline.
        curve.points = clean;
    }
    std::size_t n = curve.points.size();
    // Tangents: central differences of unit segment directions; at an exact reversal (the two directions
    // cancel) the incoming direction is kept so the tangent never becomes zero.
    curve.tangents.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        glm::dvec3 in = i > 0 ? glm::normalize(curve.points[i] - curve.points[i - 1]) : glm::dvec3(0);
        glm::dvec3 out = i + 1 < n ? glm::normalize(curve.points[i + 1] - curve.points[i]) : glm::dvec3(0);
        glm::dvec3 t = in + out;
        curve.tangents[i] = glm::length(t) > 1e-6 ? glm::normalize(t) : (i > 0 ? in : out);
    }
    // Rotation-minimising frames by double reflection (Wang et al. 2008, Algorithm 1).
    curve.normals.resize(n);
    curve.normals[0] = perpendicular(curve.tangents[0]);
    for (std::size_t i = 0; i + 1 < n; ++i) {
        glm::dvec3 v1 = curve.points[i + 1] - curve.points[i];
        double c1 = glm::dot(v1, v1);
        glm::dvec3 r = curve.normals[i], t = curve.tangents[i];
        glm::dvec3 rL = r - (2.0 / c1) * glm::dot(v1, r) * v1;
        glm::dvec3 tL = t - (2.0 / c1) * glm::dot(v1, t) * v1;
        glm::dvec3 v2 = curve.tangents[i + 1] - tL;
        double c2 = glm::dot(v2, v2);
        glm::dvec3 next = c2 > 1e-24 ? rL - (2.0 / c2) * glm::dot(v2, rL) * v2 : rL;
        // Keep it exactly orthonormal to the tangent (rounding, and tangents kept at reversals).
        next -= glm::dot(next, curve.tangents[i + 1]) * curve.tangents[i + 1];
        curve.normals[i + 1] = glm::length(next) > 1e-9 ? glm::normalize(next) : perpendicular(curve.tangents[i + 1]);
    }
    return curve;
}

glm::dvec3 colorMap(double t) {
    // Stops approximating viridis (dark violet -> blue -> green -> yellow).
    static const glm::dvec3 stops[] = {{0.267, 0.005, 0.329}, {0.231, 0.322, 0.545}, {0.129, 0.569, 0.549},
                                       {0.369, 0.788, 0.384}, {0.993, 0.906, 0.144}};
    t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0) * 4.0;
    int i = std::min(3, static_cast<int>(t));
    return glm::mix(stops[i], stops[i + 1], t - i);
}

namespace {

struct Colorer {
    const Tractogram& tracts;
    const TubeSettings& settings;
    int scalarIndex = -1;
    double lo = 0, hi = 1;
    Colorer(const Tractogram& t, const TubeSettings& s) : tracts(t), settings(s) {
        if (s.coloring != TubeSettings::Coloring::Scalar) return;
        for (std::size_t i = 0; i < t.scalarNames.size(); ++i)
            if (t.scalarNames[i] == s.scalarName) scalarIndex = static_cast<int>(i);
        if (scalarIndex < 0) {
            std::string names;
            for (const std::string& n : t.scalarNames) names += (names.empty() ? "" : ", ") + n;
            throw InputError(t.source, "scalar", "one of the file's per-point scalars (" + (names.empty() ? std::string("it has none") : names) + ")",
                             "\"" + s.scalarName + "\"");
        }
        lo = s.scalarMin, hi = s.scalarMax;
        if (lo == hi) {
            lo = 1e300, hi = -1e300;
            for (std::size_t p = 0; p < t.points.size(); ++p) {
                double v = t.scalars[p * t.scalarNames.size() + static_cast<std::size_t>(scalarIndex)];
                lo = std::min(lo, v), hi = std::max(hi, v);
            }
            if (hi <= lo) hi = lo + 1;
        }
    }
    // Scalars live on the original points: a resampled ring takes the nearest original point's value
    // (by arc-length fraction along the streamline).
    glm::vec4 operator()(std::size_t s, glm::dvec3 tangent, double fraction) const {
        switch (settings.coloring) {
            case TubeSettings::Coloring::Direction: return glm::vec4(glm::vec3(glm::abs(tangent)), 1.0f);
            case TubeSettings::Coloring::Uniform: return glm::vec4(glm::vec3(settings.uniformColor), 1.0f);
            case TubeSettings::Coloring::Scalar: {
                std::size_t first = tracts.offsets[s], count = tracts.pointCount(s);
                std::size_t p = first + std::min(count - 1, static_cast<std::size_t>(std::lround(fraction * double(count - 1))));
                double v = tracts.scalars[p * tracts.scalarNames.size() + static_cast<std::size_t>(scalarIndex)];
                return glm::vec4(glm::vec3(colorMap((v - lo) / (hi - lo))), 1.0f);
            }
        }
        return glm::vec4(1.0f);
    }
};

void validate(const TubeSettings& s) {
    if (!(s.radiusMm > 0) || !std::isfinite(s.radiusMm)) throw InputError("<tubes>", "radius_mm", "a positive radius", std::to_string(s.radiusMm));
    if (s.sides < 3 || s.sides > 64) throw InputError("<tubes>", "sides", "an integer in [3, 64]", std::to_string(s.sides));
    if (!(s.stepMm > 0) || !std::isfinite(s.stepMm)) throw InputError("<tubes>", "step_mm", "a positive resampling step", std::to_string(s.stepMm));
}

// Each streamline's swept curve with at least two points (one point has no direction: nothing to sweep), with
// its index; counts the streamlines, the duplicate points removed and the streamlines skipped in `local`.
template <class Visit>
void forEachSweptCurve(const Tractogram& tracts, const TubeSettings& settings, TubeBuildStats& local, Progress* progress, Visit visit) {
    for (std::size_t s = 0; s < tracts.streamlineCount(); ++s) {
        ++local.streamlines;
        if (progress && s % 1024 == 1023) progress->advance(1024.0);   // the clock read per call is not free
        SweptCurve curve = sweepCurve(tracts, s, settings, &local.duplicatePointsRemoved);
        if (curve.points.size() < 2) {
            ++local.skippedSinglePoint;
            continue;
        }
        visit(s, curve);
    }
}

}  // namespace

TubeRings sweepTubeRings(const Tractogram& tracts, const TubeSettings& settings, TubeBuildStats* stats, Progress* progress) {
    validate(settings);
    Colorer color(tracts, settings);
    TubeRings out;
    TubeBuildStats local;
    forEachSweptCurve(tracts, settings, local, progress, [&](std::size_t s, const SweptCurve& curve) {
        std::size_t n = curve.points.size();
        TubeStreamline line;
        line.firstRing = static_cast<std::uint32_t>(out.rings.size());
        line.ringCount = static_cast<std::uint32_t>(n);
        line.firstVertex = static_cast<std::uint32_t>(out.vertexCount);
        line.firstIndex = static_cast<std::uint32_t>(out.indexCount);
        line.radiusMm = settings.radiusMm;
        line.sides = static_cast<std::uint32_t>(settings.sides);
        line.caps = settings.caps;
        // A cap takes the colour at its end (fraction 0 or 1), which is its end ring's.
        for (std::size_t i = 0; i < n; ++i)
            out.rings.push_back({curve.points[i], curve.tangents[i], curve.normals[i], color(s, curve.tangents[i], double(i) / double(n - 1))});
        local.rings += n;
        out.vertexCount += line.vertexCount();
        out.indexCount += line.indexCount();
        if (out.vertexCount > 0xFFFFFFFFull || out.indexCount > 0xFFFFFFFFull)
            throw InputError(tracts.source, "tubes", "at most 2^32 tube vertices and indices (fewer sides, a longer step_mm, fewer streamlines)",
                             std::to_string(out.vertexCount) + " vertices");
        out.streamlines.push_back(line);
    });
    if (stats) *stats = local;
    return out;
}

TubeImpostors sweepTubeImpostors(const Tractogram& tracts, const TubeSettings& settings, TubeBuildStats* stats, Progress* progress) {
    validate(settings);
    Colorer color(tracts, settings);
    TubeImpostors out;
    TubeBuildStats local;
    glm::dvec3 lo(1e300), hi(-1e300);
    forEachSweptCurve(tracts, settings, local, progress, [&](std::size_t s, const SweptCurve& curve) {
        std::size_t n = curve.points.size();
        for (std::size_t i = 0; i < n; ++i) {
            std::uint32_t flags = (i + 1 < n ? kImpostorSegmentStarts : 0u) | (i > 0 ? kImpostorSegmentEnds : 0u);
            out.points.push_back({glm::vec3(curve.points[i]), packImpostorColor(color(s, curve.tangents[i], double(i) / double(n - 1)), flags)});
            lo = glm::min(lo, curve.points[i]), hi = glm::max(hi, curve.points[i]);
        }
        local.rings += n;
        ++out.streamlines;
    });
    if (!out.points.empty()) {
        out.bundles.push_back({0, out.points.size(), settings.radiusMm, settings.caps});
        out.boundsMin = lo - settings.radiusMm, out.boundsMax = hi + settings.radiusMm;
    }
    if (stats) *stats = local;
    return out;
}

void TubeRings::append(const TubeRings& other) {
    std::uint32_t ringBase = static_cast<std::uint32_t>(rings.size());
    rings.insert(rings.end(), other.rings.begin(), other.rings.end());
    for (TubeStreamline line : other.streamlines) {
        line.firstRing += ringBase;
        line.firstVertex += static_cast<std::uint32_t>(vertexCount);
        line.firstIndex += static_cast<std::uint32_t>(indexCount);
        streamlines.push_back(line);
    }
    vertexCount += other.vertexCount;
    indexCount += other.indexCount;
}

TubeVertices expandTubeRings(const TubeRings& rings) {
    TubeVertices v;
    v.positions.resize(rings.vertexCount);
    v.directions.resize(rings.vertexCount);
    v.colors.resize(rings.vertexCount);
    v.indices.resize(rings.indexCount);
    for (const TubeStreamline& line : rings.streamlines) {
        const std::uint32_t sides = line.sides, n = line.ringCount;
        const double radius = line.radiusMm;
        std::uint32_t vertex = line.firstVertex, index = line.firstIndex;
        auto add = [&](glm::dvec3 p, glm::dvec3 direction, glm::vec4 c) {
            v.positions[vertex] = glm::vec3(p);
            v.directions[vertex] = glm::vec3(direction);
            v.colors[vertex] = c;
            return vertex++;
        };
        for (std::uint32_t i = 0; i < n; ++i) {
            const TubeRing& ring = rings.rings[line.firstRing + i];
            glm::dvec3 b = glm::cross(ring.tangent, ring.normal);
            for (std::uint32_t k = 0; k < sides; ++k) {
                double a = 2 * std::numbers::pi * k / sides;
                glm::dvec3 radial = std::cos(a) * ring.normal + std::sin(a) * b;
                add(ring.point + radius * radial, radial, ring.color);
            }
        }
        for (std::uint32_t i = 0; i + 1 < n; ++i)
            for (std::uint32_t k = 0; k < sides; ++k) {
                std::uint32_t a = line.firstVertex + i * sides + k, b = line.firstVertex + i * sides + (k + 1) % sides;
                std::uint32_t c = a + sides, d = b + sides;
                // (normal, binormal, tangent) is right-handed, so going round the ring then along the tube,
                // (a, b, d) and (a, d, c) are counter-clockwise seen from outside.
                for (std::uint32_t corner : {a, b, d, a, d, c}) v.indices[index++] = corner;
            }
        if (line.caps) {
            for (int end = 0; end < 2; ++end) {
                const TubeRing& ring = rings.rings[line.firstRing + (end ? n - 1 : 0)];
                glm::dvec3 axis = end ? ring.tangent : -ring.tangent;
                std::uint32_t centre = add(ring.point, axis, ring.color);
                glm::dvec3 b = glm::cross(ring.tangent, ring.normal);
                std::uint32_t rim = vertex;
                for (std::uint32_t k = 0; k < sides; ++k) {
                    double a = 2 * std::numbers::pi * k / sides;
                    add(ring.point + radius * (std::cos(a) * ring.normal + std::sin(a) * b), axis, ring.color);
                }
                for (std::uint32_t k = 0; k < sides; ++k) {
                    std::uint32_t p = rim + k, q = rim + (k + 1) % sides;
                    v.indices[index++] = centre;
                    v.indices[index++] = end ? p : q;
                    v.indices[index++] = end ? q : p;
                }
            }
        }
    }
    return v;
}

TubeVertices buildTubes(const Tractogram& tracts, const TubeSettings& settings, TubeBuildStats* stats) {
    return expandTubeRings(sweepTubeRings(tracts, settings, stats));
}

TubeVertices buildIlluminatedLines(const Tractogram& tracts, const TubeSettings& settings, TubeBuildStats* stats) {
    validate(settings);
    Colorer color(tracts, settings);
    TubeVertices v;
    v.lines = true;
    TubeBuildStats local;
    forEachSweptCurve(tracts, settings, local, nullptr, [&](std::size_t s, const SweptCurve& curve) {
        std::size_t n = curve.points.size();
        std::uint32_t first = static_cast<std::uint32_t>(v.positions.size());
        for (std::size_t i = 0; i < n; ++i) {
            v.positions.emplace_back(glm::vec3(curve.points[i]));
            v.directions.emplace_back(glm::vec3(curve.tangents[i]));
            v.colors.push_back(color(s, curve.tangents[i], double(i) / double(n - 1)));
        }
        for (std::size_t i = 0; i + 1 < n; ++i) v.indices.insert(v.indices.end(), {first + static_cast<std::uint32_t>(i), first + static_cast<std::uint32_t>(i + 1)});
        local.rings += n;
    });
    if (stats) *stats = local;
    return v;
}

glm::dvec3 illuminatedLineColor(glm::dvec3 albedo, glm::dvec3 tangent, glm::dvec3 toLight, glm::dvec3 toViewer,
                                const TransferFunction::Material& m, double diffuseExponent) {
    double lt = glm::dot(toLight, tangent), vt = glm::dot(toViewer, tangent);
    double ln = std::sqrt(std::max(1.0 - lt * lt, 0.0));                               // eq. 3.12
    // Eq. 3.13 with L and V both pointing away from the line (shaders/illuminated_lines.glsl has the signs).
    double vr = ln * std::sqrt(std::max(1.0 - vt * vt, 0.0)) - lt * vt;
    double diffuse = std::pow(ln, diffuseExponent);                                     // eq. 3.14, 3.15
    double specular = std::pow(std::max(vr, 0.0), m.specularPower);
    return albedo * (m.ambient + m.diffuse * diffuse) + glm::dvec3(m.specular * specular);
}

}  // namespace curette
