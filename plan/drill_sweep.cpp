#include "plan/drill_sweep.h"

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace curette::plan {

namespace {

double distanceToSegment(glm::dvec3 p, glm::dvec3 a, glm::dvec3 b) {
    glm::dvec3 ab = b - a;
    double len2 = glm::dot(ab, ab);
    double t = len2 > 0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
    return glm::length(p - (a + t * ab));
}

// Golden-section search for the minimum of a convex f on [0, 1]: [a, b] holds the minimiser, c < d its inner
// points with their values; narrowed until `done` says so, at most `iterations` times.
struct Bracket {
    double a, b, c, d, fc, fd;
};
template <typename F, typename Done>
Bracket goldenSection(const F& f, int iterations, const Done& done) {
    const double g = (std::sqrt(5.0) - 1.0) / 2.0;
    Bracket r{0.0, 1.0, 1.0 - g, g, 0.0, 0.0};
    r.fc = f(r.c), r.fd = f(r.d);
    for (int i = 0; i < iterations && !done(r); ++i) {
        if (r.fc < r.fd) {
            r.b = r.d, r.d = r.c, r.fd = r.fc;
            r.c = r.b - g * (r.b - r.a), r.fc = f(r.c);
        } else {
            r.a = r.c, r.c = r.d, r.fc = r.fd;
            r.d = r.a + g * (r.b - r.a), r.fd = f(r.d);
        }
    }
    return r;
}

}  // namespace

DrillSweep::DrillSweep(const DrillTool& tool, const clip::RigidPose& from, const clip::RigidPose& to, double rotationToleranceMm)
    : tool_(tool) {
    boundingRadiusMm_ = glm::length(tool.shape.halfExtent() * glm::abs(tool.scale));
    smallestScale_ = std::min({std::abs(tool.scale.x), std::abs(tool.scale.y), std::abs(tool.scale.z)});
    // Sub-steps: a turn by angle a moves a point at distance rho from the centre by at most a * rho.
    glm::dquat q0 = glm::normalize(from.orientation), q1 = glm::normalize(to.orientation);
    if (glm::dot(q0, q1) < 0) q1 = -q1;
    double angle = 2.0 * std::acos(std::clamp(std::abs(glm::dot(q0, q1)), 0.0, 1.0));
    int n = std::max(1, static_cast<int>(std::ceil(angle * boundingRadiusMm_ / std::max(rotationToleranceMm, 1e-6))));
    n = std::min(n, 4096);
    auto poseAt = [&](double s) {
        clip::RigidPose p;
        p.position = glm::mix(from.position, to.position, s);
        p.orientation = n == 1 ? q0 : glm::normalize(glm::slerp(q0, q1, s));
        return p;
    };
    auto addStep = [&](const clip::RigidPose& start, glm::dvec3 end) {
        Step step;
        glm::dmat4 unscale = glm::scale(glm::dmat4(1.0), 1.0 / tool.scale);
        step.worldToLocal = unscale * start.inverseMatrix();
        glm::dvec3 d = end - start.position;
        step.localMotion = glm::dvec3(step.worldToLocal * glm::dvec4(d, 0.0));
        step.worldFrom = start.position;
        step.worldTo = end;
        steps_.push_back(step);
    };
    for (int k = 0; k < n; ++k) addStep(poseAt(double(k) / n), poseAt(double(k + 1) / n).position);
    if (n > 1) addStep(clip::RigidPose{to.position, q1}, to.position);   // the end pose itself, at its own orientation
    glm::dvec3 lo = glm::min(from.position, to.position), hi = glm::max(from.position, to.position);
    boundsMin_ = lo - glm::dvec3(boundingRadiusMm_);
    boundsMax_ = hi + glm::dvec3(boundingRadiusMm_);
}

bool DrillSweep::insideStep(const Step& step, glm::dvec3 world) const {
    if (distanceToSegment(world, step.worldFrom, step.worldTo) > boundingRadiusMm_) return false;
    glm::dvec3 q = glm::dvec3(step.worldToLocal * glm::dvec4(world, 1.0));
    auto f = [&](double t) { return tool_.shape.signedDistance(q - t * step.localMotion); };
    if (f(0.0) <= 0.0 || f(1.0) <= 0.0) return true;
    if (glm::dot(step.localMotion, step.localMotion) == 0.0) return false;
    // Stop as soon as the tool holds the point somewhere along the step.
    auto touches = [](const Bracket& r) { return r.fc <= 0.0 || r.fd <= 0.0; };
    return touches(goldenSection(f, 60, touches));
}

bool DrillSweep::contains(glm::dvec3 world) const {
    for (const Step& step : steps_)
        if (insideStep(step, world)) return true;
    return false;
}

double DrillSweep::stepDistanceBound(const Step& step, glm::dvec3 world) const {
    double far = distanceToSegment(world, step.worldFrom, step.worldTo) - boundingRadiusMm_;
    if (far > 0.0) return far;
    glm::dvec3 q = glm::dvec3(step.worldToLocal * glm::dvec4(world, 1.0));
    auto f = [&](double t) { return tool_.shape.signedDistance(q - t * step.localMotion); };
    double lipschitz = glm::length(step.localMotion);
    double lo, hi;   // the minimum over t in [0, 1] lies in [lo, hi]
    if (lipschitz == 0.0) {
        lo = hi = f(0.0);
    } else {
        const Bracket r = goldenSection(f, 200, [&](const Bracket& r) { return (r.b - r.a) * lipschitz <= 1e-9; });
        hi = std::min({r.fc, r.fd, f(0.0), f(1.0)});
        lo = std::min(r.fc, r.fd) - (r.b - r.a) * lipschitz;   // the minimiser is in [a, b], within b - a of c and d
    }
    if (lo > 0.0) return lo * smallestScale_;
    if (hi < 0.0) return hi * smallestScale_;
    return 0.0;
}

double DrillSweep::distanceBound(glm::dvec3 world) const {
    // Outside the union: outside every step (the least clearance); inside: inside one (the deepest).
    double d = std::numeric_limits<double>::infinity();
    for (const Step& step : steps_) d = std::min(d, stepDistanceBound(step, world));
    return d;
}

std::size_t applySweep(RemovalVolume& removal, const DrillSweep& sweep, bool erase, BrickMaskMap* before) {
    return removal.apply([&](glm::dvec3 w) { return sweep.contains(w); }, removal.voxelBoxAround(sweep.boundsMin(), sweep.boundsMax()), erase,
                         before, [&](glm::dvec3 w) { return sweep.distanceBound(w); });
}

}  // namespace curette::plan
