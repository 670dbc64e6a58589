#version 450
// Step II: a clip mesh rasterised by its clipping camera. The depth written to the map is the mesh-local z in
// millimetres (orthographic, so it interpolates linearly and exactly across each triangle); the normal is the
// surface's at the pixel (mesh/surface_normals.h), for the cut faces.
layout(location = 0) in vec3 position;   // scaled mesh-local millimetres
layout(location = 1) in vec3 normal;     // scaled mesh-local, unit, per triangle corner
uniform mat4 localToClip;
out float localDepth;
out vec3 localNormal;
void main() {
    localDepth = position.z;
    localNormal = normal;
    gl_Position = localToClip * vec4(position, 1.0);
}
