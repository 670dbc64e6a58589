#version 450
// ISMOS pass 2 (seed 003 sections 3.3-3.7): image-space occlusion of the ray caster's layers, one invocation
// per pixel, in place on the output image. From each shaded layer point P = (x, y, z_front) a path runs to
// each of the N samples of each light disk; N_R test points along it, up to where it leaves the box
// (section 3.3.1), look at the layers of the pixel each falls into:
//  - full occlusion (eq. 1-2): the path is blocked when the first opaque layer there lies in front;
//  - partial occlusion (eq. 4-5): opacity accumulates, Occ_i <- (1 - Occ_i) alpha_t + Occ_i, from the exact
//    layers (ISMOS_EXACT: each layer homogeneous between its front and back) or the fit (ISMOS_FIT: eq. 12's
//    alpha_app behind the first layer).
// Lights pool their samples (eq. 13-14); outside a spotlight's cone all of its samples count as occluded
// (eq. 16). C = C_p I_L max(1 - Occ, I_amb) (eq. 3, 15). With several layers the occlusion of each is blended
// front to back by the layers' opacities (ISMOS_BLEND, Fig. 7d) or taken at the first opaque one (Fig. 7c).
// CPU twin: reference::ismosOcclusionPixel (render/reference/ismos_reference.h). Binder: IsmosPass.
#include "bindings.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = IMAGE_OUTPUT) uniform image2D outputImage;
layout(binding = BINDING_ISMOS_LAYER_FRONT) uniform sampler2D layerFront;
layout(binding = BINDING_ISMOS_LAYER_ALPHA) uniform sampler2D layerAlpha;
#if ISMOS_EXACT
layout(binding = BINDING_ISMOS_LAYER_BACK) uniform sampler2D layerBack;
#endif
#if ISMOS_FIT
layout(binding = BINDING_ISMOS_FIT) uniform sampler2D fitBeta;
#endif
layout(std430, binding = SSBO_ISMOS_LIGHT_SAMPLES) readonly buffer LightSamples { vec4 lightSample[]; };

#define MAX_ISMOS_LIGHTS 4
#define NO_LAYER -1.0
#define SOLID -1.0e29

uniform ivec2 outputSize;
uniform int lightCount;
uniform int samplesPerLight;               // N
uniform int testPoints;                    // N_R
uniform vec3 lightCentre[MAX_ISMOS_LIGHTS];
uniform vec4 lightSpot[MAX_ISMOS_LIGHTS];  // aim (texture space), cos omega (< -1: no spot)
uniform vec3 lightTint[MAX_ISMOS_LIGHTS];
uniform bool falloff;
uniform float ambientFloor;                // I_amb
uniform float opacityThreshold;            // alpha_th
uniform float depthBias;
uniform vec3 texToDepth;                   // texture units -> depth units per axis (the box's mm / its depth mm)
uniform float layerStepDepth;              // one ray-casting step in depth units (a layer's least thickness)

float pathExit(vec3 p, vec3 l) {
    vec3 d = l - p;
    float t = 1.0;
    for (int a = 0; a < 3; ++a) {
        if (d[a] > 0.0) t = min(t, (1.0 - p[a]) / d[a]);
        else if (d[a] < 0.0) t = min(t, (0.0 - p[a]) / d[a]);
    }
    return max(t, 0.0);
}

#if !ISMOS_PARTIAL
// Eq. 1-2: a test point at depth z in pixel q is occluded when the first opaque layer there is in front.
bool fullyOccluded(ivec2 q, float z) {
    vec4 f = texelFetch(layerFront, q, 0), a = texelFetch(layerAlpha, q, 0);
    for (int k = 0; k < ISMOS_LAYERS; ++k) {
        if (f[k] == NO_LAYER) break;
        if (a[k] >= opacityThreshold) return f[k] > z + depthBias;
    }
    return false;
}
#else
// alpha_t of a path segment of length dz (depth units) at depth z in pixel q.
float segmentOpacity(ivec2 q, float z, float dz) {
    vec4 f = texelFetch(layerFront, q, 0);
#if ISMOS_EXACT
    vec4 a = texelFetch(layerAlpha, q, 0), b = texelFetch(layerBack, q, 0);
    float tau = 0.0;
    for (int k = 0; k < ISMOS_LAYERS; ++k) {
        if (f[k] == NO_LAYER) break;
        float top = f[k] + 0.5 * layerStepDepth - depthBias;
        if (z >= top) continue;
        if (b[k] < SOLID) return 1.0;   // the ray terminated in this layer: opaque to the back
        float bottom = b[k] - 0.5 * layerStepDepth;
        if (z < bottom) continue;
        tau += -log(max(1.0 - a[k], 1e-6)) / (f[k] - b[k] + layerStepDepth) * dz;
    }
    return 1.0 - exp(-tau);
#else
    if (f.x == NO_LAYER || z >= f.x - depthBias) return 0.0;
    float beta = texelFetch(fitBeta, q, 0).r;
    float alphaApp = max(beta * (2.0 * (1.0 - z) - dz), 0.0);   // eq. 12 per unit depth
    return 1.0 - exp(-alphaApp * dz);
#endif
}
#endif

// The occlusion (0..1) of the path from P to the light sample L (eq. 1 and eq. 4).
float pathOcclusion(vec3 P, vec3 L) {
    vec3 d = L - P;
    float dt = pathExit(P, L) / float(testPoints);
    float dz = length(d * dt * texToDepth);
    float occ = 0.0;
    for (int i = 1; i <= testPoints; ++i) {
        vec3 r = P + (float(i) * dt) * d;
        ivec2 q = ivec2(floor(r.xy * vec2(outputSize)));
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, outputSize))) break;
#if ISMOS_PARTIAL
        occ += (1.0 - occ) * segmentOpacity(q, r.z, dz);
        if (occ >= 1.0) break;
#else
        if (fullyOccluded(q, r.z)) return 1.0;
#endif
    }
    return occ;
}

bool insideSpot(int j, vec3 p) {
    if (lightSpot[j].w < -1.0) return true;
    vec3 a = p - lightCentre[j], b = lightSpot[j].xyz - lightCentre[j];
    float la = length(a), lb = length(b);
    if (la <= 0.0 || lb <= 0.0) return true;
    return dot(a, b) / (la * lb) >= lightSpot[j].w;
}

float intensity(int j, vec3 p) {
    if (!falloff) return 1.0;
    vec3 toCentre = lightCentre[j] - vec3(0.5), toP = lightCentre[j] - p;
    return dot(toCentre, toCentre) / max(dot(toP, toP), 1e-12);
}

// Eq. 13-14 (and 16): the pooled occlusion of P over every light's samples; `light` gets eq. 15's
// (1 / M) sum_j C_j I_Lj.
float pooledOcclusion(vec3 P, out vec3 light) {
    float occluded = 0.0;
    light = vec3(0.0);
    for (int j = 0; j < lightCount; ++j) {
        light += lightTint[j] * intensity(j, P);
        if (!insideSpot(j, P)) {
            occluded += float(samplesPerLight);
            continue;
        }
        for (int i = 0; i < samplesPerLight; ++i) occluded += pathOcclusion(P, lightSample[j * samplesPerLight + i].xyz);
    }
    light /= float(max(lightCount, 1));
    return occluded / float(max(lightCount * samplesPerLight, 1));
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, outputSize))) return;
    vec4 f = texelFetch(layerFront, pixel, 0);
    if (f.x == NO_LAYER || lightCount == 0) return;
    vec4 a = texelFetch(layerAlpha, pixel, 0);
    vec2 xy = (vec2(pixel) + 0.5) / vec2(outputSize);
    float occSum = 0.0, weightSum = 0.0, before = 1.0;
    vec3 lightSum = vec3(0.0);
    for (int k = 0; k < ISMOS_LAYERS; ++k) {
        if (f[k] == NO_LAYER) break;
        float w = 1.0;
#if ISMOS_LAYERS > 1
#if ISMOS_BLEND
        w = a[k] * before;   // front-to-back: this layer's share of the pixel
        before *= 1.0 - a[k];
#else
        if (a[k] < opacityThreshold) continue;   // transparent layers keep their local illumination
#endif
#endif
        vec3 light;
        float occ = pooledOcclusion(vec3(xy, f[k]), light);
        occSum += w * occ;
        lightSum += w * light;
        weightSum += w;
#if ISMOS_LAYERS == 1 || !ISMOS_BLEND
        break;   // one shaded layer
#endif
    }
    if (weightSum <= 0.0) return;
    float occ = occSum / weightSum;
    vec3 light = lightSum / weightSum;
    vec4 c = imageLoad(outputImage, pixel);
    imageStore(outputImage, pixel, vec4(c.rgb * light * max(1.0 - occ, ambientFloor), c.a));
}
