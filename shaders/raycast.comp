#version 450
// Step VI: perspective ray casting of the volume, one invocation per pixel. Front-to-back compositing with
// early termination; entry/exit from the volume box; empty bricks skipped without moving the sample
// lattice, so skipping never changes the image. Samples lie at t = (k + jitter) * stepMm along each ray,
// t measured in millimetres from the eye, so the segment length of every sample is stepMm exactly.
#include "bindings.glsl"
#include "shading_modes.glsl"
#include "volume.glsl"
#include "transfer_function.glsl"
#include "phong.glsl"
#include "random.glsl"
#include "clip_test.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = IMAGE_OUTPUT) uniform writeonly image2D outputImage;
layout(binding = BINDING_OCCUPANCY) uniform sampler3D occupancy;
layout(binding = BINDING_AMBIENT) uniform sampler3D ambientOcclusion;   // V_AO (lao/cao shading)

uniform mat4 inverseViewProjection;  // clip space -> world
uniform vec3 eyeWorld;
uniform ivec2 outputSize;
uniform float stepMm;
uniform float earlyTerminationAlpha;
uniform uint jitterSeed;             // 0: no jitter
uniform bool skipEmptySpace;
uniform float ambientScale;          // lao/cao: the factor applied to V_AO
uniform ivec3 volumeSize;
uniform int brickSize;
#ifdef COUNT_SAMPLES
layout(std430, binding = 0) buffer SampleCounter { uint samplesTaken; };  // `curette bench` only
#endif

// Ray parameter interval inside the axis-aligned box [lo, hi] (texture space), or false if it misses.
bool intersectBox(vec3 origin, vec3 direction, vec3 lo, vec3 hi, out float tNear, out float tFar) {
    vec3 inverse = 1.0 / direction;  // IEEE: +-inf for zero components, which the min/max below handle
    vec3 a = (lo - origin) * inverse, b = (hi - origin) * inverse;
    vec3 nearAxes = min(a, b), farAxes = max(a, b);
    tNear = max(max(nearAxes.x, nearAxes.y), nearAxes.z);
    tFar = min(min(farAxes.x, farAxes.y), farAxes.z);
    return tFar >= max(tNear, 0.0);
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, outputSize))) return;

    // Ray through the pixel centre; image row 0 is the top of the picture.
    vec2 ndc = (vec2(pixel) + 0.5) / vec2(outputSize) * 2.0 - 1.0;
    ndc.y = -ndc.y;
    vec4 farPoint = inverseViewProjection * vec4(ndc, 1.0, 1.0);
    vec3 direction = normalize(farPoint.xyz / farPoint.w - eyeWorld);
    vec3 originTex = toTexture(eyeWorld);
    vec3 directionTex = mat3(worldToTexture) * direction;

    vec4 accumulated = vec4(0.0);  // premultiplied colour, opacity
    uint samples = 0u;
    float tNear, tFar;
    if (intersectBox(originTex, directionTex, vec3(0.0), vec3(1.0), tNear, tFar)) {
        float jitter = jitterSeed != 0u ? pixelRandom(uvec2(pixel), jitterSeed) : 0.0;
        int k = int(ceil(max(tNear, 0.0) / stepMm - jitter));
        int kLast = int(floor(tFar / stepMm - jitter));
        for (; k <= kLast; ++k) {
            float t = (float(k) + jitter) * stepMm;
            vec3 tex = originTex + t * directionTex;
            if (skipEmptySpace) {
                ivec3 brick = clamp(ivec3(floor(tex * vec3(volumeSize) / float(brickSize))), ivec3(0),
                                    textureSize(occupancy, 0) - 1);
                if (texelFetch(occupancy, brick, 0).r == 0.0) {
                    // Jump to the last lattice sample inside this brick; the loop's ++k moves past it.
                    vec3 lo = vec3(brick * brickSize) / vec3(volumeSize);
                    vec3 hi = vec3((brick + 1) * brickSize) / vec3(volumeSize);
                    float bNear, bFar;
                    intersectBox(originTex, directionTex, lo, hi, bNear, bFar);
                    k = max(k, int(floor(bFar / stepMm - jitter)));
                    continue;
                }
            }
            // Step VI's shadow-test clipping: a sample inside any clip mesh is not there.
            if (clipMeshCount > 0 && insideAnyClipMesh(eyeWorld + t * direction)) continue;
            ++samples;
            float texel = sampleTexel(tex);
            vec4 classified = classify(texel);
#if SHADING == SHADING_PHONG
            vec3 gradient = gradientWorld(tex);
#else
            vec3 gradient = useGradientOpacity ? gradientWorld(tex) : vec3(0.0);
#endif
            float alphaUnit = classified.a;
            if (useGradientOpacity) alphaUnit *= gradientOpacityFactor(length(gradient));
            float alpha = correctOpacity(alphaUnit, stepMm);
            if (alpha <= 0.0) continue;
#if SHADING == SHADING_PHONG
            vec3 color = shadePhong(classified.rgb, gradient, -direction, 1.0);
#elif SHADING == SHADING_LAO || SHADING == SHADING_CAO
            // The ambient factor of the sample from V_AO (CAO step VI): the colour lit by ambient light only,
            // scaled so an open flat surface (half its rays blocked, A = 0.5) shows the TF colour.
            vec3 color = classified.rgb * ambientScale * texture(ambientOcclusion, tex).r;
#else
            vec3 color = classified.rgb;
#endif
            accumulated.rgb += (1.0 - accumulated.a) * alpha * color;
            accumulated.a += (1.0 - accumulated.a) * alpha;
            if (accumulated.a >= earlyTerminationAlpha) break;
        }
    }
#ifdef COUNT_SAMPLES
    atomicAdd(samplesTaken, samples);
#endif
    imageStore(outputImage, pixel, accumulated);
}
