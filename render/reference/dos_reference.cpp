#include "render/reference/dos_reference.h"

#include "render/reference/camera_ray.h"
#include "render/reference/random.h"

#include "render/model/slice_lattice.h"
#include "render/model/volume_geometry.h"

#include <cmath>
#include <numbers>

namespace curette::reference {

namespace {

// Directions uniform in solid angle over the cap of half-angle theta around +z: cos(polar) uniform in
// [cos theta, 1], azimuth by the golden angle (a spherical Fibonacci set restricted to the cap).
std::vector<glm::dvec3> coneDirections(int count, double theta) {
    std::vector<glm::dvec3> list;
    double c = std::cos(theta);
    double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < count; ++i) {
        double z = 1.0 - (1.0 - c) * (i + 0.5) / count;
        double r = std::sqrt(std::max(0.0, 1.0 - z * z));
        list.emplace_back(r * std::cos(golden * i), r * std::sin(golden * i), z);
    }
    return list;
}

}  // namespace

glm::dvec4 dosPixel(const VolumeData& volume, const TransferFunction& tf, const FrameDescription& frame,
                    double d, glm::ivec2 pixel, const DosReferenceSettings& settings, const InsideTest& inside) {
    VolumeGeometry g{volume.dims, volume.indexToWorld};
    glm::dmat4 worldToTexture = g.worldToTexture();
    const OrbitCamera& camera = frame.camera;
    glm::dvec3 forward = camera.forward();
    const auto [eye, direction] = cameraRay(frame, pixel);
    double cosine = glm::dot(direction, forward);

    VolumeSampler sampler(volume);
    auto insideBox = [&](glm::dvec3 tex) { return glm::all(glm::greaterThanEqual(tex, glm::dvec3(0))) && glm::all(glm::lessThanEqual(tex, glm::dvec3(1))); };
    // Opacity per unit length at a world point (0 outside the volume or inside a clip mesh), and colour.
    auto classify = [&](glm::dvec3 world, glm::dvec3* color) {
        glm::dvec3 tex = glm::dvec3(worldToTexture * glm::dvec4(world, 1.0));
        if (!insideBox(tex) || (inside && inside(world))) return 0.0;
        double texel = sampler.texel(tex);
        if (sampler.noData(texel)) return 0.0;
        double value = sampler.value(texel);
        if (color) *color = tf.evaluateColor(value);
        return tf.evaluateOpacity(value);
    };
    auto correct = [&](double alphaUnit, double length) {
        return 1.0 - std::pow(std::max(1.0 - alphaUnit, 0.0), length / tf.unitLengthMm);
    };

    // Cone directions around the direction towards the eye (-direction): an orthonormal frame on it.
    glm::dvec3 axis = -direction;
    glm::dvec3 helper = std::abs(axis.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
    glm::dvec3 u = glm::normalize(glm::cross(helper, axis)), w = glm::cross(axis, u);
    std::vector<glm::dvec3> cone;
    for (const glm::dvec3& c : coneDirections(settings.directions, glm::radians(frame.dos.coneAngleDeg)))
        cone.push_back(c.x * u + c.y * w + c.z * axis);
    double h = settings.marchStepMm > 0 ? settings.marchStepMm : d;
    double exitDistance = 2.0 * g.boundingRadiusMm() + 1.0;
    glm::dvec3 centre = g.worldCenter();
    double radius = g.boundingRadiusMm();

    // Eq. 10: V(x) = integral over the cone of T(x, boundary) with the normalised cone phase function, by the
    // average over the directions. T marches from the previous slice's distance outwards.
    auto visibility = [&](glm::dvec3 x) {
        double sum = 0;
        for (const glm::dvec3& omega : cone) {
            double transmittance = 1.0;
            // Every voxel lies inside the bounding sphere, which a straight line leaves only once.
            for (double s = h; s < exitDistance && transmittance > 1e-9; s += h) {
                glm::dvec3 p = x + s * omega;
                if (glm::length(p - centre) > radius) break;
                transmittance *= 1.0 - correct(classify(p, nullptr), h);
            }
            sum += transmittance;
        }
        return sum / static_cast<double>(cone.size());
    };

    // Eq. 7-8 along the primary ray at the slab pass's sample positions (depths z_k = (k + jitter) d).
    SliceLattice lattice = sliceLattice(g, camera, d);
    d = lattice.distanceMm;
    const long first = lattice.first, last = lattice.last;
    const double jitter = frame.raycast.jitterSeed != 0 ? pixelRandom(glm::uvec2(pixel), frame.raycast.jitterSeed) : 0.0;
    glm::dvec4 acc(0.0);
    for (long k = first; k <= last && acc.a < frame.raycast.earlyTerminationAlpha; ++k) {
        double t = (double(k) + jitter) * d / cosine;
        glm::dvec3 x = eye + t * direction;
        glm::dvec3 albedo(0);
        double alpha = correct(classify(x, &albedo), d / cosine);
        if (alpha <= 0) continue;
        double ambient = settings.occlusion ? visibility(x) : 1.0;
        acc += glm::dvec4((1.0 - acc.a) * alpha * frame.dos.ambientRadiance * albedo * ambient, (1.0 - acc.a) * alpha);
    }
    return acc;
}

}  // namespace curette::reference
