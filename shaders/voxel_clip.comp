#version 450
// Step IV: anti-aliased shadow-test clipping of every voxel of a list of bricks (CAO Algorithm 2), writing the clipped opacity
// V_o and the category mask V_m. Nine samples (the centre and the eight corners one voxel step away along
// the diagonals); where they disagree, N more at fixed offsets in [-1, 1]^3 and V_o is scaled by the visible
// fraction (line 10). Category: a (clipped) when no sample is visible; otherwise b (affected) when the
// voxel centre lies in a dilated shape, else c (unaffected). The LAO baseline (and step I) sets
// testDilation = false: every visible voxel is b.
#include "bindings.glsl"
#include "no_data.glsl"
#include "transfer_function.glsl"
#include "clip_coverage.glsl"
#include "visit_bricks.glsl"
#include "volume_layout.glsl"

layout(local_size_x = 64) in;   // one brick (visit_bricks.glsl)
layout(binding = BINDING_VOLUME) uniform sampler3D volumeData;
layout(r16, binding = IMAGE_OPACITY) uniform writeonly image3D clippedOpacityOut;
layout(r8ui, binding = IMAGE_MASK) uniform writeonly uimage3D maskOut;
uniform ivec3 volumeSize;
uniform bool testDilation;
uniform mat3 gradientToWorld;      // index gradient -> world gradient (value per mm)
uniform float sampleReachMm;       // the farthest any of a voxel's clip samples lies from its centre
uniform bool applyDrill;           // the drilled removal scales V_o (off in step I: V_PAO is the undrilled LAO)

// TF_o of Algorithm 2: the opacity per unit length of the voxel's own value (no interpolation), with the
// gradient-opacity factor from central differences when the TF has one (one-sided next to no data).
float voxelOpacity(ivec3 v) {
    float alpha = classify(VOLUME_FETCH(volumeData, v).r).a;
#ifdef LABELS
    alpha = withLabel(vec4(0.0, 0.0, 0.0, alpha), labelStyleAtVoxel(v)).a;
#endif
    if (useGradientOpacity) {
        ivec3 hi = volumeSize - 1;
        vec3 minus = vec3(VOLUME_FETCH(volumeData, max(v - ivec3(1, 0, 0), 0)).r, VOLUME_FETCH(volumeData, max(v - ivec3(0, 1, 0), 0)).r,
                          VOLUME_FETCH(volumeData, max(v - ivec3(0, 0, 1), 0)).r);
        vec3 plus = vec3(VOLUME_FETCH(volumeData, min(v + ivec3(1, 0, 0), hi)).r, VOLUME_FETCH(volumeData, min(v + ivec3(0, 1, 0), hi)).r,
                         VOLUME_FETCH(volumeData, min(v + ivec3(0, 0, 1), hi)).r);
        vec3 d = differencesAcross(minus, vec3(VOLUME_FETCH(volumeData, v).r), plus);
        alpha *= gradientOpacityFactor(length(gradientToWorld * (0.5 * d)));
    }
    return alpha;
}

void main() {
    ivec3 v;
    uint entry;
    if (!brickVoxel(volumeSize, v, entry)) return;
    vec3 centre = vec3(v);

    vec3 centreWorld = (indexToWorld * vec4(centre, 1.0)).xyz;
    // The meshes a clip sample of this voxel can lie in.
    //  - With the dilated maps (cao): those whose dilated shape holds the centre. A dilated shape holds every
    //    point within R of a point its depth maps call inside (step III; R = reach + 2 cell diagonals,
    //    render/passes/ambient_occlusion.cpp), and every clip sample lies within a cell diagonal of the centre, so a
    //    mesh whose dilated shape misses the centre holds none of the samples: leaving it out changes no
    //    count. (The visited bricks lie at the meshes, so no far test first: the dilated lookup answers
    //    "outside" for a far centre as quickly.)
    //  - Without them (lao, step I, which visit every voxel): every mesh near the centre. Far from every
    //    mesh's map box every sample is visible: the full test would conclude exactly this, so skip it.
    uint meshes = 0u;
    if (testDilation) {
        for (int i = 0; i < clipMeshCount; ++i)
            if (insideMeshMaps(i, centreWorld, true)) meshes |= 1u << uint(i);
    } else if (clipMeshCount > 0 && nearAnyClipMesh(centreWorld, sampleReachMm)) {
        meshes = allClipMeshes();
    }
    int samples = 9 + antiAliasingSamples;
#if defined(DEEP_INSIDE_MESH)
    // This dispatch's bricks have every clip sample inside one mesh (render/mesh_voxel_box.h
    // bricksDeepInsideMeshes), which the test below would find: the count is 9 + N, compiled in.
    int visible = 0;
#elif defined(BEYOND_SAMPLE_REACH)
    // This dispatch's bricks lie beyond every mesh's sample reach (render/mesh_voxel_box.h
    // bricksWithinSampleReach), where the test below finds no mesh to test: the count is 0, compiled out, as
    // llvmpipe runs a branch's code under a lane mask whether or not a lane takes it.
    int visible = samples;
#else
    // Of those, the meshes a clip sample can lie inside (a dilated shape reaches much farther than its mesh's
    // depth box: most of the voxels it holds lie in the dilation's shell, where no sample is inside).
    uint sampled = meshesWithinSampleReach(centreWorld, meshes, sampleReachMm);
    int visible = samples - (sampled != 0u ? insideSampleCount(centre, sampled) : 0);
#endif
    float unclipped = voxelOpacity(v);
    // The drilled removal keeps (1 - drilled fraction) of the voxel (plan/removal_volume.h); with the meshes'
    // visible fraction it multiplies: removed = 1 - (1 - meshes)(1 - drilled).
    float retained = applyDrill ? drillRetainedAtVoxel(v) : 1.0;
    float opacity = unclipped * retained;
    if (visible == 0) {
        opacity = 0.0;
    } else if (visible < samples) {
        opacity *= float(visible) / float(samples);  // line 10: scaled by the visible fraction
    }
    // Whether V_o here may differ from step I's (unclipped, undrilled) value: step V recomputes LAO only within
    // reach of such voxels (visit_bricks.glsl).
    if ((visible < samples || retained < 1.0) && unclipped > 0.0) markOpacityChanged();
    // b: the centre lies in a dilated shape (with testDilation), i.e. some mesh is left in `meshes`, or a
    // drilled voxel lies within the dilation radius (its brick's flag).
    bool nearDrill = applyDrill && nearDrilledVoxel(v);
    uint category = (visible == 0 || retained == 0.0) ? CATEGORY_CLIPPED
                    : (testDilation && meshes == 0u && !nearDrill) ? CATEGORY_UNAFFECTED
                                                                   : CATEGORY_AFFECTED;
    VOLUME_STORE(clippedOpacityOut, v, vec4(opacity));
    VOLUME_STORE(maskOut, v, uvec4(category));
}
