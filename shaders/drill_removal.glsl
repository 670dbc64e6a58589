// The drill's accumulated removal (plan/removal_volume.h): one more input to classification, so every pass
// that classifies samples sees it (binder: render/removal_texture.h, through TransferFunctionTexture).
// A sample keeps (1 - drilled fraction) of its opacity, the fraction trilinear between voxel centres; step IV
// scales a voxel's V_o by its own voxel's (voxel_clip.comp), as it scales by the meshes' visible fraction.
#include "bindings.glsl"
#include "volume_layout.glsl"

#ifdef DRILL_REMOVAL
layout(binding = BINDING_DRILLED_FRACTION) uniform sampler3D drilledFraction;
layout(binding = BINDING_DRILL_NEAR_BRICKS) uniform usampler3D drillNearBricks;
float drillRetainedAt(vec3 tex) { return 1.0 - VOLUME_SAMPLE(drilledFraction, tex).r; }
float drillRetainedAtVoxel(ivec3 v) { return 1.0 - VOLUME_FETCH(drilledFraction, v).r; }
// Whether a drilled voxel lies within the dilation radius of voxel v's brick (4^3 voxels): its LAO may differ
// from V_PAO, so step IV makes it category b (docs/subsystems.md, "Drilling").
bool nearDrilledVoxel(ivec3 v) { return texelFetch(drillNearBricks, v / 4, 0).r != 0u; }
#else
float drillRetainedAt(vec3 tex) { return 1.0; }
float drillRetainedAtVoxel(ivec3 v) { return 1.0; }
bool nearDrilledVoxel(ivec3 v) { return false; }
#endif
