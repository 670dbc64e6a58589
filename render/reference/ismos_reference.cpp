#include "render/reference/ismos_reference.h"
#include "render/reference/camera_ray.h"

#include "render/reference/random.h"
#include "render/reference/volume_sampler.h"
#include "render/model/volume_geometry.h"

#include <algorithm>
#include <cmath>

namespace curette::reference {

namespace {

constexpr float kNoLayer = -1.0f;
constexpr float kSolid = -1.0e29f;

struct Twin {
    const IsmosLayerImages& layers;
    const IsmosSettings& s;
    glm::dvec3 texToDepth;
    double stepDepth;
    int layerCount;

    bool fullyOccluded(glm::ivec2 q, double z) const {
        const glm::vec4& f = layers.front[layers.index(q)];
        const glm::vec4& a = layers.alpha[layers.index(q)];
        for (int k = 0; k < layerCount; ++k) {
            if (f[k] == kNoLayer) break;
            if (a[k] >= s.opacityThreshold) return f[k] > z + s.depthBias;
        }
        return false;
    }

    double segmentOpacity(glm::ivec2 q, double z, double dz) const {
        const glm::vec4& f = layers.front[layers.index(q)];
        if (!s.fit) {
            const glm::vec4& a = layers.alpha[layers.index(q)];
            const glm::vec4& b = layers.back[layers.index(q)];
            double tau = 0;
            for (int k = 0; k < layerCount; ++k) {
                if (f[k] == kNoLayer) break;
                if (z >= f[k] + 0.5 * stepDepth - s.depthBias) continue;
                if (b[k] < kSolid) return 1.0;
                if (z < b[k] - 0.5 * stepDepth) continue;
                tau += -std::log(std::max(1.0 - a[k], 1e-6)) / (f[k] - b[k] + stepDepth) * dz;
            }
            return 1.0 - std::exp(-tau);
        }
        if (f.x == kNoLayer || z >= f.x - s.depthBias) return 0.0;
        double alphaApp = fittedOpacity(layers.beta[layers.index(q)], 1.0 - z, dz);
        return 1.0 - std::exp(-alphaApp * dz);
    }

    double pathOcclusion(glm::dvec3 p, glm::dvec3 l) const {
        glm::dvec3 d = l - p;
        int nr = std::clamp(s.testPoints, 1, 4096);
        double dt = pathExit(p, l) / nr;
        double dz = glm::length(d * dt * texToDepth);
        double occ = 0;
        for (int i = 1; i <= nr; ++i) {
            glm::dvec3 r = p + (i * dt) * d;
            glm::ivec2 q(static_cast<int>(std::floor(r.x * layers.size.x)), static_cast<int>(std::floor(r.y * layers.size.y)));
            if (q.x < 0 || q.y < 0 || q.x >= layers.size.x || q.y >= layers.size.y) break;
            if (s.partial) {
                occ += (1.0 - occ) * segmentOpacity(q, r.z, dz);
                if (occ >= 1.0) break;
            } else if (fullyOccluded(q, r.z)) {
                return 1.0;
            }
        }
        return occ;
    }
};

}  // namespace

IsmosPixel ismosOcclusionPixel(const IsmosLayerImages& layers, const std::vector<IsmosLight>& lights, const IsmosSettings& s,
                               const IsmosSpace& space, double stepDepth, glm::ivec2 pixel) {
    IsmosPixel out;
    const glm::vec4& f = layers.front[layers.index(pixel)];
    const glm::vec4& a = layers.alpha[layers.index(pixel)];
    if (f.x == kNoLayer || lights.empty()) return out;
    Twin twin{layers, s, space.boxMm / space.boxMm.z, stepDepth, std::clamp(s.layers, 1, 4)};
    glm::dvec2 xy = (glm::dvec2(pixel) + 0.5) / glm::dvec2(layers.size);
    double occSum = 0, weightSum = 0, before = 1;
    glm::dvec3 lightSum(0);
    for (int k = 0; k < twin.layerCount; ++k) {
        if (f[k] == kNoLayer) break;
        double w = 1;
        if (twin.layerCount > 1) {
            if (s.blendLayers) {
                w = a[k] * before;
                before *= 1.0 - a[k];
            } else if (a[k] < s.opacityThreshold) {
                continue;
            }
        }
        glm::dvec3 p(xy, f[k]);
        double occluded = 0;
        glm::dvec3 light(0);
        std::size_t n = 0;
        for (const IsmosLight& l : lights) {
            light += l.tint * lightIntensity(l, p, s.falloff);
            n += l.samples.size();
            if (!insideSpot(l, p)) {
                occluded += static_cast<double>(l.samples.size());
                continue;
            }
            for (glm::dvec3 sample : l.samples) occluded += twin.pathOcclusion(p, sample);
        }
        light /= static_cast<double>(lights.size());
        occSum += w * occluded / static_cast<double>(std::max<std::size_t>(n, 1));
        lightSum += w * light;
        weightSum += w;
        if (twin.layerCount == 1 || !s.blendLayers) break;
    }
    if (weightSum <= 0) return out;
    out.shaded = true;
    out.occlusion = occSum / weightSum;
    out.light = lightSum / weightSum;
    out.factor = out.light * std::max(1.0 - out.occlusion, s.ambient);
    return out;
}

IsmosLayersPixel ismosLayersPixel(const VolumeData& volume, const TransferFunction& tf, const FrameDescription& frame, double stepMm,
                                  const IsmosSpace& space, glm::ivec2 pixel, const OccluderTriangles* tubes, double tubeThicknessMm) {
    VolumeGeometry g{volume.dims, volume.indexToWorld};
    glm::dmat4 worldToTexture = g.worldToTexture();
    const auto [eye, direction] = cameraRay(frame, pixel);
    glm::dvec3 originTex = glm::dvec3(worldToTexture * glm::dvec4(eye, 1.0));
    glm::dvec3 directionTex = glm::dmat3(worldToTexture) * direction;
    VolumeSampler sampler(volume);
    int maxLayers = std::clamp(frame.ismos.layers, 1, 4);
    double range = space.farMm - space.nearMm, cosine = glm::dot(direction, space.forward);

    IsmosLayersPixel out;
    glm::dvec4 transmittance(1.0);
    int count = 0;
    bool open = false;
    TransmittanceFit fit;
    double accumulated = 0;
    // ismos_layers.glsl's ismosSample and ismosTerminated.
    auto addSample = [&](double depth, double alpha, double transmittanceAfter) {
        if (!open) {
            open = true;
            if (count < maxLayers) out.front[count++] = 1.0 - depth;
            else count = maxLayers + 1;
        }
        if (count <= maxLayers) {
            transmittance[count - 1] *= 1.0 - alpha;
            out.back[count - 1] = 1.0 - depth;
        }
        fit.add(depth, transmittanceAfter);
    };
    auto terminated = [&] {
        if (open && count <= maxLayers) out.back[count - 1] = -1e30;
    };
    // The first tube surface on the ray (mm along it), where the ray cast stops (raycast.comp, ISMOS_TUBES).
    double tubeT = -1;
    if (tubes && !tubes->empty()) {
        constexpr double reach = 1e6;
        double hit = tubes->firstHit(eye, eye + reach * direction);
        if (hit > 0) tubeT = hit * reach;
    }

    double tNear = -1e300, tFar = 1e300;
    bool inBox = true;
    for (int a = 0; a < 3; ++a) {
        if (directionTex[a] == 0.0) {
            if (originTex[a] < 0 || originTex[a] > 1) inBox = false;
            continue;
        }
        double t0 = (0 - originTex[a]) / directionTex[a], t1 = (1 - originTex[a]) / directionTex[a];
        tNear = std::max(tNear, std::min(t0, t1));
        tFar = std::min(tFar, std::max(t0, t1));
    }
    if (inBox && tFar >= std::max(tNear, 0.0)) {
        double jitter = frame.raycast.jitterSeed ? pixelRandom(glm::uvec2(pixel), frame.raycast.jitterSeed) : 0.0;
        long k = static_cast<long>(std::ceil(std::max(tNear, 0.0) / stepMm - jitter));
        long kLast = static_cast<long>(std::floor(tFar / stepMm - jitter));
        if (tubeT > 0) kLast = std::min(kLast, static_cast<long>(std::ceil(tubeT / stepMm - jitter)) - 1);
        for (; k <= kLast; ++k) {
            double t = (static_cast<double>(k) + jitter) * stepMm;
            glm::dvec3 tex = originTex + t * directionTex;
            double texel = sampler.texel(tex);
            double alphaUnit = tf.evaluateOpacity(sampler.value(texel));
            if (tf.hasGradientOpacity()) alphaUnit *= tf.evaluateGradientOpacity(glm::length(sampler.gradientWorld(tex)));
            double alpha = sampler.noData(texel) ? 0.0 : 1.0 - std::pow(std::max(1.0 - alphaUnit, 0.0), stepMm / tf.unitLengthMm);
            if (alpha <= 0) {
                open = false;
                continue;
            }
            accumulated += (1.0 - accumulated) * alpha;
            addSample((t * cosine - space.nearMm) / range, alpha, 1.0 - accumulated);
            if (accumulated >= frame.raycast.earlyTerminationAlpha) {
                terminated();
                break;
            }
        }
    }
    // The tube is an opaque layer at its depth, as thick as the tube.
    if (tubeT > 0 && accumulated < frame.raycast.earlyTerminationAlpha) {
        open = false;
        double depth = (tubeT * cosine - space.nearMm) / range;
        addSample(depth, 1.0, 1.0 - frame.raycast.earlyTerminationAlpha);
        // The chord through the tube along the ray, in view depth, at most the tube's diameter (the GPU takes
        // the diameter times |n . forward| from the G-buffer's normal: the same for a round tube).
        constexpr double reach = 1e6;
        double past = tubes->firstHit(eye + (tubeT + 1e-6) * direction, eye + reach * direction);
        double chord = past > 0 ? std::min(past * reach * cosine, tubeThicknessMm) : tubeThicknessMm;
        if (count <= maxLayers) out.back[count - 1] = 1.0 - (depth + chord / range);
    }
    out.alpha = glm::dvec4(1.0) - transmittance;
    out.beta = fit.beta();
    return out;
}

OccluderTriangles::OccluderTriangles(const TubeVertices& tubes) {
    if (tubes.lines) return;
    for (std::size_t i = 0; i + 2 < tubes.indices.size(); i += 3) {
        glm::dvec3 a(tubes.positions[tubes.indices[i]]), b(tubes.positions[tubes.indices[i + 1]]), c(tubes.positions[tubes.indices[i + 2]]);
        if (glm::length(glm::cross(b - a, c - a)) <= 0) continue;   // degenerate: no area
        triangles_.push_back({a, b - a, c - a});
    }
    if (triangles_.empty()) return;
    std::vector<glm::dvec3> centroids;
    for (const Triangle& t : triangles_) centroids.push_back(t.p0 + (t.e1 + t.e2) / 3.0);
    nodes_.reserve(2 * triangles_.size() / 4 + 2);
    build(0, static_cast<std::uint32_t>(triangles_.size()), centroids);
}

std::uint32_t OccluderTriangles::build(std::uint32_t first, std::uint32_t count, std::vector<glm::dvec3>& centroids) {
    std::uint32_t index = static_cast<std::uint32_t>(nodes_.size());
    nodes_.push_back({});
    Node node;
    node.lo = glm::dvec3(1e300), node.hi = glm::dvec3(-1e300);
    glm::dvec3 cLo(1e300), cHi(-1e300);
    for (std::uint32_t i = first; i < first + count; ++i) {
        const Triangle& t = triangles_[i];
        for (glm::dvec3 v : {t.p0, t.p0 + t.e1, t.p0 + t.e2}) node.lo = glm::min(node.lo, v), node.hi = glm::max(node.hi, v);
        cLo = glm::min(cLo, centroids[i]), cHi = glm::max(cHi, centroids[i]);
    }
    if (count <= 4) {
        node.first = first, node.count = count;
    } else {
        glm::dvec3 extent = cHi - cLo;
        int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
        std::uint32_t half = count / 2;
        std::vector<std::uint32_t> order(count);
        for (std::uint32_t i = 0; i < count; ++i) order[i] = first + i;
        std::nth_element(order.begin(), order.begin() + half, order.end(),
                         [&](std::uint32_t a, std::uint32_t b) { return centroids[a][axis] < centroids[b][axis]; });
        std::vector<Triangle> triangles;
        std::vector<glm::dvec3> cs;
        for (std::uint32_t i : order) triangles.push_back(triangles_[i]), cs.push_back(centroids[i]);
        std::copy(triangles.begin(), triangles.end(), triangles_.begin() + first);
        std::copy(cs.begin(), cs.end(), centroids.begin() + first);
        node.left = build(first, half, centroids);
        node.right = build(first + half, count - half, centroids);
    }
    nodes_[index] = node;
    return index;
}

double OccluderTriangles::firstHit(glm::dvec3 a, glm::dvec3 b, double tMin, double tMax) const {
    if (nodes_.empty()) return -1.0;
    glm::dvec3 d = b - a;
    glm::dvec3 inv(d.x != 0 ? 1.0 / d.x : 1e300, d.y != 0 ? 1.0 / d.y : 1e300, d.z != 0 ? 1.0 / d.z : 1e300);
    double best = -1.0;
    std::vector<std::uint32_t> stack{0};
    while (!stack.empty()) {
        const Node& n = nodes_[stack.back()];
        stack.pop_back();
        double t0 = tMin, t1 = best >= 0 ? best : tMax;
        bool miss = false;
        for (int k = 0; k < 3 && !miss; ++k) {
            if (d[k] == 0) {
                miss = a[k] < n.lo[k] || a[k] > n.hi[k];
                continue;
            }
            double ta = (n.lo[k] - a[k]) * inv[k], tb = (n.hi[k] - a[k]) * inv[k];
            t0 = std::max(t0, std::min(ta, tb));
            t1 = std::min(t1, std::max(ta, tb));
            miss = t0 > t1;
        }
        if (miss) continue;
        if (n.count == 0) {
            stack.push_back(n.left);
            stack.push_back(n.right);
            continue;
        }
        for (std::uint32_t i = n.first; i < n.first + n.count; ++i) {
            // Moller-Trumbore.
            const Triangle& t = triangles_[i];
            glm::dvec3 p = glm::cross(d, t.e2);
            double det = glm::dot(t.e1, p);
            if (std::abs(det) < 1e-300) continue;
            glm::dvec3 s = a - t.p0;
            double u = glm::dot(s, p) / det;
            if (u < 0 || u > 1) continue;
            glm::dvec3 q = glm::cross(s, t.e1);
            double v = glm::dot(d, q) / det;
            if (v < 0 || u + v > 1) continue;
            double hit = glm::dot(t.e2, q) / det;
            if (hit > tMin && hit <= tMax && (best < 0 || hit < best)) best = hit;
        }
    }
    return best;
}

glm::dvec3 lightPointWorld(const IsmosSpace& space, glm::dvec3 volumeCentre, glm::dvec3 tex) {
    glm::dvec3 d = tex - space.toTexture(volumeCentre);
    return volumeCentre + d.x * space.boxMm.x * space.right - d.y * space.boxMm.y * space.up - d.z * space.boxMm.z * space.forward;
}

double physicalOcclusion(const VolumeData& volume, const TransferFunction& tf, const IsmosSpace& space, glm::dvec3 volumeCentre,
                         const std::vector<IsmosLight>& lights, const std::vector<std::vector<glm::dvec3>>& points, glm::dvec3 pTex,
                         const PhysicalSettings& ps) {
    VolumeGeometry g{volume.dims, volume.indexToWorld};
    glm::dmat4 worldToTexture = g.worldToTexture();
    VolumeSampler sampler(volume);
    bool gradientOpacity = tf.hasGradientOpacity();
    glm::dvec3 p = space.toWorld(pTex);
    // Transmittance along the world segment from p towards q, over the volume's extent.
    auto transmittance = [&](glm::dvec3 q) {
        glm::dvec3 dir = glm::normalize(q - p);
        double reach = 2.0 * g.boundingRadiusMm() + glm::length(p - volumeCentre);
        if (ps.tubes && glm::length(q - p) > ps.startOffsetMm && ps.tubes->blocks(p + ps.startOffsetMm * dir, q)) return 0.0;
        double T = 1.0;
        for (double t = ps.startOffsetMm; t < reach && T > 1e-6; t += ps.stepMm) {
            glm::dvec3 w = p + t * dir;
            glm::dvec3 tex(worldToTexture * glm::dvec4(w, 1.0));
            if (tex.x < 0 || tex.y < 0 || tex.z < 0 || tex.x > 1 || tex.y > 1 || tex.z > 1) continue;
            if (ps.insideClip && ps.insideClip(w)) continue;
            double texel = sampler.texel(tex);
            if (sampler.noData(texel)) continue;
            double alphaUnit = tf.evaluateOpacity(sampler.value(texel));
            if (gradientOpacity) alphaUnit *= tf.evaluateGradientOpacity(glm::length(sampler.gradientWorld(tex)));
            double alpha = 1.0 - std::pow(std::max(1.0 - alphaUnit, 0.0), ps.stepMm / tf.unitLengthMm);
            T *= 1.0 - alpha;
        }
        return T;
    };
    double occluded = 0;
    std::size_t n = 0;
    for (std::size_t j = 0; j < lights.size(); ++j) {
        n += points[j].size();
        if (!insideSpot(lights[j], pTex)) {
            occluded += static_cast<double>(points[j].size());
            continue;
        }
        for (glm::dvec3 l : points[j]) occluded += 1.0 - transmittance(lightPointWorld(space, volumeCentre, l));
    }
    return n ? occluded / static_cast<double>(n) : 0.0;
}

}  // namespace curette::reference
