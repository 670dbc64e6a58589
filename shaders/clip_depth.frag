#version 450
// Step II: nearest front (or back) face depth; with peelAgainst >= 0, only faces strictly behind that layer
// (depth peeling, Everitt 2001) so a concave mesh gets its second interval. The surface normal goes to the
// normal map of the same layer.
#include "bindings.glsl"
#include "octahedral.glsl"
in float localDepth;
in vec3 localNormal;
layout(location = 0) out float depthOut;
layout(location = 1) out vec2 normalOut;
layout(binding = BINDING_CLIP_DEPTH) uniform sampler2DArray previousLayers;
uniform int peelAgainst;   // layer of the array to peel against, or -1
void main() {
    if (peelAgainst >= 0 && localDepth <= texelFetch(previousLayers, ivec3(gl_FragCoord.xy, peelAgainst), 0).r) discard;
    depthOut = localDepth;
    normalOut = octahedralEncode(normalize(localNormal));
}
