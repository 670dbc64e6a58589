#version 450
// The removal report's field (plan/removal_field.h): for every voxel of a box, how many of its 9 + N clip
// samples lie inside a clip mesh, by the same rule step IV uses for the visible fraction (clip_coverage.glsl),
// so the removed volume is the complement of exactly the coverage CAO renders with.
#include "bindings.glsl"
#include "clip_coverage.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 4) in;
layout(std430, binding = SSBO_REMOVAL_COUNTS) writeonly buffer RemovalCounts { uint insideCounts[]; };
uniform ivec3 regionOrigin;      // the box of voxels this dispatch visits
uniform ivec3 regionSize;
uniform float sampleReachMm;     // the farthest any of a voxel's clip samples lies from its centre

void main() {
    ivec3 local = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(local, regionSize))) return;
    vec3 centre = vec3(regionOrigin + local);
    vec3 world = (indexToWorld * vec4(centre, 1.0)).xyz;
    uint meshes = clipMeshCount > 0 && nearAnyClipMesh(world, sampleReachMm) ? meshesWithinSampleReach(world, allClipMeshes(), sampleReachMm) : 0u;
    uint index = (uint(local.z) * uint(regionSize.y) + uint(local.y)) * uint(regionSize.x) + uint(local.x);
    insideCounts[index] = meshes != 0u ? uint(insideSampleCount(centre, meshes)) : 0u;
}
