#include "mesh/primitives.h"

#include "base/error.h"

#include <cmath>
#include <algorithm>
#include <map>
#include <numbers>

namespace curette::clip {

namespace {

constexpr double kPi = std::numbers::pi;

void requirePositive(double value, const std::string& shape, const char* field) {
    if (!(value > 0.0) || !std::isfinite(value))
        throw InputError("<" + shape + ">", field, "a positive length in millimetres", std::to_string(value));
}

void requireSegments(int value, int minimum, const std::string& shape, const char* field) {
    if (value < minimum || value > 4096)
        throw InputError("<" + shape + ">", field, "an integer in [" + std::to_string(minimum) + ", 4096]", std::to_string(value));
}

std::uint32_t vertex(TriangleMesh& m, glm::dvec3 p) {
    m.positions.emplace_back(glm::vec3(p));
    return static_cast<std::uint32_t>(m.positions.size() - 1);
}

// A surface of revolution about z: profile points (r, z) from the bottom pole to the top pole (r = 0 at a pole
// collapses the ring to one vertex). Rings are joined with outward-facing quads.
TriangleMesh revolve(const std::vector<glm::dvec2>& profile, int segments, std::string source) {
    TriangleMesh m;
    m.source = std::move(source);
    std::vector<std::vector<std::uint32_t>> rings;
    for (const glm::dvec2& rz : profile) {
        std::vector<std::uint32_t> ring;
        if (rz.x == 0.0) {
            ring.assign(static_cast<std::size_t>(segments), vertex(m, {0, 0, rz.y}));
        } else {
            for (int s = 0; s < segments; ++s) {
                double a = 2 * kPi * s / segments;
                ring.push_back(vertex(m, {rz.x * std::cos(a), rz.x * std::sin(a), rz.y}));
            }
        }
        rings.push_back(ring);
    }
    for (std::size_t r = 0; r + 1 < rings.size(); ++r)
        for (int s = 0; s < segments; ++s) {
            std::size_t s0 = static_cast<std::size_t>(s), s1 = static_cast<std::size_t>((s + 1) % segments);
            std::uint32_t a = rings[r][s0], b = rings[r][s1], c = rings[r + 1][s0], d = rings[r + 1][s1];
            // Going up the profile with the angle increasing counter-clockwise seen from +z, (a, b, d) faces out.
            if (a != b) m.triangles.emplace_back(a, b, d);
            if (c != d) m.triangles.emplace_back(a, d, c);
        }
    return m;
}

}  // namespace

TriangleMesh makeSphere(double radius, int subdivisions) {
    requirePositive(radius, "sphere", "radius_mm");
    requireSegments(subdivisions, 0, "sphere", "resolution");
    if (subdivisions > 7) throw InputError("<sphere>", "resolution", "an icosphere level in [0, 7]", std::to_string(subdivisions));
    // Icosahedron, then each triangle split in four with the new vertices pushed onto the sphere.
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    std::vector<glm::dvec3> p = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                 {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    std::vector<glm::uvec3> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                                 {3, 8, 9},  {4, 9, 5},  {2, 4, 11},  {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    for (glm::dvec3& v : p) v = glm::normalize(v);
    for (int level = 0; level < subdivisions; ++level) {
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoints;
        auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
            auto key = std::minmax(a, b);
            auto it = midpoints.find(key);
            if (it != midpoints.end()) return it->second;
            p.push_back(glm::normalize(p[a] + p[b]));
            std::uint32_t index = static_cast<std::uint32_t>(p.size() - 1);
            midpoints[key] = index;
            return index;
        };
        std::vector<glm::uvec3> next;
        for (const glm::uvec3& t3 : f) {
            std::uint32_t ab = midpoint(t3.x, t3.y), bc = midpoint(t3.y, t3.z), ca = midpoint(t3.z, t3.x);
            next.insert(next.end(), {{t3.x, ab, ca}, {t3.y, bc, ab}, {t3.z, ca, bc}, {ab, bc, ca}});
        }
        f = std::move(next);
    }
    TriangleMesh m;
    m.source = "<sphere r=" + std::to_string(radius) + ">";
    for (const glm::dvec3& v : p) m.positions.emplace_back(glm::vec3(v * radius));
    m.triangles = std::move(f);
    orientOutward(m);
    m.solid = SolidShape{SolidShape::Kind::Sphere, radius};
    return m;
}

TriangleMesh makeBox(glm::dvec3 size) {
    for (int a = 0; a < 3; ++a) requirePositive(size[a], "box", "size_mm");
    TriangleMesh m;
    m.source = "<box>";
    glm::dvec3 h = 0.5 * size;
    for (int c = 0; c < 8; ++c) vertex(m, {(c & 1) ? h.x : -h.x, (c & 2) ? h.y : -h.y, (c & 4) ? h.z : -h.z});
    // Two triangles per face, counter-clockwise seen from outside.
    const std::uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads) m.triangles.emplace_back(q[0], q[1], q[2]), m.triangles.emplace_back(q[0], q[2], q[3]);
    orientOutward(m);
    m.solid = SolidShape{SolidShape::Kind::Box, 0, 0, size};
    return m;
}

TriangleMesh makeCylinder(double radius, double height, int segments) {
    requirePositive(radius, "cylinder", "radius_mm");
    requirePositive(height, "cylinder", "height_mm");
    requireSegments(segments, 3, "cylinder", "resolution");
    TriangleMesh m = revolve({{0, -height / 2}, {radius, -height / 2}, {radius, height / 2}, {0, height / 2}}, segments, "<cylinder>");
    m.solid = SolidShape{SolidShape::Kind::Cylinder, radius, height};
    return m;
}

TriangleMesh makeCone(double radius, double height, int segments) {
    requirePositive(radius, "cone", "radius_mm");
    requirePositive(height, "cone", "height_mm");
    requireSegments(segments, 3, "cone", "resolution");
    return revolve({{0, -height / 2}, {radius, -height / 2}, {0, height / 2}}, segments, "<cone>");
}

TriangleMesh makeCapsule(double radius, double length, int segments) {
    requirePositive(radius, "capsule", "radius_mm");
    if (!(length >= 0.0) || !std::isfinite(length))
        throw InputError("<capsule>", "length_mm", "a non-negative length of the cylindrical part", std::to_string(length));
    requireSegments(segments, 4, "capsule", "resolution");
    std::vector<glm::dvec2> profile;
    int quarter = std::max(2, segments / 4);
    for (int i = 0; i <= quarter; ++i) {  // bottom hemisphere, pole to equator
        double a = -kPi / 2 + (kPi / 2) * i / quarter;
        profile.emplace_back(radius * std::cos(a), -length / 2 + radius * std::sin(a));
    }
    for (int i = 0; i <= quarter; ++i) {  // top hemisphere, equator to pole
        double a = (kPi / 2) * i / quarter;
        profile.emplace_back(radius * std::cos(a), length / 2 + radius * std::sin(a));
    }
    profile.front().x = profile.back().x = 0.0;
    if (length == 0.0) profile.erase(profile.begin() + quarter + 1);  // a sphere: no duplicate equator
    TriangleMesh m = revolve(profile, segments, "<capsule>");
    m.solid = SolidShape{SolidShape::Kind::Capsule, radius, length};
    return m;
}

TriangleMesh makeTorus(double major, double minor, int majorSegments, int minorSegments) {
    requirePositive(major, "torus", "major_radius_mm");
    requirePositive(minor, "torus", "minor_radius_mm");
    if (minor >= major) throw InputError("<torus>", "minor_radius_mm", "less than major_radius_mm (a ring with a hole)", std::to_string(minor));
    requireSegments(majorSegments, 3, "torus", "resolution");
    requireSegments(minorSegments, 3, "torus", "resolution");
    TriangleMesh m;
    m.source = "<torus>";
    for (int i = 0; i < majorSegments; ++i) {
        double u = 2 * kPi * i / majorSegments;
        for (int j = 0; j < minorSegments; ++j) {
            double v = 2 * kPi * j / minorSegments;
            double r = major + minor * std::cos(v);
            vertex(m, {r * std::cos(u), r * std::sin(u), minor * std::sin(v)});
        }
    }
    auto at = [&](int i, int j) { return static_cast<std::uint32_t>((i % majorSegments) * minorSegments + (j % minorSegments)); };
    for (int i = 0; i < majorSegments; ++i)
        for (int j = 0; j < minorSegments; ++j) {
            m.triangles.emplace_back(at(i, j), at(i + 1, j), at(i + 1, j + 1));
            m.triangles.emplace_back(at(i, j), at(i + 1, j + 1), at(i, j + 1));
        }
    orientOutward(m);
    return m;
}

}  // namespace curette::clip
