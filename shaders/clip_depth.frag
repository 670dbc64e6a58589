#version 450
// Step II: nearest front (or back) face depth; with peelAgainst >= 0, only faces strictly behind that layer
// (depth peeling, Everitt 2001) so a concave mesh gets its second interval.
#include "bindings.glsl"
in float localDepth;
layout(location = 0) out float depthOut;
layout(binding = BINDING_CLIP_DEPTH) uniform sampler2DArray previousLayers;
uniform int peelAgainst;   // layer of the array to peel against, or -1
void main() {
    if (peelAgainst >= 0 && localDepth <= texelFetch(previousLayers, ivec3(gl_FragCoord.xy, peelAgainst), 0).r) discard;
    depthOut = localDepth;
}
