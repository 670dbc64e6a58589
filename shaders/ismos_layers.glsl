// ISMOS pass 1 (seed 003 sections 3.5, 3.6): what the ray caster records for the occlusion pass, compiled in
// only with ISMOS_LAYERS (1-4), so every other mode's ray caster is the same program as before.
//  - up to ISMOS_LAYERS layers: a layer is a run of samples with opacity, a sample without (transparent,
//    clipped, in a skipped brick) ends it; its front z, its opacity, and (ISMOS_EXACT) its back z, or
//    ISMOS_SOLID when the ray terminated inside it (the layer is opaque to the back of the box);
//  - (ISMOS_FIT) eq. 8-10's two running sums over the samples with opacity, stored as beta.
// z is the paper's 1 - depth; depth is the view depth normalised over the volume's bounding sphere.
// Binder: IsmosPass::applyLayers (render/passes/ismos_pass.h).

layout(rgba32f, binding = IMAGE_ISMOS_LAYER_FRONT) uniform writeonly image2D ismosLayerFront;
layout(rgba32f, binding = IMAGE_ISMOS_LAYER_ALPHA) uniform writeonly image2D ismosLayerAlpha;
#if ISMOS_EXACT
layout(rgba32f, binding = IMAGE_ISMOS_LAYER_BACK) uniform writeonly image2D ismosLayerBack;
#endif
#if ISMOS_FIT
layout(r32f, binding = IMAGE_ISMOS_FIT) uniform writeonly image2D ismosFit;
#endif
#ifdef ISMOS_TUBES
layout(binding = BINDING_TUBE_DEPTH) uniform sampler2D ismosTubeDepth;   // G-buffer view depth, 0: no tube
layout(binding = BINDING_TUBE_NORMAL) uniform sampler2D ismosTubeNormal;  // G-buffer normal (tubes), w: kind
uniform float ismosTubeThicknessMm;   // the tubes' diameter (TubeShading::thicknessMm)
#endif
uniform vec3 ismosForward;        // the camera's unit forward
uniform float ismosDepthRangeMm;  // far - near of the bounding sphere
uniform float ismosNearDepth;     // near / (far - near)

#define ISMOS_NO_LAYER -1.0
#define ISMOS_SOLID -1.0e30

struct IsmosLayers {
    vec4 front, transmittance, back;
    int count;      // layers opened so far
    bool open;      // the last sample had opacity
    float sumZ2LogInvT, sumZ4;
};

IsmosLayers ismosBegin() {
    return IsmosLayers(vec4(ISMOS_NO_LAYER), vec4(1.0), vec4(ISMOS_NO_LAYER), 0, false, 0.0, 0.0);
}

void ismosGap(inout IsmosLayers l) { l.open = false; }

// depth: the sample's normalised depth; alpha: its opacity; transmittance: the ray's after it.
void ismosSample(inout IsmosLayers l, float depth, float alpha, float transmittance) {
    if (!l.open) {
        l.open = true;
        if (l.count < ISMOS_LAYERS) {
            l.front[l.count] = 1.0 - depth;
            ++l.count;
        } else {
            l.count = ISMOS_LAYERS + 1;   // past the last recorded layer
        }
    }
    if (l.count <= ISMOS_LAYERS) {
        l.transmittance[l.count - 1] *= 1.0 - alpha;
        l.back[l.count - 1] = 1.0 - depth;
    }
    // Eq. 8-10 over the samples with opacity (empty space is skipped or not: beta is the same).
    float z2 = depth * depth;
    l.sumZ2LogInvT += z2 * log(1.0 / max(transmittance, 1e-30));
    l.sumZ4 += z2 * z2;
}

void ismosTerminated(inout IsmosLayers l) {
    if (l.open && l.count <= ISMOS_LAYERS) l.back[l.count - 1] = ISMOS_SOLID;
}

// A tube surface at normalised depth `depth` filling `thickness` behind it: an opaque layer of that
// thickness, not one opaque to the back of the box (which shadowed everything a path passed behind a tube
// floating in front of the tissue). The ray cast stops at the surface; the fit sees one opaque sample.
void ismosOpaqueSlab(inout IsmosLayers l, float depth, float thickness, float transmittance) {
    ismosGap(l);
    ismosSample(l, depth, 1.0, transmittance);
    if (l.count <= ISMOS_LAYERS) l.back[l.count - 1] = 1.0 - (depth + thickness);
}

void ismosStore(IsmosLayers l, ivec2 pixel) {
    imageStore(ismosLayerFront, pixel, l.front);
    imageStore(ismosLayerAlpha, pixel, vec4(1.0) - l.transmittance);
#if ISMOS_EXACT
    imageStore(ismosLayerBack, pixel, l.back);
#endif
#if ISMOS_FIT
    imageStore(ismosFit, pixel, vec4(l.sumZ4 > 0.0 ? l.sumZ2LogInvT / l.sumZ4 : 0.0));
#endif
}
