#version 450
// One view-aligned slice of the slab pass (Directional Occlusion Shading, seed 001 Algorithms 1 and 3;
// with tubes, seed 000 Algorithms 2-4). All rays advance together: slice k is the plane at view depth
// z_k = firstDepth + k * sliceDistance, and a pixel's sample is where its ray crosses that plane, so the
// segment it stands for is the true length along the ray, sliceDistance / cos(angle to the view axis).
//
// With a jitter seed each pixel takes its samples a fixed random fraction of a slice behind the planes (the same
// fraction in every slice, as the ray caster jitters its lattice), so the slices do not show as rings where a
// surface crosses them; the occlusion buffer stays on the planes.
//
// Occlusion buffer (two channels, docs/subsystems.md "Tubes in the slab pass"):
//   .x "all": visibility of the ambient light through the cone, from the clipped volume and the tubes;
//   .y "geometry": the same from the tubes alone.
// Eye buffer update (seed 001 Algorithm 1): C += (1 - A) * alpha * La * colour * ambient(prev occlusion).
// Occlusion update (Algorithm 3, eq. 11-15): the average of the previous buffer over an n x n grid on the
// cone base (radius d tan(theta), projected at the previous slice's depth: the perspective correction of
// eq. 12), times this slice's transmittance.
#include "bindings.glsl"
#include "pixel_ray.glsl"
#include "shade_sample.glsl"
#include "clip_test.glsl"
#include "random.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = IMAGE_OUTPUT) uniform image2D eyeBuffer;
layout(rg32f, binding = IMAGE_OCCLUSION_NEXT) uniform writeonly image2D occlusionNext;
layout(binding = BINDING_OCCLUSION_PREVIOUS) uniform sampler2D occlusionPrevious;

uniform vec3 viewForward;          // unit, world
uniform float sliceDepth;          // z_k: distance of this slice's plane from the eye along viewForward, mm
uniform float sliceDistance;       // d, mm
uniform float coneRadiusPixels;    // d tan(theta) in pixels at the previous slice's depth (eq. 11, 12)
uniform int gridSize;              // n: the cone base is sampled on an n x n grid (points inside the disk)
uniform float ambientRadiance;     // La: the ambient light of dos shading (seed 001); lao/cao use V_AO
uniform float earlyTerminationAlpha;
uniform int firstRow;              // the dispatch covers a band of rows from here (a slice in several dispatches)
uniform uint jitterSeed;            // 0: samples on the planes

#ifdef HAS_TUBES
// Tubes (seed 000): a tube shadows the volume behind it (Algorithm 3: geometry in the occlusion buffer), and
// the volume contributes to the eye buffer only in front of the surface (Algorithm 2). The G-buffer holds
// only the nearest surface, so a tube is taken to fill the view depths [s, s + T] behind its surface s, T its
// diameter, with an extinction per millimetre that makes the whole crossing absorb geometryOpacity:
//     alpha(segment) = 1 - (1 - geometryOpacity)^(overlap / T),
// overlap the depth the slice's interval [z_k, z_k + d] shares with [s, s + T]. The slices' alphas then
// compose to geometryOpacity whatever the slice distance (the per-slice injection it replaces darkened the
// shadow with every extra slice behind the surface), and the volume behind the tube still occludes.
// The slice whose interval holds s records the occlusion reaching the surface (Algorithm 4, the partial
// occlusion buffer), interpolated in depth between this slice's value and the next one's (seed 000 eq. 3),
// so it is continuous along a tube that runs in depth instead of a staircase at the slices.
layout(binding = BINDING_TUBE_DEPTH) uniform sampler2D tubeDepth;
layout(r32f, binding = IMAGE_PARTIAL_OCCLUSION) uniform writeonly image2D partialOcclusion;
uniform float geometryOpacity;
uniform float tubeThicknessMm;     // T
#endif

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy) + ivec2(0, firstRow);
    if (outsideImage(pixel)) return;
    vec3 direction = pixelRayDirection(pixel);
    float cosine = dot(direction, viewForward);
    float sampleDepth = sliceDepth + (jitterSeed != 0u ? pixelRandom(uvec2(pixel), jitterSeed) : 0.0) * sliceDistance;
    float t = sampleDepth / cosine;              // where this ray takes the slice's sample
    float segment = sliceDistance / cosine;      // the true length of ray this sample stands for
    // The sample stands for the ray between its depth and a slice distance further; a tube surface inside that
    // interval cuts it short (Algorithm 2: sampling_distance = min(slice_distance, delta)).
    float eyeSegment = segment;
    bool behindSurface = false;
#ifdef HAS_TUBES
    float surfaceDepth = texelFetch(tubeDepth, pixel, 0).r;  // 0: no tube at this pixel
    if (surfaceDepth > 0.0) {
        behindSurface = sampleDepth >= surfaceDepth;
        eyeSegment = min(sliceDistance, max(surfaceDepth - sampleDepth, 0.0)) / cosine;
    }
#endif
    vec3 world = eyeWorld + t * direction;
    vec3 tex = toTexture(world);

    // This slice's sample (nothing outside the volume or inside a clip mesh).
    bool insideVolume = all(greaterThanEqual(tex, vec3(0.0))) && all(lessThanEqual(tex, vec3(1.0)));
    VolumeSample point = emptySample();
#ifdef CUT_FACES
    // Cut faces (clip_test.glsl): this slice's sample stands for the ray within half a slice interval of it.
    // When the ray leaves a clip mesh inside that interval (the sample clipped and the interval's far end
    // visible, or the sample visible and its near end clipped), the sample is taken at the crossing instead,
    // standing for the ray from there to the interval's far end, and lit as the face (its normal, V_AO
    // behind it); the samples of later slices are lit as the volume is.
    vec3 faceNormal = vec3(0.0);
    bool onFace = false;
    // Only the meshes whose depth box the ray meets within the sample's interval are tested, and the crossing
    // is worked out in a loop of at most one turn: llvmpipe skips a loop no lane enters, while it runs an if's
    // body for every lane when any takes it.
    ClipSpan span = rayClipSpan(eyeWorld, direction);
    uint meshesNear = span.near <= t + 0.5 * segment && span.far >= t - 0.5 * segment ? span.meshes : 0u;
    int holding = clipMeshHoldingAmong(meshesNear, world);
    bool clipped = holding >= 0;
    vec3 nearEnd = world - 0.5 * segment * direction, farEnd = world + 0.5 * segment * direction;
    int holdingOther = clipMeshHoldingAmong(meshesNear, clipped ? farEnd : nearEnd);
    bool leaves = clipped ? holdingOther < 0 : holdingOther >= 0;
    for (int once = leaves && insideVolume ? 1 : 0; once > 0; --once) {
        vec3 outward;
        vec3 from = clipped ? world : nearEnd, to = clipped ? farEnd : world;
        float s = clipExitFraction(clipped ? holding : holdingOther, from, to, outward);
        float crossing = t + (clipped ? 0.0 : -0.5 * segment) + s * 0.5 * segment;
        faceNormal = -outward;
        float rest = t + 0.5 * segment - crossing;
        eyeSegment = max(eyeSegment - (segment - rest), 0.0);
        segment = rest;
        world = eyeWorld + crossing * direction;
        tex = toTexture(world);
        clipped = false;
        onFace = true;
    }
#else
    bool clipped = clipMeshCount > 0 && insideAnyClipMesh(world);
#endif
    for (int visible = insideVolume && !clipped ? 1 : 0; visible > 0; --visible) point = classifySample(tex);
    float alpha = correctOpacity(point.alphaUnit, segment);           // for the occlusion buffer: the whole slice
    float eyeAlpha = correctOpacity(point.alphaUnit, eyeSegment);     // for the eye: up to a tube surface

    // Cone-base average of the previous occlusion buffer (Algorithm 3).
    vec2 previousSum = vec2(0.0);
    float count = 0.0;
    vec2 centre = (vec2(pixel) + 0.5) / vec2(outputSize);
    for (int j = 0; j < gridSize; ++j)
        for (int i = 0; i < gridSize; ++i) {
            vec2 p = (vec2(i, j) + 0.5) / float(gridSize) * 2.0 - 1.0;
            if (gridSize > 1 && dot(p, p) > 1.0) continue;
            vec2 offset = (gridSize > 1 ? p : vec2(0.0)) * coneRadiusPixels;
            previousSum += texture(occlusionPrevious, centre + offset / vec2(outputSize)).rg;
            count += 1.0;
        }
    vec2 occlusionBefore = texture(occlusionPrevious, centre).rg;
    vec2 blurred = previousSum / count;

    // Eye buffer (front to back). The sample is lit by the ambient light that reaches it through the cone:
    // dos shading uses channel "all"; cao/lao take the volume's own occlusion from V_AO and only the tubes'
    // shadows from channel "geometry", so nothing is counted twice.
    vec4 eye = imageLoad(eyeBuffer, pixel);
    if (!behindSurface && eyeAlpha > 0.0 && eye.a < earlyTerminationAlpha) {
#ifdef CUT_FACES
        vec3 color = shadeCutFaceSample(point, tex, -direction, faceNormal, onFace ? 0.0 : 1e30, onFace ? 0.0 : 1.0);
#else
        vec3 color = shadeSample(point, tex, -direction);
#endif
#if SHADING == SHADING_DOS
        color = ambientRadiance * color * occlusionBefore.x;
#elif SHADING == SHADING_LAO || SHADING == SHADING_CAO
        color *= occlusionBefore.y;
#endif
        eye.rgb += (1.0 - eye.a) * eyeAlpha * color;
        eye.a += (1.0 - eye.a) * eyeAlpha;
        imageStore(eyeBuffer, pixel, eye);
    }
    // This slice attenuates the light reaching every later slice; the geometry channel sees tubes only.
    vec2 sliceAlpha = vec2(alpha, 0.0);
#ifdef HAS_TUBES
    if (surfaceDepth > 0.0) {
        float overlap = max(min(sliceDepth + sliceDistance, surfaceDepth + tubeThicknessMm) - max(sliceDepth, surfaceDepth), 0.0);
        float tubeAlpha = 1.0 - pow(1.0 - geometryOpacity, overlap / tubeThicknessMm);
        sliceAlpha = vec2(1.0 - (1.0 - alpha) * (1.0 - tubeAlpha), tubeAlpha);
        // The surface lies in this slice's interval: the light reaching it, between this slice's value at
        // z_k and the volume-attenuated cone average at z_k + d (the tube's own opacity not yet applied).
        if (sliceDepth <= surfaceDepth && surfaceDepth < sliceDepth + sliceDistance) {
            float ratio = (surfaceDepth - sliceDepth) / sliceDistance;
            imageStore(partialOcclusion, pixel, vec4(mix(occlusionBefore.x, blurred.x * (1.0 - alpha), ratio)));
        }
    }
#endif
    vec2 next = blurred * (1.0 - sliceAlpha);
#ifdef OCCLUSION_UNCLAMPED
    // Tests only (SlabPass::setClampOcclusion(false)): the value as computed, so a test sees one outside [0, 1].
    imageStore(occlusionNext, pixel, vec4(next, 0.0, 0.0));
#else
    imageStore(occlusionNext, pixel, vec4(clamp(next, 0.0, 1.0), 0.0, 0.0));
#endif
}
