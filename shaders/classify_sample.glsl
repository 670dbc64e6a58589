// Classification of one volume sample: TF colour and opacity per unit length, the gradient when a mode or the
// TF needs it, and the gradient-opacity factor. One definition for the ray caster and the slab pass; the
// segment's opacity is then correctOpacity(alphaUnit, length) (transfer_function.glsl).
// Binders: VolumePiece (volume.glsl), NoDataPiece (no_data.glsl, the gradients next to no data) and
// TransferFunctionTexture (transfer_function.glsl, and labels.glsl through its LabelOverlay); no uniforms of
// its own.
#include "shading_modes.glsl"
#include "no_data.glsl"
#include "volume.glsl"
#include "transfer_function.glsl"

struct VolumeSample {
    vec3 albedo;       // TF colour
    float alphaUnit;   // opacity per tfUnitLengthMm, times the gradient-opacity factor
    vec3 gradient;     // world gradient of the value (zero when neither phong nor gradient opacity needs it)
};

// What decides whether the sample is visible: colour and opacity, and the gradient only when gradient
// opacity needs it (zero otherwise).
VolumeSample classifyOpacity(vec3 tex) {
    VolumeSample s;
    vec4 classified = classify(sampleTexel(tex));
#ifdef LABELS
    classified = withLabel(classified, labelStyleAt(tex));
#endif
    s.albedo = classified.rgb;
    s.gradient = useGradientOpacity ? gradientWorld(tex) : vec3(0.0);
    s.alphaUnit = classified.a;
    if (useGradientOpacity) s.alphaUnit *= gradientOpacityFactor(length(s.gradient));
    return s;
}

// The rest a visible sample needs for its shading: phong's gradient, where gradient opacity has not taken it.
VolumeSample withShadingGradient(VolumeSample s, vec3 tex) {
#if SHADING == SHADING_PHONG
    if (!useGradientOpacity) s.gradient = gradientWorld(tex);
#endif
    return s;
}

VolumeSample classifySample(vec3 tex) { return withShadingGradient(classifyOpacity(tex), tex); }

// Nothing there: outside the volume or inside a clip mesh.
VolumeSample emptySample() { return VolumeSample(vec3(0.0), 0.0, vec3(0.0)); }
