#include "render/reference/raycast_reference.h"
#include "render/reference/camera_ray.h"

#include "render/model/frame.h"
#include "render/reference/random.h"
#include "render/reference/volume_sampler.h"
#include "render/model/volume_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace curette::reference {

namespace {

bool intersectBox(glm::dvec3 origin, glm::dvec3 direction, glm::dvec3 lo, glm::dvec3 hi, double& tNear, double& tFar) {
    tNear = -std::numeric_limits<double>::infinity();
    tFar = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
        if (direction[a] == 0.0) {
            if (origin[a] < lo[a] || origin[a] > hi[a]) return false;
            continue;
        }
        double t0 = (lo[a] - origin[a]) / direction[a], t1 = (hi[a] - origin[a]) / direction[a];
        tNear = std::max(tNear, std::min(t0, t1));
        tFar = std::min(tFar, std::max(t0, t1));
    }
    return tFar >= std::max(tNear, 0.0);
}

glm::dvec3 shadePhong(const TransferFunction::Material& m, const std::vector<std::pair<glm::dvec3, glm::dvec3>>& lights,
                      glm::dvec3 albedo, glm::dvec3 gradient, glm::dvec3 view, double ambient) {
    double magnitude = glm::length(gradient);
    glm::dvec3 color = m.ambient * ambient * albedo;
    if (magnitude < 1e-6) return color + m.diffuse * albedo;
    glm::dvec3 normal = -gradient / magnitude;
    if (glm::dot(normal, view) < 0) normal = -normal;
    for (const auto& [l, c] : lights) {
        double diffuse = std::max(glm::dot(normal, l), 0.0);
        glm::dvec3 halfway = glm::normalize(l + view);
        double specular = diffuse > 0 ? std::pow(std::max(glm::dot(normal, halfway), 0.0), m.specularPower) : 0.0;
        color += c * (m.diffuse * diffuse * albedo + m.specular * specular);
    }
    return color;
}

std::vector<std::pair<glm::dvec3, glm::dvec3>> frameLights(const FrameDescription& frame) {
    std::vector<std::pair<glm::dvec3, glm::dvec3>> lights;
    for (const Light& l : frame.lights) {
        if (lights.size() == 4) break;
        lights.emplace_back(worldLightDirection(l, frame.camera), l.color);
    }
    return lights;
}

bool readsAmbient(ShadingMode mode) { return mode == ShadingMode::Lao || mode == ShadingMode::Cao; }

}  // namespace

glm::dvec3 shadeTubeSurface(const VolumeData& volume, const FrameDescription& frame, const TubeSurface& surface, glm::dvec3 eye,
                            glm::dvec3 direction, double t, const RaycastOptions& options) {
    if (frame.shading == ShadingMode::Solid) return surface.color;
    const TransferFunction::Material& m = options.tubeShading.material;
    glm::dvec3 toViewer = -direction;
    glm::dvec3 diffuse(0.0), specular(0.0);
    glm::dvec3 n = glm::normalize(surface.normalOrTangent);
    if (!surface.line && glm::dot(n, toViewer) < 0) n = -n;
    for (const auto& [l, c] : frameLights(frame)) {
        double d = 0, s = 0;
        if (surface.line) {
            // Seed 004 eq. 3.12-3.15 (render/model/tube_geometry.h illuminatedLineColor), L and V pointing away.
            double lt = glm::dot(l, n), vt = glm::dot(toViewer, n);
            double ln = std::sqrt(std::max(1.0 - lt * lt, 0.0));
            double vr = ln * std::sqrt(std::max(1.0 - vt * vt, 0.0)) - lt * vt;
            d = std::pow(ln, options.tubeShading.lineDiffuseExponent);
            s = std::pow(std::max(vr, 0.0), m.specularPower);
        } else {
            d = std::max(glm::dot(n, l), 0.0);
            glm::dvec3 halfway = glm::normalize(l + toViewer);
            s = d > 0 ? std::pow(std::max(glm::dot(n, halfway), 0.0), m.specularPower) : 0.0;
        }
        diffuse += c * d;
        specular += c * s;
    }
    double occlusion = 1.0;
    if (readsAmbient(frame.shading)) {
        VolumeGeometry g{volume.dims, volume.indexToWorld};
        occlusion = options.ambient(glm::dvec3(g.worldToTexture() * glm::dvec4(eye + t * direction, 1.0)));
    }
    return occlusion * surface.color * (m.ambient + m.diffuse * diffuse) + m.specular * specular;
}

RaycastResult raycastPixel(const VolumeData& volume, const TransferFunction& tf, const FrameDescription& frame,
                           double stepMm, glm::ivec2 pixel, const RaycastOptions& options) {
    VolumeGeometry g{volume.dims, volume.indexToWorld};
    glm::dmat4 worldToTexture = g.worldToTexture();
    const auto [eye, direction] = cameraRay(frame, pixel);
    glm::dvec3 originTex = glm::dvec3(worldToTexture * glm::dvec4(eye, 1.0));
    glm::dvec3 directionTex = glm::dmat3(worldToTexture) * direction;

    std::vector<std::pair<glm::dvec3, glm::dvec3>> lights = frameLights(frame);
    VolumeSampler sampler(volume);
    bool useGradient = frame.shading == ShadingMode::Phong || tf.hasGradientOpacity();
    if (readsAmbient(frame.shading) && !options.ambient) throw std::invalid_argument("reference::raycastPixel: lao/cao need V_AO");
    // A tube surface ends the ray in front of it (tube_surface.glsl: samples with t below the surface's).
    double stopAt = options.opaqueAtMm, tubeT = -1.0;
    if (options.tube && options.tube->viewDepthMm > 0) {
        tubeT = options.tube->viewDepthMm / glm::dot(direction, frame.camera.forward());
        stopAt = std::min(stopAt, tubeT);
    }

    RaycastResult result;
    glm::dvec4& acc = result.rgba;
    // The opaque tube behind what the ray gathered in front of it, whether or not the ray met the volume's box.
    auto withTube = [&]() {
        if (tubeT > 0)
            acc = glm::dvec4(glm::dvec3(acc) + (1.0 - acc.a) * shadeTubeSurface(volume, frame, *options.tube, eye, direction, tubeT, options), 1.0);
        return result;
    };
    double tNear, tFar;
    if (!intersectBox(originTex, directionTex, glm::dvec3(0), glm::dvec3(1), tNear, tFar)) return withTube();
    double jitter = frame.raycast.jitterSeed ? pixelRandom(glm::uvec2(pixel), frame.raycast.jitterSeed) : 0.0;
    long k = static_cast<long>(std::ceil(std::max(tNear, 0.0) / stepMm - jitter));
    long kLast = static_cast<long>(std::floor(tFar / stepMm - jitter));
    // Cut faces (the rules of shaders/raycast.comp and shade_sample.glsl, render/model/frame.h CutFaceSettings): the
    // first visible lattice sample after clipped ones is taken at the crossing (here by bisection with the
    // exact inside test), standing for the ray to the end of its half step; phong lights the tissue behind the
    // face with the face normal until normalOpacity or half of normalDepthMm, then fades into the gradient normal.
    const CutFaceSettings& faces = frame.raycast.cutFace;
    bool cutFaces = faces.enabled && options.clipped && options.clipNormal;
    bool afterClipped = false;
    double faceT = -1.0, faceOpacityStart = 0.0;
    glm::dvec3 faceNormal(0.0);
    for (; k <= kLast; ++k) {
        double t = (static_cast<double>(k) + jitter) * stepMm;
        if (t >= stopAt) break;
        double segment = stepMm;
        if (options.clipped && options.clipped(eye + t * direction)) {
            afterClipped = true;
            continue;
        }
        if (cutFaces && afterClipped) {
            double inside = t - stepMm, outside = t;
            for (int i = 0; i < 48; ++i) {
                double middle = 0.5 * (inside + outside);
                (options.clipped(eye + middle * direction) ? inside : outside) = middle;
            }
            faceT = outside;
            faceOpacityStart = acc.a;
            faceNormal = -options.clipNormal(eye + faceT * direction);
            segment = t + 0.5 * stepMm - faceT;
            t = faceT;
        }
        afterClipped = false;
        glm::dvec3 tex = originTex + t * directionTex;
        double texel = sampler.texel(tex);
        double value = sampler.value(texel);
        glm::dvec3 gradient = useGradient ? sampler.gradientWorld(tex) : glm::dvec3(0);
        double alphaUnit = tf.evaluateOpacity(value) * tf.evaluateGradientOpacity(glm::length(gradient));
        double alpha = sampler.noData(texel) ? 0.0 : 1.0 - std::pow(std::max(1.0 - alphaUnit, 0.0), segment / tf.unitLengthMm);
        if (alpha <= 0) continue;
        glm::dvec3 albedo = tf.evaluateColor(value);
        if (cutFaces && faceT >= 0 && frame.shading == ShadingMode::Phong) {
            double depth = (t - faceT) * std::abs(glm::dot(direction, faceNormal));
            double behind = (acc.a - faceOpacityStart) / std::max(1.0 - faceOpacityStart, 1e-6);
            double faceWeight = (1.0 - glm::smoothstep(faces.normalOpacity, 1.0, behind)) *
                                (1.0 - glm::smoothstep(0.5 * faces.normalDepthMm, faces.normalDepthMm, depth));
            double magnitude = glm::length(gradient);
            glm::dvec3 volumeNormal = magnitude < 1e-6 ? faceNormal : -gradient / magnitude;
            if (glm::dot(volumeNormal, faceNormal) < 0) volumeNormal = -volumeNormal;
            if (faceWeight > 0) gradient = -glm::normalize(glm::mix(volumeNormal, faceNormal, faceWeight));
        }
        glm::dvec3 color = frame.shading == ShadingMode::Phong ? shadePhong(tf.material, lights, albedo, gradient, -direction, 1.0)
                           : readsAmbient(frame.shading)       ? albedo * options.ambientScale * options.ambient(tex)
                                                               : albedo;
        acc += glm::dvec4((1.0 - acc.a) * alpha * color, (1.0 - acc.a) * alpha);
        ++result.samples;
        if (acc.a >= 0.5 && result.halfOpacityDistanceMm < 0) result.halfOpacityDistanceMm = t;
        if (acc.a >= frame.raycast.earlyTerminationAlpha) break;
    }
    return withTube();
}

}  // namespace curette::reference
