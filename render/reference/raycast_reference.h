#pragma once
// CPU double-precision twin of shaders/raycast.comp for single pixels: the same rays, the same sample
// lattice, trilinear sampling, the exact (unbaked) transfer function, opacity correction, Blinn-Phong and
// early termination; V_AO in lao/cao; a tube surface ending the ray. Tests compare the GPU image against it pixel
// by pixel.

#include "render/model/frame.h"
#include "render/model/tube_vertices.h"
#include "base/transfer_function.h"
#include "base/volume.h"

#include <glm/glm.hpp>

#include <functional>
#include <limits>
#include <optional>

namespace curette::reference {

struct RaycastResult {
    glm::dvec4 rgba{0.0};   // premultiplied
    int samples = 0;        // samples with non-zero opacity composited
    // Distance from the eye (mm, along the ray) of the first sample after which the accumulated opacity is at
    // least 0.5: where the pixel's surface is (render/reference/stereo_match.h); negative when it never gets there.
    double halfOpacityDistanceMm = -1.0;
};

// The tube surface a pixel shows (the G-buffer's: its view depth along the camera's forward axis, its colour,
// and its normal, or its tangent for an illuminated line).
struct TubeSurface {
    double viewDepthMm = 0.0;
    glm::dvec3 color{0.0}, normalOrTangent{0.0};
    bool line = false;
};

// What the plain ray cast leaves out, for callers that need the pixel as the GPU shows it in a scene.
struct RaycastOptions {
    std::function<bool(glm::dvec3 world)> clipped;                     // samples it accepts are cut away; empty: none
    double opaqueAtMm = std::numeric_limits<double>::infinity();        // an opaque surface (a tube) ends the ray here
    // With `clipped` and frame.raycast.cutFace on: the unit normal of the clip surface at a world point on it,
    // pointing out of the clipped region (the cut-face rules need it).
    std::function<glm::dvec3(glm::dvec3 world)> clipNormal;
    // lao/cao: V_AO at a texture point (trilinear, clamp to edge) and its scale (LaoSettings::ambientScale).
    std::function<double(glm::dvec3 tex)> ambient;
    double ambientScale = 2.0;
    // Tubes in the ray cast (shaders/tube_surface.glsl): the ray ends in front of the surface (as at opaqueAtMm),
    // which is shaded in the frame's mode with `tubeShading`'s material and laid behind the volume.
    std::optional<TubeSurface> tube;
    TubeShading tubeShading;
};

// The colour of a tube surface at ray parameter t along `direction` from the eye: the rule of
// shaders/tube_surface.glsl (solid: its colour; phong: Blinn-Phong or illuminated-line terms; lao/cao: the same
// times V_AO at the surface point).
glm::dvec3 shadeTubeSurface(const VolumeData& volume, const FrameDescription& frame, const TubeSurface& surface, glm::dvec3 eye,
                            glm::dvec3 direction, double t, const RaycastOptions& options);

// `stepMm` must be the resolved step (Renderer::resolveStepMm).
RaycastResult raycastPixel(const VolumeData& volume, const TransferFunction& tf, const FrameDescription& frame,
                           double stepMm, glm::ivec2 pixel, const RaycastOptions& options = {});

}  // namespace curette::reference
