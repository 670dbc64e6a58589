// The colour of a classified volume sample in each shading mode (shading_modes.glsl): one definition for the
// ray caster and the slab pass. The slab pass multiplies it by the light its cone lets through (channel
// "all" in dos, channel "geometry" in lao/cao: DESIGN.md "Tubes and DOS").
// Binder: SampleShadingPiece (render/shader_pieces.h): SHADING, ambientScale and V_AO.
#include "bindings.glsl"
#include "shading_modes.glsl"
#include "classify_sample.glsl"
#include "phong.glsl"

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
    return s.albedo * ambientScale * texture(ambientOcclusion, tex).r;
#else
    return s.albedo;
#endif
}
