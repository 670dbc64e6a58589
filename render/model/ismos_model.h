#pragma once
// The ISMOS model's geometry (seed 003 sections 3.2, 3.5, 3.7), GL-free: the texture-space box of one frame,
// the light disks and their samples, the spotlight cone and the transmittance fit. The renderer's passes,
// the CPU twins in render/reference/ismos_reference.h and the tests all use these, so the GPU and its oracles
// agree on where a light and its samples are.
//
// Texture space (section 3.2): x = (pixel x + 0.5) / width, y = (pixel y + 0.5) / height (row 0 at the top),
// z = 1 - depth, depth the view depth normalised over the volume's bounding sphere (0 at its front, 1 at its
// back). A camera-space light direction is carried into the box by the box's size in millimetres, so a light
// lies where phong's light comes from.

#include "render/model/frame.h"

#include <glm/glm.hpp>

#include <vector>

namespace curette {

struct IsmosSpace {
    glm::dvec3 eye{0.0}, forward{0, 0, -1}, right{1, 0, 0}, up{0, 1, 0};
    double tanHalfX = 1, tanHalfY = 1;
    double nearMm = 0, farMm = 1;    // view depths of z = 1 and z = 0
    glm::dvec3 boxMm{1.0};           // the box's extent in mm at the volume centre's depth (x, y) and in depth

    glm::dvec3 toTexture(glm::dvec3 world) const;
    glm::dvec3 toWorld(glm::dvec3 tex) const;
    // z = 1 - depth of a view depth (mm along `forward`).
    double zOfViewDepth(double viewDepthMm) const { return 1.0 - (viewDepthMm - nearMm) / (farMm - nearMm); }
    // A light's unit direction (from the box towards it) in texture space.
    glm::dvec3 lightDirection(const Light& light) const;
};

IsmosSpace ismosSpace(const FrameDescription& frame, glm::dvec3 volumeCentre, double boundingRadiusMm);

// One light on the hemisphere (or sphere) of radius R: its centre L_c, unit normal facing the centre, disk
// radius d, the spotlight (cosine of omega, and the aim C in texture space; cosOmega < -1: no spot) and the
// tint eq. 15 multiplies by (the light's colour over a solid base; white over phong, which has it already).
struct IsmosLight {
    glm::dvec3 centre{0.0}, normal{0.0};
    double diskRadius = 0;
    double cosOmega = -2;
    glm::dvec3 spotTarget{0.5};
    glm::dvec3 tint{1.0};
    std::vector<glm::dvec3> samples;   // N points on the disk (section 3.2)
};

// N points spread evenly over the disk of `radius` around `centre` in the plane normal to `normal` (a Vogel
// spiral: equal area per point, deterministic; N = 1 is the centre).
std::vector<glm::dvec3> diskSamples(glm::dvec3 centre, glm::dvec3 normal, double radius, int n);

// The frame's lights (at most 4) in texture space, with `samplesPerLight` samples each.
std::vector<IsmosLight> ismosLights(const FrameDescription& frame, const IsmosSpace& space, glm::dvec3 volumeCentre,
                                    int samplesPerLight);

// Eq. 16: whether point p (texture space) lies inside the light's cone (always, for a light without a spot).
bool insideSpot(const IsmosLight& light, glm::dvec3 p);

// I_L (section 3.2): 1, or with falloff |L_c - box centre|^2 / |L_c - P|^2.
double lightIntensity(const IsmosLight& light, glm::dvec3 p, bool falloff);

// Parameter t_b where the path P + t (L - P) leaves the unit box (section 3.3.1), at most 1.
double pathExit(glm::dvec3 p, glm::dvec3 l);

// Eq. 8-10: the least-squares beta of T(z) ~ exp(-beta z^2) from the running sums sum z_i^2 ln(1/T_i) and
// sum z_i^4 (z here is the depth 1 - z_tex), and eq. 12's opacity per unit depth over a step dz.
struct TransmittanceFit {
    double sumZ2LogInvT = 0, sumZ4 = 0;
    void add(double depth, double transmittance);
    double beta() const { return sumZ4 > 0 ? sumZ2LogInvT / sumZ4 : 0.0; }
};
double fittedOpacity(double beta, double depth, double dz);   // alpha_app = beta (2 depth - dz), >= 0

}  // namespace curette

namespace curette {

// What pass 1 wrote, read back (tests, the bench, the CPU twin of pass 2). Unused layers have front -1;
// back < -1e29 marks a layer the ray terminated in; back and beta are empty when the variant has none.
struct IsmosLayerImages {
    glm::ivec2 size{0};
    std::vector<glm::vec4> front, alpha, back;
    std::vector<float> beta;
    std::size_t index(glm::ivec2 p) const { return static_cast<std::size_t>(p.y) * static_cast<std::size_t>(size.x) + static_cast<std::size_t>(p.x); }
};

}  // namespace curette
