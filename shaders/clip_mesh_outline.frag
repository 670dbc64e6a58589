#version 450
// The clip-mesh overlay's second pass, over the target with premultiplied "over" blending: each pixel the first
// pass covered gets its fill, or its mesh's outline colour where it borders another mesh or no mesh (the
// silhouette) or where the surface's normal turns by more than the crease angle to a neighbour (a box's
// edges, a cylinder's rims). Pixels no mesh covers are discarded: the target keeps them bit for bit. The
// outline lies on the mesh's own pixels, so what the overlay covers is what the mesh covers.
layout(binding = 0) uniform sampler2D fillTexture;
layout(binding = 1) uniform sampler2D normalSlotTexture;
layout(binding = 2) uniform sampler2D outlineTexture;
uniform ivec2 viewportOrigin;   // the target's pixel of the first pass's texel (0, 0)
uniform float creaseCosine;
out vec4 color;

bool bordersAt(ivec2 texel, ivec2 size, vec4 own) {
    if (any(lessThan(texel, ivec2(0))) || any(greaterThanEqual(texel, size))) return false;   // the view's edge is no outline
    vec4 other = texelFetch(normalSlotTexture, texel, 0);
    return other.w != own.w || dot(other.xyz, own.xyz) < creaseCosine;
}

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy) - viewportOrigin;
    vec4 own = texelFetch(normalSlotTexture, texel, 0);
    if (own.w == 0.0) discard;
    ivec2 size = textureSize(normalSlotTexture, 0);
    bool edge = bordersAt(texel + ivec2(1, 0), size, own) || bordersAt(texel - ivec2(1, 0), size, own) ||
                bordersAt(texel + ivec2(0, 1), size, own) || bordersAt(texel - ivec2(0, 1), size, own);
    if (edge) {
        vec4 outline = texelFetch(outlineTexture, texel, 0);
        color = vec4(outline.rgb * outline.a, outline.a);
    } else {
        color = texelFetch(fillTexture, texel, 0);
    }
}
