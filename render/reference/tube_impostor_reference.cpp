#include "render/reference/tube_impostor_reference.h"

#include <algorithm>
#include <cmath>

namespace curette::reference {

std::optional<ImpostorHit> firstImpostorHit(const TubeImpostors& impostors, glm::dvec3 origin, glm::dvec3 direction,
                                            const std::function<bool(glm::dvec3)>& clipped) {
    std::optional<ImpostorHit> best;
    glm::dvec3 c0, c1;
    auto consider = [&](double t, glm::dvec3 normal, double along) {
        if (t <= 0 || (best && t >= best->t)) return;
        if (clipped && clipped(origin + t * direction)) return;
        best = ImpostorHit{t, glm::normalize(normal), glm::mix(c0, c1, std::clamp(along, 0.0, 1.0))};
    };
    for (const TubeImpostorBundle& bundle : impostors.bundles) {
        const double r = bundle.radiusMm;
        for (std::size_t i = bundle.firstPoint; i + 1 < bundle.firstPoint + bundle.pointCount; ++i) {
            const TubeImpostorPoint &a = impostors.points[i], &b = impostors.points[i + 1];
            if (!(a.colorAndFlags & kImpostorSegmentStarts)) continue;
            glm::dvec3 p0(a.position), p1(b.position), axis = p1 - p0;
            double L = glm::length(axis);
            axis /= L;
            c0 = glm::dvec3(unpackImpostorColor(a.colorAndFlags)), c1 = glm::dvec3(unpackImpostorColor(b.colorAndFlags));
            glm::dvec3 oc = origin - p0;
            double oa = glm::dot(oc, axis), da = glm::dot(direction, axis);
            glm::dvec3 ocPerp = oc - oa * axis, dirPerp = direction - da * axis;
            double A = glm::dot(dirPerp, dirPerp), B = glm::dot(ocPerp, dirPerp), C = glm::dot(ocPerp, ocPerp) - r * r;
            double disc = B * B - A * C;
            if (A > 1e-15 && disc >= 0)
                for (double sign : {-1.0, 1.0}) {
                    double t = (-B + sign * std::sqrt(disc)) / A, y = oa + t * da;
                    if (y >= 0 && y <= L) consider(t, ocPerp + t * dirPerp, y / L);
                }
            if (b.colorAndFlags & kImpostorSegmentStarts) {   // the joint's ball
                glm::dvec3 o1 = origin - p1;
                double bb = glm::dot(o1, direction), d = bb * bb - (glm::dot(o1, o1) - r * r);
                if (d >= 0) {
                    double t = -bb - std::sqrt(d);
                    consider(t, o1 + t * direction, 1.0);
                }
            }
            if (bundle.caps && std::abs(da) > 1e-12) {
                if (!(a.colorAndFlags & kImpostorSegmentEnds)) {
                    double t = -oa / da;
                    if (glm::length(oc + t * direction) <= r) consider(t, -axis, 0.0);
                }
                if (!(b.colorAndFlags & kImpostorSegmentStarts)) {
                    double t = (L - oa) / da;
                    if (glm::length(oc + t * direction - L * axis) <= r) consider(t, axis, 1.0);
                }
            }
        }
    }
    return best;
}

}  // namespace curette::reference
