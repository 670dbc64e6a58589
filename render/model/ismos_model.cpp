#include "render/model/ismos_model.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace curette {

glm::dvec3 IsmosSpace::toTexture(glm::dvec3 world) const {
    glm::dvec3 c = world - eye;
    double w = glm::dot(c, forward);
    double x = glm::dot(c, right) / (w * tanHalfX), y = glm::dot(c, up) / (w * tanHalfY);
    return {0.5 + 0.5 * x, 0.5 - 0.5 * y, zOfViewDepth(w)};
}

glm::dvec3 IsmosSpace::toWorld(glm::dvec3 tex) const {
    double w = nearMm + (1.0 - tex.z) * (farMm - nearMm);
    double x = 2.0 * tex.x - 1.0, y = 1.0 - 2.0 * tex.y;
    return eye + w * (forward + x * tanHalfX * right + y * tanHalfY * up);
}

glm::dvec3 IsmosSpace::lightDirection(const Light& light) const {
    glm::dvec3 cam = glm::normalize(light.direction);
    if (!light.cameraSpace) cam = glm::dvec3(glm::dot(cam, right), glm::dot(cam, up), -glm::dot(cam, forward));
    // Camera (right, up, towards the viewer) -> texture (x right, y down, z towards the viewer), each axis
    // divided by the box's extent in mm so a direction in the box is the same direction in the world.
    return glm::normalize(glm::dvec3(cam.x / boxMm.x, -cam.y / boxMm.y, cam.z / boxMm.z));
}

IsmosSpace ismosSpace(const FrameDescription& frame, glm::dvec3 volumeCentre, double boundingRadiusMm) {
    IsmosSpace s;
    s.eye = frame.camera.position();
    s.forward = frame.camera.forward();
    s.right = frame.camera.right();
    s.up = frame.camera.up();
    double aspect = double(frame.size.x) / frame.size.y;
    s.tanHalfY = std::tan(glm::radians(frame.camera.fovYDeg) / 2.0);
    s.tanHalfX = aspect * s.tanHalfY;
    double centreDepth = glm::dot(volumeCentre - s.eye, s.forward);
    s.nearMm = centreDepth - boundingRadiusMm;
    s.farMm = centreDepth + boundingRadiusMm;
    s.boxMm = glm::dvec3(2.0 * centreDepth * s.tanHalfX, 2.0 * centreDepth * s.tanHalfY, 2.0 * boundingRadiusMm);
    return s;
}

std::vector<glm::dvec3> diskSamples(glm::dvec3 centre, glm::dvec3 normal, double radius, int n) {
    glm::dvec3 helper = std::abs(normal.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    glm::dvec3 a = glm::normalize(glm::cross(normal, helper)), b = glm::cross(normal, a);
    std::vector<glm::dvec3> out;
    const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < n; ++i) {
        double r = n == 1 ? 0.0 : radius * std::sqrt((i + 0.5) / n);
        double angle = i * golden;
        out.push_back(centre + r * (std::cos(angle) * a + std::sin(angle) * b));
    }
    return out;
}

std::vector<IsmosLight> ismosLights(const FrameDescription& frame, const IsmosSpace& space, glm::dvec3 volumeCentre,
                                    int samplesPerLight) {
    const IsmosSettings& s = frame.ismos;
    glm::dvec3 origin = s.sphere ? glm::dvec3(0.5, 0.5, 0.5) : glm::dvec3(0.5, 0.5, 0.0);
    std::vector<IsmosLight> lights;
    for (const Light& l : frame.lights) {
        if (lights.size() == 4) break;
        IsmosLightShape shape = lights.size() < s.lightShapes.size() ? s.lightShapes[lights.size()] : IsmosLightShape{};
        IsmosLight out;
        glm::dvec3 direction = space.lightDirection(l);
        out.centre = origin + s.hemisphereRadius * direction;
        out.normal = -direction;   // the disk faces the centre of the (hemi)sphere
        out.diskRadius = shape.diskRadius >= 0 ? shape.diskRadius : s.diskRadius;
        if (shape.spotAngleDeg > 0) {
            out.cosOmega = std::cos(glm::radians(shape.spotAngleDeg));
            out.spotTarget = space.toTexture(shape.spotTarget.value_or(volumeCentre));
        }
        out.tint = s.base == ShadingMode::Solid ? l.color : glm::dvec3(1.0);
        out.samples = diskSamples(out.centre, out.normal, out.diskRadius, samplesPerLight);
        lights.push_back(std::move(out));
    }
    return lights;
}

bool insideSpot(const IsmosLight& light, glm::dvec3 p) {
    if (light.cosOmega < -1.0) return true;
    glm::dvec3 a = p - light.centre, b = light.spotTarget - light.centre;
    double la = glm::length(a), lb = glm::length(b);
    if (la <= 0 || lb <= 0) return true;
    return glm::dot(a, b) / (la * lb) >= light.cosOmega;   // gamma <= omega
}

double lightIntensity(const IsmosLight& light, glm::dvec3 p, bool falloff) {
    if (!falloff) return 1.0;
    glm::dvec3 toCentre = light.centre - glm::dvec3(0.5), toP = light.centre - p;
    return glm::dot(toCentre, toCentre) / std::max(glm::dot(toP, toP), 1e-12);
}

double pathExit(glm::dvec3 p, glm::dvec3 l) {
    glm::dvec3 d = l - p;
    double t = 1.0;
    for (int a = 0; a < 3; ++a) {
        if (d[a] > 0) t = std::min(t, (1.0 - p[a]) / d[a]);
        else if (d[a] < 0) t = std::min(t, (0.0 - p[a]) / d[a]);
    }
    return std::max(t, 0.0);
}

void TransmittanceFit::add(double depth, double transmittance) {
    double z2 = depth * depth;
    sumZ2LogInvT += z2 * std::log(1.0 / std::max(transmittance, 1e-30));
    sumZ4 += z2 * z2;
}

double fittedOpacity(double beta, double depth, double dz) { return std::max(beta * (2.0 * depth - dz), 0.0); }

}  // namespace curette
