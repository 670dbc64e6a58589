#include "mesh/surface_normals.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace curette::clip {

namespace {

// Closest point of triangle abc to p as barycentric weights (Ericson, Real-Time Collision Detection, 5.1.5).
glm::dvec3 closestBarycentric(glm::dvec3 p, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
    glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
    double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
    glm::dvec3 bp = p - b;
    double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
    double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        double v = d1 / (d1 - d3);
        return {1 - v, v, 0};
    }
    glm::dvec3 cp = p - c;
    double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
    double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        double w = d2 / (d2 - d6);
        return {1 - w, 0, w};
    }
    double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
        double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return {0, 1 - w, w};
    }
    double denominator = 1.0 / (va + vb + vc);
    double v = vb * denominator, w = vc * denominator;
    return {1 - v - w, v, w};
}

}  // namespace

std::vector<glm::vec3> cornerNormals(const TriangleMesh& mesh, glm::dvec3 scale, double creaseAngleDeg) {
    const std::size_t n = mesh.triangles.size();
    auto position = [&](std::uint32_t v) { return glm::dvec3(mesh.positions[v]) * scale; };
    std::vector<glm::dvec3> area(n);   // the face normal times twice the area
    std::vector<std::vector<std::uint32_t>> around(mesh.positions.size());
    for (std::size_t t = 0; t < n; ++t) {
        const glm::uvec3& tri = mesh.triangles[t];
        area[t] = glm::cross(position(tri.y) - position(tri.x), position(tri.z) - position(tri.x));
        for (int c = 0; c < 3; ++c) around[tri[c]].push_back(static_cast<std::uint32_t>(t));
    }
    const double cosCrease = std::cos(creaseAngleDeg * std::numbers::pi / 180.0);
    std::vector<glm::vec3> normals(3 * n);
    for (std::size_t t = 0; t < n; ++t) {
        double length = glm::length(area[t]);
        glm::dvec3 own = length > 0 ? area[t] / length : glm::dvec3(0, 0, 1);
        for (int c = 0; c < 3; ++c) {
            glm::dvec3 sum(0.0);
            for (std::uint32_t other : around[mesh.triangles[t][c]]) {
                double l = glm::length(area[other]);
                if (l > 0 && glm::dot(area[other] / l, own) >= cosCrease) sum += area[other];
            }
            double s = glm::length(sum);
            normals[3 * t + static_cast<std::size_t>(c)] = glm::vec3(s > 0 ? sum / s : own);
        }
    }
    return normals;
}

SurfacePoint nearestSurfacePoint(const TriangleMesh& mesh, glm::dvec3 scale, const std::vector<glm::vec3>& corners, glm::dvec3 point) {
    double best = 1e300;
    glm::dvec3 normal(0, 0, 1), nearest = point;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const glm::uvec3& tri = mesh.triangles[t];
        glm::dvec3 a = glm::dvec3(mesh.positions[tri.x]) * scale, b = glm::dvec3(mesh.positions[tri.y]) * scale,
                   c = glm::dvec3(mesh.positions[tri.z]) * scale;
        glm::dvec3 w = closestBarycentric(point, a, b, c);
        glm::dvec3 q = w.x * a + w.y * b + w.z * c;
        double d = glm::dot(q - point, q - point);
        if (d < best) {
            best = d;
            nearest = q;
            normal = w.x * glm::dvec3(corners[3 * t]) + w.y * glm::dvec3(corners[3 * t + 1]) + w.z * glm::dvec3(corners[3 * t + 2]);
        }
    }
    double l = glm::length(normal);
    return {nearest, l > 0 ? normal / l : glm::dvec3(0, 0, 1)};
}

}  // namespace curette::clip
