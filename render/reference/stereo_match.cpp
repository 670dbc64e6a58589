#include "render/reference/stereo_match.h"

#include "render/reference/camera_ray.h"
#include "render/reference/raycast_reference.h"

#include <algorithm>
#include <cmath>

namespace curette {

std::optional<SurfacePoint> surfacePoint(const SurfaceScene& scene, const EyeView& eye, glm::ivec2 pixel) {
    const reference::CameraRay ray = reference::cameraRay(eye.frame, pixel);
    reference::RaycastOptions options;
    options.clipped = scene.clipped;
    std::size_t index = static_cast<std::size_t>(pixel.y) * static_cast<std::size_t>(eye.frame.size.x) + static_cast<std::size_t>(pixel.x);
    double tubeDepth = index < eye.tubeViewDepth.size() ? eye.tubeViewDepth[index] : 0.0;
    // The G-buffer holds the depth along the view axis; the march measures along the ray.
    if (tubeDepth > 0) options.opaqueAtMm = tubeDepth / glm::dot(ray.direction, eye.frame.camera.forward());
    FrameDescription solid = eye.frame;
    solid.shading = ShadingMode::Solid;   // only the opacity matters: no gradients for lighting
    reference::RaycastResult r = reference::raycastPixel(scene.volume, scene.transferFunction, solid, scene.stepMm, pixel, options);
    if (r.halfOpacityDistanceMm >= 0) return SurfacePoint{ray.origin + r.halfOpacityDistanceMm * ray.direction, false};
    if (tubeDepth > 0) return SurfacePoint{ray.origin + options.opaqueAtMm * ray.direction, true};
    return std::nullopt;
}

glm::dvec2 projectToPixel(const FrameDescription& frame, glm::dvec3 world) {
    glm::dvec4 clip = frame.camera.viewProjection(frame.size) * glm::dvec4(world, 1.0);
    glm::dvec2 ndc = glm::dvec2(clip) / clip.w;
    return {(ndc.x + 1.0) / 2.0 * frame.size.x, (1.0 - ndc.y) / 2.0 * frame.size.y};
}

std::vector<StereoMatch> matchSurfacePoints(const SurfaceScene& scene, const EyeView& left, const EyeView& right,
                                            const MatchSettings& settings, MatchCounts* counts) {
    MatchCounts c;
    std::vector<StereoMatch> matches;
    const int stride = std::max(1, settings.stride);
    for (int y = 0; y < left.frame.size.y; y += stride) {
        for (int x = 0; x < left.frame.size.x; x += stride) {
            ++c.tried;
            std::optional<SurfacePoint> l = surfacePoint(scene, left, {x, y});
            if (!l) continue;
            ++c.surfaces;
            glm::dvec2 q = projectToPixel(right.frame, l->world);
            glm::ivec2 r(static_cast<int>(std::floor(q.x)), static_cast<int>(std::floor(q.y)));
            if (r.x < 0 || r.y < 0 || r.x >= right.frame.size.x || r.y >= right.frame.size.y) {
                ++c.outside;
                continue;
            }
            if (std::abs(q.x - (r.x + 0.5)) > settings.maxColumnOffsetPx || std::abs(q.y - (r.y + 0.5)) > settings.maxColumnOffsetPx) {
                ++c.offCentre;
                continue;
            }
            std::optional<SurfacePoint> seen = surfacePoint(scene, right, r);
            double distance = seen ? glm::length(seen->world - l->world) : HUGE_VAL;
            if (!seen || seen->tube != l->tube || distance > settings.depthToleranceMm) {
                ++c.hidden;
                continue;
            }
            ++c.matched;
            matches.push_back({{x, y}, r, l->tube, distance});
        }
    }
    if (counts) *counts = c;
    return matches;
}

ShadeDifference shadeDifference(const Image& left, const Image& right, const std::vector<StereoMatch>& matches) {
    ShadeDifference d;
    double sum = 0, sumSquares = 0, shade = 0;
    for (const StereoMatch& m : matches) {
        glm::vec4 a = left.at(m.left.x, m.left.y), b = right.at(m.right.x, m.right.y);
        double difference = std::max({std::abs(double(a.r) - b.r), std::abs(double(a.g) - b.g), std::abs(double(a.b) - b.b)});
        shade += std::max({double(a.r), double(a.g), double(a.b)});
        sum += difference;
        sumSquares += difference * difference;
        d.max = std::max(d.max, difference);
        ++d.points;
    }
    if (d.points) {
        d.mean = sum / d.points;
        d.meanShade = shade / d.points;
        d.rms = std::sqrt(sumSquares / d.points);
    }
    return d;
}

}  // namespace curette
