#version 450
// Step V, compacted variant, first half: over the visited bricks (visit_bricks.glsl), take every voxel's
// decision (lao_common.glsl); write the copies and
// the unreachable ones directly and append the voxels to recompute to a list (atomic append). A second
// one-invocation pass turns the count into an indirect dispatch of lao.comp in LIST mode. The list holds the
// voxels of one chunk of the visited bricks at a time (AmbientOcclusion::listChunkBricks_): with countChunks, this
// pass appends the first chunk's voxels and counts each later chunk's instead, in listVoxels[chunkCountsAt + chunk]
// (a chunk's list is built when step V reaches it: the decisions, taken once more there, are the same).
#include "bindings.glsl"
#include "lao_common.glsl"

layout(local_size_x = 64) in;
layout(r16, binding = IMAGE_AMBIENT) uniform writeonly image3D ambientOut;
layout(binding = BINDING_PRECOMPUTED_AO) uniform sampler3D precomputedAmbient;
layout(std430, binding = SSBO_RECOMPUTE_LIST) buffer RecomputeList { uint listCount; uint computedCount; uint listVoxels[]; };
layout(std430, binding = SSBO_DISPATCH) buffer Dispatch { uvec3 dispatchSize; };

uniform ivec3 volumeSize;
uniform int prepareDispatch;   // 1: the single invocation that sizes the indirect dispatch
uniform uint maxGroupsX;
uniform uint countChunks;      // 0: append to the list; else the bricks of a chunk: count per chunk after the first
uniform uint chunkCountsAt;    // with countChunks: where in listVoxels the counts begin (past a chunk's voxels)

void main() {
    if (prepareDispatch == 1) {
        // workGroupGrid's grid (render/model/worker_deal.h): as few rows as maxGroupsX allows, each as narrow as it
        // can be, so fewer groups than rows lie past the list and llvmpipe's per-thread runs split the list.
        uint groups = (listCount + 63u) / 64u;
        uint rows = (groups + maxGroupsX - 1u) / maxGroupsX;
        uint x = groups == 0u ? 1u : (groups + rows - 1u) / rows;
        dispatchSize = uvec3(x, groups == 0u ? 0u : (groups + x - 1u) / x, 1u);
        return;
    }
    ivec3 v;
    uint entry;
    if (!brickVoxel(volumeSize, v, entry)) return;
    uint decision = stepVDecision(v, volumeSize, entry);
    if (decision == DECISION_COPY) {
        VOLUME_STORE(ambientOut, v, VOLUME_FETCH(precomputedAmbient, v));
    } else if (decision == DECISION_UNREACHABLE) {
        VOLUME_STORE(ambientOut, v, vec4(1.0));
    } else if (countChunks != 0u && visitSlot() >= countChunks) {
        atomicAdd(listVoxels[chunkCountsAt + visitSlot() / countChunks], 1u);
    } else {
        listVoxels[atomicAdd(listCount, 1u)] = indexFromVoxel(v, volumeSize);
    }
}
