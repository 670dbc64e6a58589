// Label volumes in the classification (compiled in with LABELS only; a scene without labels has none of
// this). Labels are ids on the scan grid (the scene's label maps resampled by nearest label, never
// interpolated between ids: base/label_map.h); each id has a style, rgb and an opacity per unit length, 0
// when the label is not shown. A sample takes the label of the voxel it lies in, and a shown label replaces
// the sample's TF colour by its own and raises its opacity to at least the label's:
//     classified' = (rgb_label, max(alpha_TF, alpha_label))     where alpha_label > 0
// so a structure shows in its colour on a cut face and inside clear tissue alike. Step IV classifies each
// voxel by the same rule (labelStyleAtVoxel), so the AO modes see the labels' opacity too.
// Binder: render/label_overlay.h (LabelOverlay::apply, through TransferFunctionTexture::apply).
#include "bindings.glsl"

#ifdef LABELS
layout(binding = BINDING_LABEL_IDS) uniform usampler3D labelIds;
layout(binding = BINDING_LABEL_STYLES) uniform sampler1D labelStyles;

vec4 labelStyleAtVoxel(ivec3 voxel) { return texelFetch(labelStyles, int(texelFetch(labelIds, voxel, 0).r), 0); }

// The style of the voxel a sample at texture coordinate `tex` lies in.
vec4 labelStyleAt(vec3 tex) {
    ivec3 size = textureSize(labelIds, 0);
    return labelStyleAtVoxel(clamp(ivec3(floor(tex * vec3(size))), ivec3(0), size - 1));
}

vec4 withLabel(vec4 classified, vec4 style) {
    return vec4(style.a > 0.0 ? style.rgb : classified.rgb, max(classified.a, style.a));
}
#endif
