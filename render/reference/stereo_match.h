#pragma once
// Surface points a stereo pair shows in both eyes, and the shading difference between the eyes there: the
// measure of `curette bench stereo` (docs/subsystems.md, "Stereo"). CPU only.
//
// A pixel's surface point is where its ray's accumulated opacity first reaches 0.5 (the CPU reference ray
// march, render/reference/raycast_reference.h, with the scene's clip region cut away), or the tube surface
// the G-buffer holds when the ray reaches that first (a tube is opaque). A left-eye surface point is matched
// with the right-eye pixel whose centre it projects onto, within maxColumnOffsetPx (the rig is parallel, so
// the row is the same and only the column moves), when that pixel's own surface point lies within
// depthToleranceMm of it: the point is visible in the right eye too, not hidden behind something nearer.
// Both eyes' pixels are pixel centres, so the colours compared are the renderer's own, uninterpolated.

#include "base/transfer_function.h"
#include "base/volume.h"
#include "render/model/frame.h"
#include "render/model/image.h"

#include <glm/glm.hpp>

#include <functional>
#include <optional>
#include <vector>

namespace curette {

// The volume as the ray caster sees it.
struct SurfaceScene {
    const VolumeData& volume;
    const TransferFunction& transferFunction;
    std::function<bool(glm::dvec3 world)> clipped;   // the clip region (empty: none)
    double stepMm;                                    // the resolved ray step (Renderer::resolveStepMm)
};

// What the matcher needs of one rendered eye.
struct EyeView {
    FrameDescription frame;
    std::vector<float> tubeViewDepth;   // per pixel (row 0 at the top) the G-buffer's view depth; <= 0 or empty: no tube
};

struct SurfacePoint {
    glm::dvec3 world{0.0};
    bool tube = false;
};

std::optional<SurfacePoint> surfacePoint(const SurfaceScene& scene, const EyeView& eye, glm::ivec2 pixel);

// Continuous pixel coordinates of a world point in a frame: pixel (i, j)'s centre is (i + 0.5, j + 0.5), row 0
// at the top (the inverse of the pixel ray, render/reference/camera_ray.h).
glm::dvec2 projectToPixel(const FrameDescription& frame, glm::dvec3 world);

struct MatchSettings {
    int stride = 2;                    // left-eye pixels tried: every stride-th column and row
    double maxColumnOffsetPx = 0.1;    // how far from a right-eye pixel centre the point may project
    double depthToleranceMm = 1.0;     // how far apart the two eyes' surface points may be
};

struct StereoMatch {
    glm::ivec2 left{0}, right{0};
    bool tube = false;
    double distanceMm = 0.0;   // between the two eyes' surface points
};

struct MatchCounts {
    int tried = 0, surfaces = 0, outside = 0, offCentre = 0, hidden = 0, matched = 0;
};

std::vector<StereoMatch> matchSurfacePoints(const SurfaceScene& scene, const EyeView& left, const EyeView& right,
                                            const MatchSettings& settings, MatchCounts* counts = nullptr);

// Per matched point the largest RGB difference |left - right| of the premultiplied colours (display values
// in [0, 1]); over the points its RMS, maximum and mean, and the mean shade (the left pixel's largest
// channel), so modes that darken everything (occlusion) can be compared relative to how bright they are.
struct ShadeDifference {
    int points = 0;
    double rms = 0.0, max = 0.0, mean = 0.0;
    double meanShade = 0.0;
    double relativeRms() const { return meanShade > 0 ? rms / meanShade : 0.0; }
};
ShadeDifference shadeDifference(const Image& left, const Image& right, const std::vector<StereoMatch>& matches);

}  // namespace curette
