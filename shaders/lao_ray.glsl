// Local Ambient Occlusion of one voxel: CAO eq. 2 and 3. The one definition: step I (V_PAO) and step V
// (V_AO) run the same program (lao.comp) with a single call site, so a voxel's value depends only on V_o
// around it, bit for bit. The CPU twin is render/reference/lao_reference.cpp.
//
//   A_k(x) = 1/M * sum_{m=1..M} prod_{i=1..m-1} (1 - a_i)        (eq. 2)
//   A(x)   = 1/K * sum_{k=1..K} w_k A_k(x)                        (eq. 3)
//
// Sample i lies i * step millimetres from the voxel centre along direction k, so term M needs samples 1..M-1
// only: the farthest sample is (M - 1) * step away (render/passes/ambient_occlusion.cpp derives the dilation radius
// from this). a_i is V_o (opacity per TF unit length, trilinear, zero outside the volume) corrected to the
// step length.
//
// Compiled in (AmbientOcclusion::laoDefines), because llvmpipe pays for what a loop cannot know:
//   LAO_DIRECTIONS  K, and LAO_SAMPLES M: loops of a constant trip count need no per-step mask bookkeeping
//                   (the same arithmetic in the same order, so V_AO is the same bit for bit);
//   LAO_UNIT_STEP   defined when the step equals the TF's unit length: the correction (1 - a)^(step / unit)
//                   is then 1 - a exactly, and pow (exp2 of log2 on llvmpipe) is about a quarter of a sample.
#include "bindings.glsl"
#include "volume_layout.glsl"

layout(binding = BINDING_OPACITY) uniform sampler3D clippedOpacity;
layout(std430, binding = SSBO_LAO_DIRECTIONS) readonly buffer LaoDirections {
    vec4 laoDirections[];  // xyz: one step along direction k in texture coordinates; w: w_k / (K * M)
};
#ifndef LAO_UNIT_STEP
uniform float laoOpacityExponent;  // step / TF unit length
#endif
uniform vec3 laoTextureMargin;   // half a texel: beyond it every sample reads zero (the border; folded, the test below)

float localAmbientOcclusion(vec3 centreTex) {
    float ambient = 0.0;
    for (int k = 0; k < LAO_DIRECTIONS; ++k) {
        vec3 stepTex = laoDirections[k].xyz;
        float transmittance = 1.0;
        float sum = 0.0;
        for (int m = 1; m <= LAO_SAMPLES; ++m) {
            sum += transmittance;  // term m: the transmittance of samples 1 .. m-1
            if (m == LAO_SAMPLES) break;
            vec3 p = centreTex + float(m) * stepTex;
            // Past the volume's faces (and their half-texel margin) V_o is zero: the ray goes on with its
            // transmittance, and every later term is that transmittance. Unfolded, the zero border says so by
            // itself, and no test runs on every sample (llvmpipe pays for a branch whether or not a lane takes
            // it: 3-6 % of steps I and V); folded, the next piece lies across the border, so the sample is
            // zeroed, the same sum bit for bit.
            float a = VOLUME_SAMPLE_ZERO_BORDER(clippedOpacity, p).r;
#ifdef VOLUME_FOLD
            if (any(lessThan(p, -laoTextureMargin)) || any(greaterThan(p, 1.0 + laoTextureMargin))) a = 0.0;
#endif
#ifdef LAO_UNIT_STEP
            transmittance *= 1.0 - a;
#else
            transmittance *= pow(1.0 - a, laoOpacityExponent);
#endif
        }
        ambient += laoDirections[k].w * sum;
    }
    return ambient;
}
