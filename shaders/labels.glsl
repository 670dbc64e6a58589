// Label volumes in the classification (compiled in with LABELS only; a scene without labels has none of
// this). Labels are ids on the scan grid (the scene's label maps resampled by nearest label, never
// interpolated between ids: base/label_map.h); each id has a style, rgb and an opacity per unit length, 0
// when the label is not shown. A shown label replaces the sample's TF colour by its own and raises its
// opacity to at least the label's:
//     classified' = (rgb_label, max(alpha_TF, alpha_label))     where alpha_label > 0
// so a structure shows in its colour on a cut face and inside clear tissue alike. Step IV classifies each
// voxel centre by this rule (labelStyleAtVoxel), so the AO modes see the labels' opacity too. The ray
// caster reads the shown labels smoothed instead (labelAt: render/label_overlay.h's label field, each voxel's
// shown indicator, colour and opacity through a Gaussian of 0.75 voxels, filtered trilinearly): a label's
// surface is where its smoothed indicator is one half, a surface, not the staircase of its voxels' cells.
// Binder: render/label_overlay.h (LabelOverlay::apply, through TransferFunctionTexture::apply).
#include "bindings.glsl"
#include "volume_layout.glsl"

#ifdef LABELS
layout(binding = BINDING_LABEL_IDS) uniform usampler3D labelIds;
layout(binding = BINDING_LABEL_STYLES) uniform sampler1D labelStyles;

vec4 labelStyleAtVoxel(ivec3 voxel) { return texelFetch(labelStyles, int(VOLUME_FETCH(labelIds, voxel).r), 0); }

layout(binding = BINDING_LABEL_FIELD) uniform sampler3D labelField;     // smoothed (rgb * shown, shown)
layout(binding = BINDING_LABEL_OPACITY) uniform sampler3D labelOpacity; // smoothed opacity * shown

struct LabelSample {
    vec3 rgb;       // the shown labels' colour (their blend where two meet)
    float alpha;    // their opacity inside the label's surface, 0 outside
    float edge;     // 0 outside the surface, 1 inside: the smoothed shown share through a narrow smoothstep
};

// The surface is where the smoothed shown share is one half; the narrow smoothstep across it keeps the
// surface crisp and still sampled without aliasing at the ray step.
LabelSample labelAt(vec3 tex) {
    vec4 f = VOLUME_SAMPLE(labelField, tex);
    float alpha = VOLUME_SAMPLE(labelOpacity, tex).r;
    float edge = smoothstep(0.4, 0.6, f.a);
    return LabelSample(f.a > 0.0 ? f.rgb / f.a : vec3(0.0), f.a > 0.0 ? alpha / f.a * edge : 0.0, edge);
}

// d shown / d voxel index by central differences (the label surface's inward normal, for phong).
vec3 labelShownGradient(vec3 tex, vec3 texel) {
    return 0.5 * vec3(VOLUME_SAMPLE(labelField, tex + vec3(texel.x, 0, 0)).a - VOLUME_SAMPLE(labelField, tex - vec3(texel.x, 0, 0)).a,
                      VOLUME_SAMPLE(labelField, tex + vec3(0, texel.y, 0)).a - VOLUME_SAMPLE(labelField, tex - vec3(0, texel.y, 0)).a,
                      VOLUME_SAMPLE(labelField, tex + vec3(0, 0, texel.z)).a - VOLUME_SAMPLE(labelField, tex - vec3(0, 0, texel.z)).a);
}

vec4 withLabel(vec4 classified, vec4 style) {
    return vec4(style.a > 0.0 ? style.rgb : classified.rgb, max(classified.a, style.a));
}

// The smoothed rule: inside the label's surface its colour and at least its opacity; across the surface the
// colours blend by their opacities there (the TF's fading out by the edge), so a label in clear tissue keeps
// its colour to its rim. Where no voxel around is shown, the TF's classification bit for bit.
vec4 withLabel(vec4 classified, LabelSample l) {
    float share = l.alpha / max(classified.a * (1.0 - l.edge) + l.alpha, 1e-6);
    return vec4(mix(classified.rgb, l.rgb, share), max(classified.a, l.alpha));
}
#endif
