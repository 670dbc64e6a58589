// Shadow-test clipping (CAO section 3.2, Algorithm 2 lines 17-27): one definition of "is this point inside a
// clip mesh" for every pass (step IV, step VI, the DOS slab pass), looping over the active meshes — no copy
// per mesh count. Each mesh has a clipping camera (orthographic, attached to the mesh: a rigid motion changes
// only worldToMap) and depth maps rendered once per geometry: interval 1 = (front 1, back 1), and for concave
// meshes interval 2 = (front 2, back 2) from depth peeling. Empty pixels hold +inf (front) / -inf (back).
// The dilated maps hold the same intervals grown by the LAO reach (step III). Lookups use the nearest map
// pixel, the rule clip/clip_mesh_set.cpp's dilation radius derivation assumes.
#include "bindings.glsl"

#define MAX_CLIP_MESHES 16

struct ClipMeshGpu {
    mat4 worldToMap;   // world mm -> (map x, map y in [0,1], depth along the camera in mm)
    ivec4 info;        // x: first layer in the map arrays, y: intervals (1 or 2), z: map resolution,
                       // w: 1 when the mesh also clips tubes
    vec4 mapBox;       // the camera's map box in its own frame: x the map side in mm, y and z the depth
                       // range (local z, mm) holding every finite map value, w a slack for float rounding.
                       // Outside the box no map answers "inside".
};

// A uniform block, not a storage buffer: the array is small and every invocation reads the same entries,
// which llvmpipe then loads once per SIMD group instead of gathering per lane.
layout(std140, binding = UBO_CLIP_MESHES) uniform ClipMeshes { ClipMeshGpu clipMeshes[MAX_CLIP_MESHES]; };
layout(binding = BINDING_CLIP_DEPTH) uniform sampler2DArray clipDepthMaps;
layout(binding = BINDING_CLIP_DILATED) uniform sampler2DArray clipDilatedMaps;
uniform int clipMeshCount;

// Point `world` inside the interval(s) of mesh `i` in maps `maps` (depth or dilated).
bool insideMeshMaps(int i, vec3 world, bool dilated) {
    ClipMeshGpu mesh = clipMeshes[i];
    vec3 m = (mesh.worldToMap * vec4(world, 1.0)).xyz;
    if (any(lessThan(m.xy, vec2(0.0))) || any(greaterThanEqual(m.xy, vec2(1.0)))) return false;
    ivec2 pixel = ivec2(m.xy * float(mesh.info.z));
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

// Clipped: inside at least one mesh (section 3.6: union of clipped regions).
bool insideAnyClipMesh(vec3 world) {
    for (int i = 0; i < clipMeshCount; ++i)
        if (insideMeshMaps(i, world, false)) return true;
    return false;
}

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
