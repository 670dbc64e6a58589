#version 450
// The clip-mesh overlay's first pass: the nearest mesh surface of each pixel (depth-tested among the meshes
// only; the volume has no depth here). Writes its translucent fill, premultiplied, darker where the surface
// turns away and more opaque towards the silhouette (a rim term, so a round tool reads as round); its world
// normal and mesh slot, from which the second pass finds the outlines; and the outline's colour.
in vec3 worldPosition;
in vec3 worldNormal;
layout(location = 0) out vec4 fillOut;
layout(location = 1) out vec4 normalSlotOut;
layout(location = 2) out vec4 outlineOut;
uniform vec3 eyeWorld;
uniform vec3 meshColor;
uniform float fillOpacity;
uniform float outlineOpacity;
uniform float meshSlot;   // mesh index + 1 (0: no mesh)
void main() {
    vec3 n = normalize(worldNormal);
    float facing = abs(dot(n, normalize(eyeWorld - worldPosition)));
    float rim = pow(1.0 - facing, 3.0);
    float alpha = min(max(fillOpacity, outlineOpacity), fillOpacity * (1.0 + 2.0 * rim));
    vec3 color = meshColor * (0.6 + 0.4 * facing);
    fillOut = vec4(color * alpha, alpha);
    normalSlotOut = vec4(n, meshSlot);
    outlineOut = vec4(meshColor, outlineOpacity);
}
