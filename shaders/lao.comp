#version 450
// Steps I and V: LAO per voxel (lao_ray.glsl). One program for both so V_PAO and V_AO agree bit for bit.
//   mode GRID: one invocation per voxel of the visited bricks (visit_bricks.glsl); the decision (lao_common.glsl) is taken
//              here, so skipped voxels cost a mask read and a copy ("full-grid dispatch with early exit").
//   mode LIST: one invocation per entry of the recompute list built by lao_compact.comp (indirect dispatch).
// Step I runs GRID over a mask that marks every voxel b, writing V_PAO.
#include "bindings.glsl"
#include "lao_common.glsl"
#include "lao_ray.glsl"

#define MODE_GRID 0
#define MODE_LIST 1

layout(local_size_x = 64) in;
layout(r16, binding = IMAGE_AMBIENT) uniform writeonly image3D ambientOut;
layout(binding = BINDING_PRECOMPUTED_AO) uniform sampler3D precomputedAmbient;
layout(std430, binding = SSBO_RECOMPUTE_LIST) buffer RecomputeList { uint listCount; uint computedCount; uint listVoxels[]; };

uniform int laoMode;
uniform ivec3 volumeSize;
uniform uint listOffset;   // mode LIST: the first list entry of this dispatch (step V in slices)

void main() {
    uint id = linearInvocation();
    ivec3 v;
    if (laoMode == MODE_LIST) {
        id += listOffset;
        if (id >= listCount) return;
        v = voxelFromIndex(listVoxels[id], volumeSize);
    } else {
        uint entry;
        if (!brickVoxel(volumeSize, v, entry)) return;
        uint decision = stepVDecision(v, volumeSize, entry);
        if (decision == DECISION_COPY) {
            VOLUME_STORE(ambientOut, v, VOLUME_FETCH(precomputedAmbient, v));
            return;
        }
        if (decision == DECISION_UNREACHABLE) {
            VOLUME_STORE(ambientOut, v, vec4(1.0));
            return;
        }
    }
    // The single call site of the LAO ray.
    atomicAdd(computedCount, 1u);
    float ambient = localAmbientOcclusion((vec3(v) + 0.5) / vec3(volumeSize));
    VOLUME_STORE(ambientOut, v, vec4(ambient));
}
