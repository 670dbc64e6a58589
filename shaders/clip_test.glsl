// Shadow-test clipping (CAO section 3.2, Algorithm 2 lines 17-27): one definition of "is this point inside a
// clip mesh" for every pass (step IV, step VI, the DOS slab pass), looping over the active meshes — no copy
// per mesh count. Each mesh has a clipping camera (orthographic, attached to the mesh: a rigid motion changes
// only worldToMap) and depth maps rendered once per geometry: interval 1 = (front 1, back 1), and for concave
// meshes interval 2 = (front 2, back 2) from depth peeling. Empty pixels hold +inf (front) / -inf (back).
// The dilated maps hold the same intervals grown by the LAO reach (step III). The depth maps cover only the
// mesh's bounds (the depth square) at a fine resolution of their own, so a face across the map lies within a
// small fraction of a voxel of the mesh's; the dilated maps cover the map square at a coarser one. Lookups use
// the nearest pixel of either, the rule render/passes/clip_mesh_set.cpp's derivations assume.
#include "bindings.glsl"
#include "octahedral.glsl"

#define MAX_CLIP_MESHES 16

struct ClipMeshGpu {
    mat4 worldToMap;   // world mm -> (map x, map y in [0,1], depth along the camera in mm)
    ivec4 info;        // x: first layer in the map arrays, y: intervals (1 or 2), z: map resolution,
                       // w: 1 when the mesh also clips tubes
    vec4 mapBox;       // the camera's map box in its own frame: x the map side in mm, y and z the depth
                       // range (local z, mm) holding every finite map value, w a slack for float rounding.
                       // Outside the box no map answers "inside".
    vec4 depthBoxLo;   // xyz: the depth box (ClipMeshSet::depthBoxLocal) in map coordinates (x, y over the
    vec4 depthBoxHi;   // map side, z the local depth in mm): outside it no depth map answers "inside"
    vec4 depthBall;    // xyz: the depth ball's world centre, w: its radius (mm; ClipMeshSet::depthBallLocal):
                       // outside it no depth map answers "inside" either
    vec4 depthMap;     // the depth square in map coordinates: depth x, y = (map x, y - depthMap.xy) * depthMap.z,
                       // w: the depth maps' resolution (ClippingCamera::depthOffset, depthScale)
};

// A uniform block, not a storage buffer: the array is small and every invocation reads the same entries,
// which llvmpipe then loads once per SIMD group instead of gathering per lane.
layout(std140, binding = UBO_CLIP_MESHES) uniform ClipMeshes { ClipMeshGpu clipMeshes[MAX_CLIP_MESHES]; };
layout(binding = BINDING_CLIP_DEPTH) uniform sampler2DArray clipDepthMaps;
layout(binding = BINDING_CLIP_NORMALS) uniform sampler2DArray clipNormalMaps;   // the cut faces' normals
layout(binding = BINDING_CLIP_DILATED) uniform sampler2DArray clipDilatedMaps;
// NO_CLIP_MESHES (ClipMeshSet::addDefines, a frame without meshes): the count is the constant 0, so every test
// below folds to "outside" at compile time. As a uniform 0 the tests were still paid: llvmpipe runs a branch's
// code under a lane mask, and the per-sample test was 45 % of the head's solid ray cast without any mesh.
#ifdef NO_CLIP_MESHES
const int clipMeshCount = 0;
#else
uniform int clipMeshCount;
#endif
// Whether the passes skip the clip tests no depth map can answer "inside" by the meshes' depth boxes (the ray
// caster's span, step IV's nearDepthBox): on, except for the tests' and `bench cao`'s reference
// (ClipMeshSet::setDepthBoxTests); the answers are the same either way.
uniform bool clipDepthBoxTests;

// Every active mesh, as a set of mesh bits (at most MAX_CLIP_MESHES = 16).
uint allClipMeshes() { return (1u << uint(clipMeshCount)) - 1u; }

// Point `world` inside the interval(s) of mesh `i` in maps `maps` (depth or dilated).
bool insideMeshMaps(int i, vec3 world, bool dilated) {
    ClipMeshGpu mesh = clipMeshes[i];
    vec3 m = (mesh.worldToMap * vec4(world, 1.0)).xyz;
    vec2 xy = dilated ? m.xy : (m.xy - mesh.depthMap.xy) * mesh.depthMap.z;
    if (any(lessThan(xy, vec2(0.0))) || any(greaterThanEqual(xy, vec2(1.0)))) return false;
    ivec2 pixel = ivec2(xy * (dilated ? float(mesh.info.z) : mesh.depthMap.w));
    int layer = mesh.info.x;
    for (int interval = 0; interval < mesh.info.y; ++interval, layer += 2) {
        float front = dilated ? texelFetch(clipDilatedMaps, ivec3(pixel, layer), 0).r
                              : texelFetch(clipDepthMaps, ivec3(pixel, layer), 0).r;
        float back = dilated ? texelFetch(clipDilatedMaps, ivec3(pixel, layer + 1), 0).r
                             : texelFetch(clipDepthMaps, ivec3(pixel, layer + 1), 0).r;
        if (front < m.z && m.z < back) return true;  // eq. 1 negated: inside the interval
    }
    return false;
}

// Whether any mesh's map box comes within `margin` of `world`: if not, every clip and dilation test of
// points within `margin` is false (step IV uses it to skip voxels far from all meshes). The distance to the
// box is measured in the camera's frame, which is rigid, so it is the world distance in mm.
bool nearAnyClipMesh(vec3 world, float margin) {
    for (int i = 0; i < clipMeshCount; ++i) {
        ClipMeshGpu mesh = clipMeshes[i];
        vec3 m = (mesh.worldToMap * vec4(world, 1.0)).xyz;
        vec3 outside = vec3(max(max(-m.xy, m.xy - 1.0), 0.0) * mesh.mapBox.x,
                            max(max(mesh.mapBox.y - m.z, m.z - mesh.mapBox.z), 0.0));
        float reach = margin + mesh.mapBox.w;
        if (dot(outside, outside) <= reach * reach) return true;
    }
    return false;
}

// The stretch of a ray that can lie in a clip mesh. Along origin + t direction (t in mm, direction a unit
// vector) mesh i's depth box (outside it no depth map answers "inside"; grown on the CPU by a margin for the
// rounding between a point computed from t here and in the test, ClipMeshSet::depthBoxLocal) is met only for
// t in [near_i, far_i]. A span holds the union of those intervals over the meshes and the set of meshes the
// ray meets at all. A ray caster tests a sample against the depth maps only inside its span and only for
// those meshes, so a mesh costs the samples near it, not every sample of the image; the answers are the same.
struct ClipSpan {
    float near, far;   // t in mm (near > far: the ray meets no mesh)
    uint meshes;       // bit i: the ray meets mesh i's depth box
};

ClipSpan rayClipSpan(vec3 origin, vec3 direction) {
    ClipSpan span = ClipSpan(1e30, -1e30, 0u);
    for (int i = 0; i < clipMeshCount; ++i) {
        ClipMeshGpu mesh = clipMeshes[i];
        // Slabs in map coordinates: the map transform is affine, so t is the world ray's parameter. A zero
        // component gets a tiny stand-in (no 0 * inf), ordering the slabs as inf would.
        vec3 o = (mesh.worldToMap * vec4(origin, 1.0)).xyz;
        vec3 d = mat3(mesh.worldToMap) * direction;
        vec3 safe = mix(d, vec3(1e-30), lessThan(abs(d), vec3(1e-30)));
        vec3 a = (mesh.depthBoxLo.xyz - o) / safe, b = (mesh.depthBoxHi.xyz - o) / safe;
        vec3 nearAxes = min(a, b), farAxes = max(a, b);
        float tNear = max(max(nearAxes.x, nearAxes.y), nearAxes.z), tFar = min(min(farAxes.x, farAxes.y), farAxes.z);
        // And where it meets the depth ball: |origin + t direction - centre| <= radius.
        vec3 fromCentre = origin - mesh.depthBall.xyz;
        float half_b = dot(fromCentre, direction);
        float discriminant = half_b * half_b - (dot(fromCentre, fromCentre) - mesh.depthBall.w * mesh.depthBall.w);
        float root = sqrt(max(discriminant, 0.0));
        tNear = max(tNear, -half_b - root);
        tFar = min(tFar, -half_b + root);
        if (discriminant >= 0.0 && tFar >= tNear) {
            span.near = min(span.near, tNear);
            span.far = max(span.far, tFar);
            span.meshes |= 1u << uint(i);
        }
    }
    return span;
}

// Whether mesh i's depth box and its depth ball both come within `margin` (mm) of `world`: if not, no point
// within `margin` of `world` is inside its depth maps. The box is measured in the map's frame with x and y
// scaled to mm (rigid).
bool nearDepthBox(int i, vec3 world, float margin) {
    ClipMeshGpu mesh = clipMeshes[i];
    vec3 m = (mesh.worldToMap * vec4(world, 1.0)).xyz;
    vec3 outside = max(max(mesh.depthBoxLo.xyz - m, m - mesh.depthBoxHi.xyz), 0.0) * vec3(mesh.mapBox.x, mesh.mapBox.x, 1.0);
    return dot(outside, outside) <= margin * margin && distance(world, mesh.depthBall.xyz) <= mesh.depthBall.w + margin;
}

bool insideSpan(ClipSpan span, float t) { return t >= span.near && t <= span.far; }

// The first mesh of the set `meshes` (bit i: mesh i) whose interval holds `world` (-1: none): the one loop
// behind every "inside a clip mesh" test (all meshes, a ray's span, the meshes near a voxel).
int clipMeshHoldingAmong(uint meshes, vec3 world) {
    // Over the set's bits, lowest first, not over every mesh: llvmpipe runs a loop's body for every lane while
    // any lane is still in the loop, so a voxel near one of two meshes then costs one mesh's test, not two.
    for (uint rest = meshes & allClipMeshes(); rest != 0u; rest &= rest - 1u) {
        int i = findLSB(rest);
        if (insideMeshMaps(i, world, false)) return i;
    }
    return -1;
}

// Clipped: inside at least one mesh (section 3.6: union of clipped regions).
bool insideAnyClipMesh(vec3 world) { return clipMeshHoldingAmong(0xffffffffu, world) >= 0; }

// Tubes are clipped only by the meshes set to clip them.
bool insideAnyTubeClippingMesh(vec3 world) {
    for (int i = 0; i < clipMeshCount; ++i)
        if (clipMeshes[i].info.w != 0 && insideMeshMaps(i, world, false)) return true;
    return false;
}

// Affected: inside at least one dilation shape (section 3.6: union of dilated regions).
bool insideAnyDilatedMesh(vec3 world) {
    for (int i = 0; i < clipMeshCount; ++i)
        if (insideMeshMaps(i, world, true)) return true;
    return false;
}

// ---- Cut faces (Weiskopf, Engel and Ertl 2003, "Interactive clipping techniques for texture-based volume
// visualization and volume shading", sec. 5: the clip surface, not the data, decides where a cut face is and
// how it is lit). Only passes compiled with CUT_FACES call these. llvmpipe runs every branch under a lane
// mask, so these run for every sample of a pass that calls them: each is a few fetches, no loop.

// The first mesh whose interval holds `world` (-1: none): insideAnyClipMesh that also says which.
int clipMeshHolding(vec3 world) { return clipMeshHoldingAmong(0xffffffffu, world); }

// Where the segment from `inside` (held by mesh i) to `outside` (held by no mesh) leaves mesh i, as the
// fraction s in [0, 1] along it, and the mesh's outward unit world normal there. The crossing is found by
// bisection with the clip test itself (insideMeshMaps), so the face lies exactly where the samples around it
// are clipped or kept: on the depth maps' pixels, a small fraction of a voxel across (the depth square,
// ClipMapSettings::depthResolution). (Newton steps on a bilinear reading of the maps did this before; near a
// silhouette of the map, where the surface is steep, they found no root or the wrong one, and the face
// showed a salt of misplaced samples there.) The normal is the surface's (mesh/surface_normals.h) from the
// normal maps: the texels of the interval's front and back around the crossing, each weighted by the inverse
// square of its surface point's distance from the crossing in millimetres plus a texel's square (near a
// silhouette texels a pixel apart in x, y lie millimetres apart in depth, and only the distance in all three
// axes tells which of them the crossing is on), carried from mesh-local to world through worldToMap (whose
// rows are the local axes over the map's extents). With no surface near it faces back along the segment.
const int kCrossingBisections = 6;   // 1/64 of a ray step

float clipExitFraction(int i, vec3 inside, vec3 outside, out vec3 outwardWorld) {
    float lo = 0.0, hi = 1.0;
    for (int step = 0; step < kCrossingBisections; ++step) {
        float middle = 0.5 * (lo + hi);
        if (insideMeshMaps(i, mix(inside, outside, middle), false)) lo = middle;
        else hi = middle;
    }
    float s = hi;   // the first point found outside: the sample taken there is kept, as the lattice's would be
    ClipMeshGpu mesh = clipMeshes[i];
    vec3 m0 = (mesh.worldToMap * vec4(inside, 1.0)).xyz, m = (mesh.worldToMap * vec4(mix(inside, outside, s), 1.0)).xyz;
    int resolution = int(mesh.depthMap.w);
    // In the depth square's texels (its x, y are the map's scaled by depthMap.z), z in mm.
    vec3 q = vec3((m.xy - mesh.depthMap.xy) * mesh.depthMap.z * float(resolution), m.z);
    ivec2 pixel0 = clamp(ivec2((m0.xy - mesh.depthMap.xy) * mesh.depthMap.z * float(resolution)), ivec2(0), ivec2(resolution - 1));
    int layer = mesh.info.x;   // the front of the interval holding `inside`
    for (int interval = 1; interval < mesh.info.y; ++interval) {
        int front = mesh.info.x + 2 * interval;
        if (texelFetch(clipDepthMaps, ivec3(pixel0, front), 0).r < m0.z) layer = front;  // the last front before m0
    }
    mat3 L = mat3(mesh.worldToMap);
    vec3 extent = vec3(1.0 / length(vec3(L[0][0], L[1][0], L[2][0])), 1.0 / length(vec3(L[0][1], L[1][1], L[2][1])), 1.0);
    vec2 texelMm = extent.xy / (float(resolution) * mesh.depthMap.z);
    ivec2 c = ivec2(clamp(floor(q.xy - 0.5), vec2(0.0), vec2(resolution - 2)));
    vec3 local = vec3(0.0);
    for (int n = 0; n < 8; ++n) {
        ivec3 texel = ivec3(c + ivec2(n & 1, (n >> 1) & 1), layer + (n >> 2));
        float z = texelFetch(clipDepthMaps, texel, 0).r;
        vec3 d = vec3((vec2(texel.xy) + 0.5 - q.xy) * texelMm, z - q.z);
        float w = abs(z) < 1e30 ? 1.0 / (dot(d, d) + dot(texelMm, texelMm)) : 0.0;
        local += w * octahedralDecode(texelFetch(clipNormalMaps, texel, 0).rg);
    }
    // Local -> world: worldToMap's linear part L = diag(1 / extent.x, 1 / extent.y, 1) R^T, so R n = L^T (n * extent).
    outwardWorld = dot(local, local) > 0.0 ? normalize(transpose(L) * (local * extent)) : normalize(outside - inside);
    return s;
}
