// What step V does with a voxel, from V_m: c copies V_PAO, b recomputes, a recomputes when any of its 26
// neighbours is not a (trilinear sampling of V_AO at a visible point near the cut reaches it: the seam rule)
// and is 1 otherwise (no visible sample can reach it). A recompute in a brick whose LAO cannot change (no V_o
// its rays read differs from step I's; visit_bricks.glsl) copies V_PAO instead: the same inputs give the
// same LAO, bit for bit. With AO_ONLY_WHERE_SEEN, a voxel no visible sample can read is 1 as well (below).
// Shared by the full-grid and compacted variants, and by step I, so V_PAO, V_AO and full LAO agree.
#include "bindings.glsl"
#include "visit_bricks.glsl"
#include "volume_layout.glsl"

#define DECISION_COPY 0u
#define DECISION_COMPUTE 1u
#define DECISION_UNREACHABLE 2u

layout(binding = BINDING_MASK) uniform usampler3D categoryMask;

#ifdef AO_ONLY_WHERE_SEEN
// Whether a sample the ray caster shades can read voxel v's V_AO. V_AO is read only at samples with opacity
// (shade_sample.glsl, after raycast.comp's opacity test), trilinearly, at the 8 corners of the sample's cell.
// Those corners lie, along every axis, within one voxel of each other, so all 8 lie inside the apron of the
// brick that holds any one of them (render/gpu_volume.h, bricks of seenBrickSize: a brick's value range covers
// the brick and a one-voxel apron, and a shown label marks every brick whose apron holds it). If v's own brick
// is empty (not 0 here, Renderer::updateOccupancy), the TF gives no opacity anywhere in that range, so no
// sample that reads v has opacity: no pixel depends on v's LAO, and steps I and V write 1 without a ray.
layout(binding = BINDING_SEEN_BRICKS) uniform sampler3D seenBricks;
uniform int seenBrickSize;

bool ambientSeen(ivec3 v) { return texelFetch(seenBricks, v / seenBrickSize, 0).r == 0.0; }
#endif

uint stepVDecision(ivec3 v, ivec3 size, uint brickEntry) {
    uint category = VOLUME_FETCH(categoryMask, v).r;
    if (category == CATEGORY_UNAFFECTED) return DECISION_COPY;   // (an unseen voxel's V_PAO is 1 too)
#ifdef AO_ONLY_WHERE_SEEN
    if (!ambientSeen(v)) return DECISION_UNREACHABLE;
#endif
    bool lao = (brickEntry & VISIT_LAO_CAN_CHANGE) != 0u;
    if (category == CATEGORY_AFFECTED) return lao ? DECISION_COMPUTE : DECISION_COPY;
    for (int z = -1; z <= 1; ++z)
        for (int y = -1; y <= 1; ++y)
            for (int x = -1; x <= 1; ++x) {
                ivec3 n = v + ivec3(x, y, z);
                if (any(lessThan(n, ivec3(0))) || any(greaterThanEqual(n, size))) continue;
                if (VOLUME_FETCH(categoryMask, n).r != CATEGORY_CLIPPED) return lao ? DECISION_COMPUTE : DECISION_COPY;
            }
    return DECISION_UNREACHABLE;
}

// Voxels are numbered i + size.x * (j + size.y * k), as uints in the recompute list.
ivec3 voxelFromIndex(uint index, ivec3 size) {
    uint sx = uint(size.x), sy = uint(size.y);
    return ivec3(int(index % sx), int((index / sx) % sy), int(index / (sx * sy)));
}

uint indexFromVoxel(ivec3 v, ivec3 size) { return uint(v.x) + uint(size.x) * (uint(v.y) + uint(size.y) * uint(v.z)); }

// Invocation id of a 1-D job spread over a 2-D dispatch of groups of 64 (work-group counts are limited per
// dimension; render/passes/ambient_occlusion.cpp sizes the grid).
#define LAO_GROUP_SIZE 64u
uint linearInvocation() {
    uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    return group * LAO_GROUP_SIZE + gl_LocalInvocationIndex;
}
