// The voxels steps IV and V visit: a list of bricks of 4^3 voxels (render/mesh_voxel_box.h, kVisitBrickSize),
// one work group of 64 invocations per brick, the work groups numbered over a 2-D dispatch (work-group
// counts are limited per dimension; render/passes/ambient_occlusion.cpp sizes the grid). Step I and full LAO list
// every brick; a CAO update the bricks the meshes' dilated boxes reach, now or at the last update.
// Each entry also carries two flags (render/passes/ambient_occlusion.cpp, "Which LAO can change"):
//   VISIT_OPACITY_CHANGED  set by step IV when a voxel of the brick gets a clipped V_o unlike its unclipped one;
//   VISIT_LAO_CAN_CHANGE   set (on the CPU, between steps IV and V) when a brick holding such a voxel lies
//                          within the LAO reach plus the trilinear footprint: elsewhere every V_o a voxel's LAO
//                          reads is unclipped, so its LAO is V_PAO bit for bit and step V copies it.
// Binder: AmbientOcclusion (visitBrickCount, brickGrid, the list on SSBO_VISIT_BRICKS).
#include "bindings.glsl"

#define BRICK_SIZE 4
#define BRICK_VOXELS 64u
#define VISIT_BRICK_NUMBER 0x3FFFFFFFu
#define VISIT_OPACITY_CHANGED 0x40000000u
#define VISIT_LAO_CAN_CHANGE 0x80000000u

layout(std430, binding = SSBO_VISIT_BRICKS) buffer VisitBricks {
    uint visitBricks[];   // brick number bx + grid.x * (by + grid.y * bz) | flags
};
uniform uint visitBrickCount;
uniform ivec3 brickGrid;        // bricks per axis
uniform uint visitSlotOffset;   // the slot of this dispatch's first work group (step IV in slices; else 0)

// This invocation's slot in the list (its work group).
uint visitSlot() { return visitSlotOffset + gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x; }

// This invocation's voxel and its brick's list entry, or false when the slot is past the list or the voxel
// past the grid's upper faces (partial bricks). Needs a work group of BRICK_VOXELS invocations.
bool brickVoxel(ivec3 volumeSize, out ivec3 v, out uint entry) {
    uint slot = visitSlot();
    if (slot >= visitBrickCount) return false;
    entry = visitBricks[slot];
    uint b = entry & VISIT_BRICK_NUMBER;
    uint gx = uint(brickGrid.x), gy = uint(brickGrid.y);
    ivec3 brick = ivec3(int(b % gx), int((b / gx) % gy), int(b / (gx * gy)));
    uint l = gl_LocalInvocationIndex;
    v = BRICK_SIZE * brick + ivec3(int(l & 3u), int((l >> 2) & 3u), int(l >> 4));
    return all(lessThan(v, volumeSize));
}

// Step IV: a voxel of this invocation's brick has a V_o unlike its unclipped one.
void markOpacityChanged() { atomicOr(visitBricks[visitSlot()], VISIT_OPACITY_CHANGED); }
