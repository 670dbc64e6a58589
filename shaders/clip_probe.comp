#version 450
// The clip probe: evaluates clip_test.glsl at arbitrary world points: the removal report asks which tract
// points a carve cuts (render/passes/removal_probe.h), and tests compare the shader's inside
// test (and dilated test) with analytic shapes.
#include "bindings.glsl"
#include "clip_test.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = SSBO_PROBE_POINTS) readonly buffer Points { vec4 points[]; };
layout(std430, binding = SSBO_PROBE_RESULTS) writeonly buffer Results { uint results[]; };  // bit 0 inside, bit 1 dilated, bit 2 near
uniform uint pointCount;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= pointCount) return;
    vec3 p = points[i].xyz;
    results[i] = (insideAnyClipMesh(p) ? 1u : 0u) | (insideAnyDilatedMesh(p) ? 2u : 0u) |
                 (nearAnyClipMesh(p, 0.0) ? 4u : 0u);
}
