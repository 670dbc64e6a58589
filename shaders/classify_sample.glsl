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
#ifdef LABELS
    bool labelShapes;     // the label, not the TF, gives the opacity: phong lights it by the label's gradient
#endif
};

// What decides whether the sample is visible: colour and opacity, and the gradient only when gradient
// opacity needs it (zero otherwise).
VolumeSample classifyOpacity(vec3 tex) {
    VolumeSample s;
    vec4 classified = classify(sampleTexel(tex));
#ifdef LABELS
    LabelSample label = labelAt(tex);
    // Phong lights a label's surface by the label's own gradient where the label makes the opacity: the data
    // inside a structure may be homogeneous, and its gradient noise.
    s.labelShapes = label.alpha > classified.a;
    classified = withLabel(classified, label);
#endif
    s.albedo = classified.rgb;
    s.gradient = useGradientOpacity ? gradientWorld(tex) : vec3(0.0);
    s.alphaUnit = classified.a * drillRetainedAt(tex);
    if (useGradientOpacity) s.alphaUnit *= gradientOpacityFactor(length(s.gradient));
    return s;
}

// The rest a visible sample needs for its shading: phong's gradient, where gradient opacity has not taken it.
VolumeSample withShadingGradient(VolumeSample s, vec3 tex) {
#if SHADING == SHADING_PHONG
    if (!useGradientOpacity) s.gradient = gradientWorld(tex);
#ifdef LABELS
    if (s.labelShapes) s.gradient = gradientToWorld * labelShownGradient(tex, texelSize);
#endif
#endif
    return s;
}

VolumeSample classifySample(vec3 tex) { return withShadingGradient(classifyOpacity(tex), tex); }

// Nothing there: outside the volume or inside a clip mesh.
VolumeSample emptySample() {
    VolumeSample s;
    s.albedo = vec3(0.0);
    s.alphaUnit = 0.0;
    s.gradient = vec3(0.0);
#ifdef LABELS
    s.labelShapes = false;
#endif
    return s;
}
