#version 450
// The clip-mesh overlay's first pass (render/clip_mesh_overlay.h): one clip mesh, from the vertex buffer step II
// draws (scaled mesh-local corners), placed by its pose and seen by the frame's camera.
layout(location = 0) in vec3 position;   // scaled mesh-local millimetres
layout(location = 1) in vec3 normal;     // scaled mesh-local, unit, per triangle corner
uniform mat4 localToWorld;               // the mesh's RigidPose::matrix() (rigid: its 3x3 turns normals too)
uniform mat4 viewProjection;             // OrbitCamera::viewProjection of the frame's image size
uniform float flipY;                     // -1: rows from the top (an Image), 1: GL's rows from the bottom (a window)
out vec3 worldPosition;
out vec3 worldNormal;
void main() {
    vec4 world = localToWorld * vec4(position, 1.0);
    worldPosition = world.xyz;
    worldNormal = mat3(localToWorld) * normal;
    gl_Position = viewProjection * world;
    gl_Position.y *= flipY;
}
