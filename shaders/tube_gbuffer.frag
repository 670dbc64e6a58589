#version 450
// G-buffer fragment: discards fragments inside a clip mesh set to clip tubes; writes colour, the world normal
// (tubes) or tangent (lines) with the surface kind in w, and the view depth along the camera axis.
#include "bindings.glsl"
#include "clip_test.glsl"
in vec3 worldPosition;
in vec3 worldDirection;
in vec4 surfaceColor;
layout(location = 0) out vec4 colorOut;
layout(location = 1) out vec4 normalOut;
layout(location = 2) out float depthOut;
uniform vec3 eyeWorld;
uniform vec3 viewForward;
uniform float surfaceKind;   // SURFACE_TUBE or SURFACE_LINE
void main() {
    if (clipMeshCount > 0 && insideAnyTubeClippingMesh(worldPosition)) discard;
    colorOut = surfaceColor;
    normalOut = vec4(normalize(worldDirection), surfaceKind);
    depthOut = dot(worldPosition - eyeWorld, viewForward);
}
