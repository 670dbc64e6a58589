#include "mesh/solid_shape.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace curette::clip {

double SolidShape::signedDistance(glm::dvec3 p) const {
    switch (kind) {
    case Kind::Sphere: return glm::length(p) - radiusMm;
    case Kind::Capsule: {
        double h = 0.5 * lengthMm;
        glm::dvec3 onAxis{0.0, 0.0, std::clamp(p.z, -h, h)};
        return glm::length(p - onAxis) - radiusMm;
    }
    case Kind::Cylinder: {
        // The box distance in (radial, axial): outside part's length plus the inside part's largest component.
        glm::dvec2 d{std::sqrt(p.x * p.x + p.y * p.y) - radiusMm, std::abs(p.z) - 0.5 * lengthMm};
        return std::min(std::max(d.x, d.y), 0.0) + glm::length(glm::max(d, glm::dvec2(0.0)));
    }
    case Kind::Box: {
        glm::dvec3 d = glm::abs(p) - 0.5 * sizeMm;
        return std::min(std::max(d.x, std::max(d.y, d.z)), 0.0) + glm::length(glm::max(d, glm::dvec3(0.0)));
    }
    }
    return 0;
}

glm::dvec3 SolidShape::halfExtent() const {
    switch (kind) {
    case Kind::Sphere: return glm::dvec3(radiusMm);
    case Kind::Capsule: return {radiusMm, radiusMm, radiusMm + 0.5 * lengthMm};
    case Kind::Cylinder: return {radiusMm, radiusMm, 0.5 * lengthMm};
    case Kind::Box: return 0.5 * sizeMm;
    }
    return glm::dvec3(0.0);
}

double SolidShape::volumeMm3() const {
    constexpr double pi = std::numbers::pi;
    double r = radiusMm;
    switch (kind) {
    case Kind::Sphere: return 4.0 / 3.0 * pi * r * r * r;
    case Kind::Capsule: return 4.0 / 3.0 * pi * r * r * r + pi * r * r * lengthMm;
    case Kind::Cylinder: return pi * r * r * lengthMm;
    case Kind::Box: return sizeMm.x * sizeMm.y * sizeMm.z;
    }
    return 0;
}

std::string SolidShape::name() const {
    switch (kind) {
    case Kind::Sphere: return "sphere";
    case Kind::Capsule: return "capsule";
    case Kind::Cylinder: return "cylinder";
    case Kind::Box: return "box";
    }
    return "?";
}

}  // namespace curette::clip
