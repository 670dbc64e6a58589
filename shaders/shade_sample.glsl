// The colour of a classified volume sample in each shading mode (shading_modes.glsl): one definition for the
// ray caster and the slab pass. The slab pass multiplies it by the light its cone lets through (channel
// "all" in dos, channel "geometry" in lao/cao: docs/subsystems.md "Tubes in the slab pass").
// Binder: SampleShadingPiece (render/shader_pieces.h): SHADING, ambientScale and V_AO.
#include "bindings.glsl"
#include "shading_modes.glsl"
#include "classify_sample.glsl"
#include "phong.glsl"
#include "volume_layout.glsl"

#if SHADING == SHADING_LAO || SHADING == SHADING_CAO
layout(binding = BINDING_AMBIENT) uniform sampler3D ambientOcclusion;   // V_AO
uniform float ambientScale;          // the factor applied to V_AO
#endif

// toEye: unit, from the sample towards the eye; tex: the sample's texture coordinate.
vec3 shadeSample(VolumeSample s, vec3 tex, vec3 toEye) {
#if SHADING == SHADING_PHONG
    return shadePhong(s.albedo, s.gradient, toEye, 1.0);
#elif SHADING == SHADING_LAO || SHADING == SHADING_CAO
    // CAO step VI: the colour lit by ambient light only, V_AO the fraction that reaches the sample, scaled so
    // an open flat surface (half its rays blocked, A = 0.5) shows the TF colour.
    return s.albedo * ambientScale * VOLUME_SAMPLE(ambientOcclusion, tex).r;
#else
    return s.albedo;
#endif
}

#ifdef CUT_FACES
// A cut face (Weiskopf, Engel and Ertl 2003, sec. 5): the tissue seen through a clip boundary is lit as the
// clip surface, not as the data. `faceNormal` is the cut face's unit world normal (out of the tissue, into
// the clipped region); `depthMm` how far behind the face the sample lies, measured along it (1e30: no face in
// front of it); `opacityBehindFace` the opacity the ray has gathered since the face.
//  - phong: the normal is the face normal, blended into the volume's gradient normal only once the ray has
//    gathered cutFaceNormalOpacity of its opacity behind the face (fading out by full opacity) or passed half
//    of cutFaceNormalDepthMm (fading out by all of it): the gradient of homogeneous tissue is noise, and even
//    a small share of it in the blend speckles the face, so the fade comes late;
//  - lao/cao: shadeSample's rule, V_AO at the sample; the face's own sample lies on the face (raycast.comp),
//    so the face reads V_AO at the boundary in every pixel, not wherever the lattice put its first sample.
//    (Reading it 1 or 2 mm deeper along the normal instead was measured: 4 % and 2 % less roughness on the
//    uniform bench scene, against 38 % for the sample on the face; not worth a rule of its own.) CAO and full
//    LAO shade through the same code, so CAO == LAO holds for the images as it does for V_AO.
// Beyond both depths the result is shadeSample's, bit for bit, and the cost is one select: no branch, so
// llvmpipe does not pay for a second shading path on every sample.
uniform float cutFaceNormalDepthMm;
uniform float cutFaceNormalOpacity;

vec3 shadeCutFaceSample(VolumeSample s, vec3 tex, vec3 toEye, vec3 faceNormal, float depthMm, float opacityBehindFace) {
#if SHADING == SHADING_PHONG
    float faceWeight = (1.0 - smoothstep(cutFaceNormalOpacity, 1.0, opacityBehindFace)) *
                       (1.0 - smoothstep(0.5 * cutFaceNormalDepthMm, cutFaceNormalDepthMm, depthMm));
    float magnitude = length(s.gradient);
    vec3 volumeNormal = magnitude < 1e-6 ? faceNormal : -s.gradient / magnitude;
    volumeNormal = dot(volumeNormal, faceNormal) < 0.0 ? -volumeNormal : volumeNormal;  // the side the face shows
    // shadePhong takes minus the normal as its gradient
    vec3 gradient = faceWeight > 0.0 ? -normalize(mix(volumeNormal, faceNormal, faceWeight)) : s.gradient;
    return shadePhong(s.albedo, gradient, toEye, 1.0);
#else
    return shadeSample(s, tex, toEye);
#endif
}
#endif
