// How much of a voxel the clip meshes cover: the sample pattern of CAO Algorithm 2 (lines 3-10), one
// definition for step IV (voxel_clip.comp: the visible fraction scales V_o) and for the removal report
// (removal_count.comp: the removed fraction is what the carve takes away). The CPU twin is
// clip::insideSampleCount (mesh/coverage.h).
// Nine samples, the centre and the eight corners of the voxel's own cell, inset (CELL_SAMPLE_HALF_WIDTH,
// clip::kCellSampleHalfWidth: the count is the covered fraction of this voxel's cell); only where they
// disagree, N more at fixed offsets in the same cell (antiAliasingOffsets, clip::antiAliasingOffsets).
// Binder: the pass sets indexToWorld and antiAliasingSamples and binds SSBO_ANTI_ALIASING; clip_test.glsl's
// binder is clip::ClipMeshSet::apply.
#include "bindings.glsl"
#include "clip_test.glsl"

layout(std430, binding = SSBO_ANTI_ALIASING) readonly buffer AntiAliasing { vec4 antiAliasingOffsets[]; };
uniform mat4 indexToWorld;
uniform int antiAliasingSamples;   // N
#define CELL_SAMPLE_HALF_WIDTH 0.484375

// Inside one of the meshes of the set `meshes` (bit i: mesh i); with allClipMeshes(), insideAnyClipMesh.
bool clippedAtIndex(vec3 index, uint meshes) { return clipMeshHoldingAmong(meshes, (indexToWorld * vec4(index, 1.0)).xyz) >= 0; }

// Of the 9 + N samples of voxel `centre` (index coordinates), how many lie inside a mesh of `meshes`. The
// N extra samples are taken only when the first nine disagree, so the result is 0 or 9 + N wherever they
// agree. A caller that knows some meshes cannot hold any sample of this voxel may leave them out (step IV
// with the dilated maps); the count is the same.
int insideSampleCount(vec3 centre, uint meshes) {
    int inside = clippedAtIndex(centre, meshes) ? 1 : 0;
    for (int c = 0; c < 8; ++c) {
        const float h = CELL_SAMPLE_HALF_WIDTH;
        vec3 corner = vec3((c & 1) != 0 ? h : -h, (c & 2) != 0 ? h : -h, (c & 4) != 0 ? h : -h);
        inside += clippedAtIndex(centre + corner, meshes) ? 1 : 0;
    }
    if (inside == 0) return 0;
    if (inside == 9) return 9 + antiAliasingSamples;
    for (int s = 0; s < antiAliasingSamples; ++s) inside += clippedAtIndex(centre + antiAliasingOffsets[s].xyz, meshes) ? 1 : 0;
    return inside;
}

// ... inside any mesh.
int insideSampleCount(vec3 centre) { return insideSampleCount(centre, allClipMeshes()); }

// Of the meshes `meshes`, those a clip sample of the voxel centred at `centreWorld` can lie in: every sample
// lies within `sampleReachMm` of the centre, so a mesh whose depth box (clip_test.glsl nearDepthBox) is
// farther away holds none of them and leaving it out changes no count. All of `meshes` when the depth-box
// tests are off.
uint meshesWithinSampleReach(vec3 centreWorld, uint meshes, float sampleReachMm) {
    if (!clipDepthBoxTests) return meshes;
    for (int i = 0; i < clipMeshCount; ++i)
        if ((meshes & (1u << uint(i))) != 0u && !nearDepthBox(i, centreWorld, sampleReachMm)) meshes &= ~(1u << uint(i));
    return meshes;
}
