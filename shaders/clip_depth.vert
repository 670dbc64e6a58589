#version 450
// Step II: a clip mesh rasterised by its clipping camera. The depth written to the map is the mesh-local z in
// millimetres (orthographic, so it interpolates linearly and exactly across each triangle).
layout(location = 0) in vec3 position;   // scaled mesh-local millimetres
uniform mat4 localToClip;
out float localDepth;
void main() {
    localDepth = position.z;
    gl_Position = localToClip * vec4(position, 1.0);
}
