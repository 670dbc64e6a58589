#version 450
// Test probe: evaluates clip_test.glsl at arbitrary world points so tests can compare the shader's inside
// test (and dilated test) with analytic shapes. Not used when rendering.
#include "bindings.glsl"
#include "clip_test.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 6) readonly buffer Points { vec4 points[]; };
layout(std430, binding = 7) writeonly buffer Results { uint results[]; };  // bit 0 inside, bit 1 dilated, bit 2 near
uniform uint pointCount;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= pointCount) return;
    vec3 p = points[i].xyz;
    results[i] = (insideAnyClipMesh(p) ? 1u : 0u) | (insideAnyDilatedMesh(p) ? 2u : 0u) |
                 (nearAnyClipMesh(p, 0.0) ? 4u : 0u);
}
