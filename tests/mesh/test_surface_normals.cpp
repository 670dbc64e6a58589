// The surface normals of clip meshes (mesh/surface_normals.h): smooth where the mesh stands for a smooth
// surface, creased where it has edges, turned by a non-uniform scale as a covector is.
#include "mesh/primitives.h"
#include "mesh/surface_normals.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace curette::clip {
namespace {

double angleDeg(glm::dvec3 a, glm::dvec3 b) {
    return std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0, 1.0)) * 180.0 / 3.14159265358979;
}

TEST(SurfaceNormals, AnIcosphereShadesAsASphere) {
    TriangleMesh sphere = makeSphere(20.0, 4);
    std::vector<glm::vec3> corners = cornerNormals(sphere, glm::dvec3(1.0));
    ASSERT_EQ(corners.size(), 3 * sphere.triangles.size());
    double worst = 0;
    for (std::size_t t = 0; t < sphere.triangles.size(); ++t)
        for (int c = 0; c < 3; ++c)
            worst = std::max(worst, angleDeg(glm::dvec3(corners[3 * t + c]), glm::dvec3(sphere.positions[sphere.triangles[t][c]])));
    EXPECT_LT(worst, 0.5) << "corner normals against the radial direction, degrees";
    // Between corners: the interpolated normal at a point near the surface is near its radial direction,
    // closer than the facet normals (up to half a facet's angle off) are.
    SurfacePoint p = nearestSurfacePoint(sphere, glm::dvec3(1.0), corners, glm::dvec3(7.0, -11.0, 14.5));
    EXPECT_LT(angleDeg(p.normal, p.point), 0.5);
    EXPECT_NEAR(glm::length(p.point), 20.0, 0.2);
}

TEST(SurfaceNormals, ABoxKeepsItsEdges) {
    TriangleMesh box = makeBox(glm::dvec3(10, 20, 30));
    std::vector<glm::vec3> corners = cornerNormals(box, glm::dvec3(1.0));
    for (std::size_t t = 0; t < box.triangles.size(); ++t) {
        const glm::uvec3& tri = box.triangles[t];
        glm::dvec3 a(box.positions[tri.x]), b(box.positions[tri.y]), c(box.positions[tri.z]);
        glm::dvec3 facet = glm::normalize(glm::cross(b - a, c - a));
        for (int k = 0; k < 3; ++k) EXPECT_LT(angleDeg(glm::dvec3(corners[3 * t + k]), facet), 1e-4) << "triangle " << t;
    }
}

TEST(SurfaceNormals, ANonUniformScaleTurnsThemAsCovectors) {
    // A sphere scaled to an ellipsoid x^2/a^2 + y^2/b^2 + z^2/c^2 = 1: its normal is (x/a^2, y/b^2, z/c^2).
    const glm::dvec3 scale(2.0, 1.0, 0.5);
    TriangleMesh sphere = makeSphere(10.0, 5);
    std::vector<glm::vec3> corners = cornerNormals(sphere, scale);
    glm::dvec3 axes = 10.0 * scale;
    double worst = 0;
    for (std::size_t t = 0; t < sphere.triangles.size(); t += 7)
        for (int c = 0; c < 3; ++c) {
            glm::dvec3 p = glm::dvec3(sphere.positions[sphere.triangles[t][c]]) * scale;
            worst = std::max(worst, angleDeg(glm::dvec3(corners[3 * t + c]), p / (axes * axes)));
        }
    EXPECT_LT(worst, 1.5) << "degrees from the ellipsoid's normal";
}

}  // namespace
}  // namespace curette::clip
