#pragma once
// The analytic solid a primitive clip mesh approximates (mesh/primitives.h: centred at the origin, axis along
// +z): what a drill removes when the mesh is a burr (plan/drill_sweep.h). Its signed distance is exact (the
// Euclidean distance to the surface, negative inside) and convex for every kind here, which the swept-volume
// test relies on. Cones and tori carry none: a cone's apex makes its exact distance awkward, a torus is not
// convex.

#include <glm/glm.hpp>

#include <string>

namespace curette::clip {

struct SolidShape {
    enum class Kind { Sphere, Box, Cylinder, Capsule };
    Kind kind = Kind::Sphere;
    double radiusMm = 0;        // sphere, cylinder, capsule
    double lengthMm = 0;        // cylinder: its height; capsule: its cylindrical part (between the caps' centres)
    glm::dvec3 sizeMm{0.0};     // box: edge lengths

    // Exact signed distance of a mesh-local point (mm), negative inside.
    double signedDistance(glm::dvec3 local) const;
    // Half the extent along each local axis.
    glm::dvec3 halfExtent() const;
    double volumeMm3() const;
    std::string name() const;   // "sphere", "box", "cylinder", "capsule"
};

}  // namespace curette::clip
