#version 450
// Step VI: perspective ray casting of the volume, one invocation per pixel. Front-to-back compositing with
// early termination; entry/exit from the volume box; empty bricks skipped without moving the sample
// lattice, so skipping never changes the image: the occupancy texture holds each empty brick's Chebyshev
// distance d to the nearest brick with a visible value (render/model/brick_distance.h), so the ray jumps out of
// the cube of (2d - 1)^3 empty bricks around it at once. Samples lie at t = (k + jitter) * stepMm along each ray,
// t measured in millimetres from the eye, so the segment length of every sample is stepMm exactly, except
// with CUT_FACES: where the ray leaves a clip mesh, one extra segment from the crossing to the next lattice
// sample, with its partial length (the lattice itself does not move). With TUBES (tube_surface.glsl) the ray
// ends in front of the tube G-buffer's surface, which is shaded in the mode's light and laid behind it.
#include "bindings.glsl"
#include "pixel_ray.glsl"
#include "shade_sample.glsl"
#include "random.glsl"
#include "clip_test.glsl"
#include "tile_order.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = IMAGE_OUTPUT) uniform writeonly image2D outputImage;
layout(binding = BINDING_OCCUPANCY) uniform sampler3D occupancy;

uniform float stepMm;
uniform float earlyTerminationAlpha;
uniform uint jitterSeed;             // 0: no jitter
uniform bool skipEmptySpace;
uniform ivec3 volumeSize;
uniform int brickSize;
uniform int maxSkipBricks;           // the most bricks one jump crosses (Renderer::setEmptySpaceJumpLimit)
#ifdef COUNT_SAMPLES
// `curette bench` only: samples, loop steps, and the steps of the groups in each half of the dispatch.
layout(std430, binding = 0) buffer SampleCounter { uint samplesTaken; uint raySteps; uint halfSteps[2]; };
#endif
#ifdef ISMOS_LAYERS
#include "ismos_layers.glsl"
#endif
#ifdef TUBES
#include "tube_surface.glsl"
#endif

// Front-to-back compositing of one segment: premultiplied colour and opacity.
void composite(inout vec4 accumulated, vec3 color, float alpha) {
    accumulated.rgb += (1.0 - accumulated.a) * alpha * color;
    accumulated.a += (1.0 - accumulated.a) * alpha;
}

// Ray parameter interval inside the axis-aligned box [lo, hi] (texture space), or false if it misses.
bool intersectBox(vec3 origin, vec3 direction, vec3 lo, vec3 hi, out float tNear, out float tFar) {
    // A zero component would give 1/0 = inf and, for an origin on that face, 0 * inf = NaN; a tiny stand-in
    // keeps every product finite and orders the slabs as inf would.
    vec3 safe = mix(direction, vec3(1e-30), lessThan(abs(direction), vec3(1e-30)));
    vec3 inverse = 1.0 / safe;
    vec3 a = (lo - origin) * inverse, b = (hi - origin) * inverse;
    vec3 nearAxes = min(a, b), farAxes = max(a, b);
    tNear = max(max(nearAxes.x, nearAxes.y), nearAxes.z);
    tFar = min(min(farAxes.x, farAxes.y), farAxes.z);
    return tFar >= max(tNear, 0.0);
}

// Phong's six gradient fetches are taken between rounds of the sample loop, for the visible samples only
// (see castRay), unless the renderer found most of a ray's steps visible (PHONG_SHADED_IN_LOOP:
// render/model/phong_shading_placement.h). Solid and lao/cao shading cost less than the rounds do, so they
// shade in the loop.
#if SHADING == SHADING_PHONG && !defined(GRADIENT_OPACITY) && !defined(PHONG_SHADED_IN_LOOP)
#define SHADE_BETWEEN_ROUNDS
#endif
// Without either reason for rounds the loop runs in one (the loop around it cost the solid head 10 %).
#if defined(CUT_FACES) || defined(SHADE_BETWEEN_ROUNDS)
#define SAMPLE_ROUNDS
#endif

// Phong lights the tissue behind a cut face by the face (shade_sample.glsl), also where the face lies in empty
// space, so a jump must not pass over a crossing: within the span of the meshes' depth boxes the ray walks
// every lattice sample, and a jump stops before it. The crossing is found as without skipping, so skipping
// cannot change the image. (The other modes shade no sample by a face it has left, and a face sample in an
// empty brick is transparent: their jumps only keep out of the meshes.)
#if defined(CUT_FACES) && SHADING == SHADING_PHONG
#define JUMPS_STAY_OUT_OF_CROSSINGS
#endif

#ifdef CUT_FACES
float faceT;          // ray parameter of the last cut face crossed (-1: none)
vec3 faceNormal;
float faceCosine;     // |cos| between the ray and the face normal: depth behind the face per mm of ray
float faceOpacityStart;   // the ray's opacity in front of the face
#endif
#ifdef ISMOS_LAYERS
IsmosLayers layers;
float depthPerMm;
#endif

// Shades a visible sample at ray parameter t and composites it; true once the ray is opaque enough to stop.
bool shadeAndComposite(inout vec4 accumulated, VolumeSample point, vec3 tex, float t, float alpha, vec3 direction) {
    point = withShadingGradient(point, tex);
#ifdef CUT_FACES
    float behind = faceT >= 0.0 ? (accumulated.a - faceOpacityStart) / max(1.0 - faceOpacityStart, 1e-6) : 1.0;
    vec3 color = shadeCutFaceSample(point, tex, -direction, faceNormal, faceT >= 0.0 ? (t - faceT) * faceCosine : 1e30, behind);
#else
    vec3 color = shadeSample(point, tex, -direction);
#endif
    composite(accumulated, color, alpha);
#ifdef ISMOS_LAYERS
    ismosSample(layers, t * depthPerMm - ismosNearDepth, alpha, 1.0 - accumulated.a);
    if (accumulated.a >= earlyTerminationAlpha) ismosTerminated(layers);
#endif
    return accumulated.a >= earlyTerminationAlpha;
}

// The ray's lattice samples k..kLast inside the box [tNear, tFar], and its jitter.
void latticeRange(ivec2 pixel, vec3 direction, float tNear, float tFar, out float jitter, out int k, out int kLast) {
    jitter = jitterSeed != 0u ? pixelRandom(uvec2(pixel), jitterSeed) : 0.0;
    k = int(ceil(max(tNear, 0.0) / stepMm - jitter));
    kLast = int(floor(tFar / stepMm - jitter));
#ifdef ISMOS_TUBES
    // The ray stops in front of the tube surface (G-buffer view depth; 0: none).
    float tubeView = texelFetch(ismosTubeDepth, pixel, 0).r;
    if (tubeView > 0.0) kLast = min(kLast, int(ceil(tubeView / dot(direction, ismosForward) / stepMm - jitter)) - 1);
#endif
#ifdef TUBES
    // The ray ends in front of the tube surface: only lattice samples with t < the surface's are taken.
    float tubeT = tubeRayT(pixel, direction);
    if (tubeT > 0.0) kLast = min(kLast, int(ceil(tubeT / stepMm - jitter)) - 1);
#endif
}

#ifdef CUT_FACES
// The ray left mesh `meshBehind` between lattice samples k - 1 and k: sets the face (faceT, faceNormal,
// faceCosine) and returns the segment the sample taken on it stands for, from the crossing to the end of
// lattice sample k's half step.
float crossFace(int meshBehind, int k, float jitter, vec3 direction) {
    float tLattice = (float(k) + jitter) * stepMm;
    vec3 outward;
    float s = clipExitFraction(meshBehind, eyeWorld + (tLattice - stepMm) * direction, eyeWorld + tLattice * direction, outward);
    float crossing = tLattice - (1.0 - s) * stepMm;
    faceNormal = -outward;
    faceCosine = abs(dot(direction, faceNormal));
    faceT = crossing;
    return tLattice + 0.5 * stepMm - crossing;
}
#endif

// In an empty brick (occupancy distance d > 0) moves k to the last lattice sample inside the cube of bricks
// within Chebyshev distance d - 1, all empty (the caller's ++k moves past it), and returns true.
bool skipEmptyBricks(vec3 tex, vec3 originTex, vec3 directionTex, float jitter, inout int k) {
    ivec3 brick = clamp(ivec3(floor(tex * vec3(volumeSize) / float(brickSize))), ivec3(0),
                        textureSize(occupancy, 0) - 1);
    int distance = int(texelFetch(occupancy, brick, 0).r * 255.0 + 0.5);
    if (distance <= 0) return false;
    int reach = min(distance, maxSkipBricks) - 1;
    vec3 lo = vec3((brick - reach) * brickSize) / vec3(volumeSize);
    vec3 hi = vec3((brick + 1 + reach) * brickSize) / vec3(volumeSize);
    float bNear, bFar;
    intersectBox(originTex, directionTex, lo, hi, bNear, bFar);
    k = max(k, int(floor(bFar / stepMm - jitter)));
#ifdef ISMOS_LAYERS
    ismosGap(layers);
#endif
    return true;
}

// Walks the ray's lattice samples inside the box and returns their composite (premultiplied colour, opacity).
// `crossings` is where the ray can lie in a clip mesh (rayClipSpan). main() calls this twice, with the literal
// meshesNear false for a ray that meets no mesh's depth box and true for the others: the compiler folds every
// clip test, crossing and face of the first call away (no sample of such a ray is in a mesh, so the answers
// are the same), and a group of rays that all miss the meshes runs the first call's loop alone. llvmpipe runs
// an if's body under a lane mask whether or not any lane takes it, so the tests cost a ray that could never
// use them: rays beside two meshes of the carved head took 1.5 times as long as without the meshes.
vec4 castRay(ivec2 pixel, vec3 direction, vec3 originTex, vec3 directionTex, float tNear, float tFar, ClipSpan crossings,
             const bool meshesNear, inout uint samples, inout uint steps) {
    vec4 accumulated = vec4(0.0);
    float jitter;
    int k, kLast;
    latticeRange(pixel, direction, tNear, tFar, jitter, k, kLast);
    // Without the box tests (the reference) every sample is tested against every mesh.
    ClipSpan span = clipDepthBoxTests ? crossings : ClipSpan(-1e30, 1e30, 0xffffffffu);
#ifdef CUT_FACES
    // Cut faces (clip_test.glsl, shade_sample.glsl). Lattice sample k stands for the ray within half a
    // step of it (the sum over the lattice is the midpoint rule). Where the ray leaves a clip mesh, the
    // first visible lattice sample is taken at the crossing instead, standing for the ray from there to
    // the end of its own half step, so the tissue starts exactly where the face is; the lattice does not
    // move. A clipped sample costs its clip test alone (no jump, no classification); the face is worked out
    // once per crossing, between rounds of the sample loop (below).
    faceT = -1.0;
    faceNormal = vec3(0.0);
    faceCosine = 0.0;
    faceOpacityStart = 0.0;
    int meshBehind = -1;        // the mesh holding the last lattice sample (-1: none)
#endif
    // The ray runs in rounds. A round's sample loop walks the lattice until it meets a crossing (the first
    // sample past it, with cut faces) or, with SHADE_BETWEEN_ROUNDS, a visible sample, and stops there; the
    // next round works the face out, or shades the sample. llvmpipe runs every line of a loop body on every
    // step, taken or not (a block never taken that fetched 18 texels took the head's solid ray cast from
    // 53 to 333 ms), so what only some samples need is kept out of the sample loop where that pays for the
    // lanes that wait at the end of a round: the crossing (40 % of the carved head's solid ray cast when it
    // was in the loop) and phong's gradient.
    bool rayDone = false;
#ifdef SHADE_BETWEEN_ROUNDS
    bool shadePending = false;  // the last round stopped at a visible sample:
    VolumeSample pending;       // its classification,
    vec3 pendingTex;            // where it is,
    float pendingT = 0.0;       // how far along the ray,
    float pendingAlpha = 0.0;   // and the opacity of its segment
#endif
#ifdef SAMPLE_ROUNDS
    while (!rayDone) {
#endif
#ifdef SHADE_BETWEEN_ROUNDS
        if (shadePending) {
            shadePending = false;
            if (shadeAndComposite(accumulated, pending, pendingTex, pendingT, pendingAlpha, direction)) break;
            ++k;
        }
#endif
#ifdef CUT_FACES
        // The last round stopped at the first lattice sample past a crossing: this round takes it on the face.
        bool atFace = meshesNear && meshBehind >= 0;
        float faceSegment = stepMm;
        if (atFace) {
            faceSegment = crossFace(meshBehind, k, jitter, direction);
            faceOpacityStart = accumulated.a;
            meshBehind = -1;
        }
#endif
        for (; k <= kLast; ++k) {
            float t = (float(k) + jitter) * stepMm;
#ifdef CUT_FACES
            // The round's first sample, past a crossing, is taken at the face (its lattice sample is in no mesh).
            bool face = atFace;
            atFace = false;
            t = face ? faceT : t;
            float segment = face ? faceSegment : stepMm;
#endif
            vec3 tex = originTex + t * directionTex;
#ifdef COUNT_SAMPLES
#ifdef CUT_FACES
            if (!face) ++steps;
#else
            ++steps;
#endif
#endif
#if defined(JUMPS_STAY_OUT_OF_CROSSINGS)
            // Where the ray can cross a mesh: its empty-space jumps stay out, with or without the box tests.
            bool mayJump = skipEmptySpace && !(meshesNear && insideSpan(crossings, t));
#elif defined(CUT_FACES)
            // Inside a mesh the ray walks every lattice sample, so it finds the one past the crossing.
            bool mayJump = skipEmptySpace && meshBehind < 0 && !face;
#else
            bool mayJump = skipEmptySpace;
#endif
            if (mayJump && skipEmptyBricks(tex, originTex, directionTex, jitter, k)) {
#ifdef JUMPS_STAY_OUT_OF_CROSSINGS
                if (meshesNear && t < crossings.near) k = min(k, int(ceil(crossings.near / stepMm - jitter)) - 1);
#endif
                continue;
            }
            // Step VI's shadow-test clipping: a sample inside any clip mesh is not there.
#ifdef CUT_FACES
            int holding = -1;
            if (meshesNear && !face && insideSpan(span, t)) holding = clipMeshHoldingAmong(span.meshes, eyeWorld + t * direction);
            if (holding >= 0) {
                meshBehind = holding;
#ifdef ISMOS_LAYERS
                ismosGap(layers);
#endif
                continue;  // the ray ends inside the mesh if no later lattice sample leaves it
            }
            // The ray left mesh `meshBehind` between the last lattice sample and this one: the next round takes
            // this sample at the face between them.
            if (meshesNear && meshBehind >= 0) break;
#else
            if (meshesNear && insideSpan(span, t) && clipMeshHoldingAmong(span.meshes, eyeWorld + t * direction) >= 0) {
#ifdef ISMOS_LAYERS
                ismosGap(layers);
#endif
                continue;
            }
#endif
            ++samples;
            VolumeSample point = classifyOpacity(tex);
#ifdef CUT_FACES
            // (Both are computed, llvmpipe taking either branch; the root costs little beside pow.)
            float alpha = face ? correctOpacity(point.alphaUnit, segment) : correctStepOpacity(point.alphaUnit, stepMm);
#else
            float alpha = correctStepOpacity(point.alphaUnit, stepMm);
#endif
            if (alpha <= 0.0) {
                // (A cut face's layer goes on through transparent samples: ending it at the first one lit the
                // tissue beyond a face in faint tissue by its gradient in some pixels and by the face in their
                // neighbours, a salt of specular dots. The depth and opacity fades end it.)
#ifdef ISMOS_LAYERS
                ismosGap(layers);
#endif
                continue;
            }
#ifdef SHADE_BETWEEN_ROUNDS
            shadePending = true;
            pending = point;
            pendingTex = tex;
            pendingT = t;
            pendingAlpha = alpha;
            break;
#else
            if (shadeAndComposite(accumulated, point, tex, t, alpha, direction)) {
                rayDone = true;
                break;
            }
#endif
        }
#ifdef SAMPLE_ROUNDS
        // A round that stopped at a visible sample or a crossing stopped at a lattice sample; past the last
        // one, the lattice ran out.
        if (k > kLast) rayDone = true;
    }
#endif
    return accumulated;
}

#ifdef ISMOS_LAYERS
// The pixel's ISMOS layers; a tube is an opaque layer at its depth, as thick as the tube there (the compositor
// adds its colour behind the volume).
void storeIsmosLayers(ivec2 pixel, vec4 accumulated) {
#ifdef ISMOS_TUBES
    float surface = texelFetch(ismosTubeDepth, pixel, 0).r;
    if (surface > 0.0 && accumulated.a < earlyTerminationAlpha) {
        // The view depth the tube fills at this pixel: a round tube's chord along the view, its diameter times
        // |n . forward| (n the surface normal; a line has no chord: the diameter).
        vec4 normalKind = texelFetch(ismosTubeNormal, pixel, 0);
        float chord = normalKind.w == SURFACE_TUBE ? ismosTubeThicknessMm * abs(dot(normalize(normalKind.xyz), ismosForward))
                                                   : ismosTubeThicknessMm;
        ismosOpaqueSlab(layers, surface / ismosDepthRangeMm - ismosNearDepth, chord / ismosDepthRangeMm, 1.0 - earlyTerminationAlpha);
    }
#endif
    ismosStore(layers, pixel);
}
#endif

void main() {
    ivec2 pixel;
    if (!tilePixel(gl_WorkGroupSize.xy, pixel) || outsideImage(pixel)) return;
    vec3 direction = pixelRayDirection(pixel);
    vec3 originTex = toTexture(eyeWorld);
    vec3 directionTex = mat3(worldToTexture) * direction;

    vec4 accumulated = vec4(0.0);  // premultiplied colour, opacity
    uint samples = 0u, steps = 0u;
#ifdef ISMOS_LAYERS
    layers = ismosBegin();
    depthPerMm = dot(direction, ismosForward) / ismosDepthRangeMm;
#endif
    float tNear, tFar;
    bool hitsVolume = intersectBox(originTex, directionTex, vec3(0.0), vec3(1.0), tNear, tFar);
    ClipSpan crossings = rayClipSpan(eyeWorld, direction);   // (NO_CLIP_MESHES: folds to the empty span)
#ifdef NO_CLIP_MESHES
    // (A loop of one turn around the sample loop, as below, cost the head without meshes 5-10 %.)
    if (hitsVolume) accumulated = castRay(pixel, direction, originTex, directionTex, tNear, tFar, crossings, false, samples, steps);
#else
    // Loops of at most one turn, not an if and an else: llvmpipe skips a loop no lane enters (castRay).
    bool meshesNear = clipMeshCount > 0 && (crossings.meshes != 0u || !clipDepthBoxTests);
    for (int once = hitsVolume && !meshesNear ? 1 : 0; once > 0; --once)
        accumulated = castRay(pixel, direction, originTex, directionTex, tNear, tFar, crossings, false, samples, steps);
    for (int once = hitsVolume && meshesNear ? 1 : 0; once > 0; --once)
        accumulated = castRay(pixel, direction, originTex, directionTex, tNear, tFar, crossings, true, samples, steps);
#endif
#ifdef TUBES
    // The opaque tube surface behind the volume in front of it (also where the ray misses the volume's box).
    float tubeT = tubeRayT(pixel, direction);
    if (tubeT > 0.0) accumulated = vec4(accumulated.rgb + (1.0 - accumulated.a) * shadeTubeSurface(pixel, direction, tubeT), 1.0);
#endif
#ifdef COUNT_SAMPLES
    atomicAdd(samplesTaken, samples);
    atomicAdd(raySteps, steps);
    atomicAdd(halfSteps[inFirstHalfOfDispatch() ? 0 : 1], steps);
#endif
    imageStore(outputImage, pixel, accumulated);
#ifdef ISMOS_LAYERS
    storeIsmosLayers(pixel, accumulated);
#endif
}
