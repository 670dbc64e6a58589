// What step V does with a voxel, from V_m: c copies V_PAO, b recomputes, a recomputes when any of its 26
// neighbours is not a (trilinear sampling of V_AO at a visible point near the cut reaches it: the seam rule)
// and is 1 otherwise (no visible sample can reach it). Shared by the full-grid and compacted variants, and
// mirrored by render/reference/lao_reference.cpp.
#include "bindings.glsl"

#define DECISION_COPY 0u
#define DECISION_COMPUTE 1u
#define DECISION_UNREACHABLE 2u

layout(binding = BINDING_MASK) uniform usampler3D categoryMask;

uint stepVDecision(ivec3 v, ivec3 size) {
    uint category = texelFetch(categoryMask, v, 0).r;
    if (category == CATEGORY_UNAFFECTED) return DECISION_COPY;
    if (category == CATEGORY_AFFECTED) return DECISION_COMPUTE;
    for (int z = -1; z <= 1; ++z)
        for (int y = -1; y <= 1; ++y)
            for (int x = -1; x <= 1; ++x) {
                ivec3 n = v + ivec3(x, y, z);
                if (any(lessThan(n, ivec3(0))) || any(greaterThanEqual(n, size))) continue;
                if (texelFetch(categoryMask, n, 0).r != CATEGORY_CLIPPED) return DECISION_COMPUTE;
            }
    return DECISION_UNREACHABLE;
}

// Voxels are numbered i + size.x * (j + size.y * k), as uints in the recompute list.
ivec3 voxelFromIndex(uint index, ivec3 size) {
    uint sx = uint(size.x), sy = uint(size.y);
    return ivec3(int(index % sx), int((index / sx) % sy), int(index / (sx * sy)));
}

uint indexFromVoxel(ivec3 v, ivec3 size) { return uint(v.x) + uint(size.x) * (uint(v.y) + uint(size.y) * uint(v.z)); }

// The box of voxels a step V dispatch visits (render/ambient_occlusion.cpp); invocation `id` takes the voxel
// numbered `id` inside it. Step I and full LAO visit the whole volume.
uniform ivec3 regionOrigin;
uniform ivec3 regionSize;
bool regionVoxel(uint id, out ivec3 v) {
    // In uint: a box of more than 2^31 voxels must not wrap (AmbientOcclusion refuses more than 2^32 - 1).
    if (id >= uint(regionSize.x) * uint(regionSize.y) * uint(regionSize.z)) return false;
    v = regionOrigin + voxelFromIndex(id, regionSize);
    return true;
}

// Invocation id of a 1-D job spread over a 2-D dispatch of groups of 64 (work-group counts are limited per
// dimension; render/ambient_occlusion.cpp sizes the grid).
#define LAO_GROUP_SIZE 64u
uint linearInvocation() {
    uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    return group * LAO_GROUP_SIZE + gl_LocalInvocationIndex;
}
