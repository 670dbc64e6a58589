#version 450
// Step IV: anti-aliased shadow-test clipping of every voxel in a box (CAO Algorithm 2), writing the clipped opacity
// V_o and the category mask V_m. Nine samples (the centre and the eight corners one voxel step away along
// the diagonals); where they disagree, N more at fixed offsets in [-1, 1]^3 and V_o is scaled by the visible
// fraction (line 10). Category: a (clipped) when no sample is visible; otherwise b (affected) when the
// voxel centre lies in a dilated shape, else c (unaffected). The LAO baseline (and step I) sets
// testDilation = false: every visible voxel is b.
#include "bindings.glsl"
#include "transfer_function.glsl"
#include "clip_coverage.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 4) in;
layout(binding = BINDING_VOLUME) uniform sampler3D volumeData;
layout(r16, binding = IMAGE_OPACITY) uniform writeonly image3D clippedOpacityOut;
layout(r8ui, binding = IMAGE_MASK) uniform writeonly uimage3D maskOut;
uniform ivec3 volumeSize;
uniform ivec3 regionOrigin;        // the box of voxels this dispatch visits (render/ambient_occlusion.cpp)
uniform ivec3 regionSize;
uniform bool testDilation;
uniform mat3 gradientToWorld;      // index gradient -> world gradient (value per mm)
uniform float sampleReachMm;       // the farthest any of a voxel's clip samples lies from its centre

// TF_o of Algorithm 2: the opacity per unit length of the voxel's own value (no interpolation), with the
// gradient-opacity factor from central differences when the TF has one.
float voxelOpacity(ivec3 v) {
    float alpha = classify(texelFetch(volumeData, v, 0).r).a;
#ifdef LABELS
    alpha = withLabel(vec4(0.0, 0.0, 0.0, alpha), labelStyleAtVoxel(v)).a;
#endif
    if (useGradientOpacity) {
        ivec3 hi = volumeSize - 1;
        vec3 d = vec3(texelFetch(volumeData, min(v + ivec3(1, 0, 0), hi), 0).r - texelFetch(volumeData, max(v - ivec3(1, 0, 0), 0), 0).r,
                      texelFetch(volumeData, min(v + ivec3(0, 1, 0), hi), 0).r - texelFetch(volumeData, max(v - ivec3(0, 1, 0), 0), 0).r,
                      texelFetch(volumeData, min(v + ivec3(0, 0, 1), hi), 0).r - texelFetch(volumeData, max(v - ivec3(0, 0, 1), 0), 0).r);
        alpha *= gradientOpacityFactor(length(gradientToWorld * (0.5 * d)));
    }
    return alpha;
}

void main() {
    if (any(greaterThanEqual(ivec3(gl_GlobalInvocationID), regionSize))) return;
    ivec3 v = regionOrigin + ivec3(gl_GlobalInvocationID);
    vec3 centre = vec3(v);

    vec3 centreWorld = (indexToWorld * vec4(centre, 1.0)).xyz;
    // Far from every mesh's map box, every sample is visible and the centre is in no dilated shape: the
    // full test would conclude exactly this, so skip it.
    bool near = clipMeshCount > 0 && nearAnyClipMesh(centreWorld, sampleReachMm);
    int samples = 9 + antiAliasingSamples;
    int visible = samples - (near ? insideSampleCount(centre) : 0);
    float opacity = voxelOpacity(v);
    if (visible == 0) {
        opacity = 0.0;
    } else if (visible < samples) {
        opacity *= float(visible) / float(samples);  // line 10: scaled by the visible fraction
    }
    uint category = visible == 0 ? CATEGORY_CLIPPED
                    : (testDilation && !(near && insideAnyDilatedMesh(centreWorld))) ? CATEGORY_UNAFFECTED
                                                                                     : CATEGORY_AFFECTED;
    imageStore(clippedOpacityOut, v, vec4(opacity));
    imageStore(maskOut, v, uvec4(category));
}
