#version 450
// Step III: the dilated depth maps, the 2-D Minkowski sum of a depth map with the sphere of LAO influence
// (CAO Algorithm 1). Algorithm 1 takes the sphere profile h(d) = sqrt(R^2 - |d|^2) over a disk, O(R^2) taps
// a pixel. We use the separable kernel
//     k(dx, dy) = a(dx) + a(dy),   a(t) = sqrt(R^2 - t^2) - R/2,
// applied as two 1-D passes (O(R) taps). On the disk k >= h, because for u = R^2 - dx^2, v = R^2 - dy^2,
// sqrt(u) + sqrt(v) >= sqrt(R^2) + sqrt(u + v - R^2) (concavity of sqrt: the pair (R^2, u+v-R^2) is more
// spread than (u, v) and has the same sum). Subtracting more than the sphere makes the dilated shape a
// superset of Algorithm 1's, so the CAO classification stays conservative and CAO stays exactly LAO; along
// the axes k = h exactly. Front maps take min(z - k), back maps max(z + k) (Algorithm 1, line 7-8 and the
// text after it). Pixels outside the map are empty; the clipping camera leaves a margin so none is needed.
#include "bindings.glsl"

layout(local_size_x = 16, local_size_y = 16) in;
layout(binding = BINDING_CLIP_DEPTH) uniform sampler2DArray sourceMaps;
layout(r32f, binding = IMAGE_DILATION) uniform writeonly image2DArray destinationMaps;

uniform int sourceLayer;
uniform int destinationLayer;
uniform ivec2 direction;      // (1, 0) for the first pass, (0, 1) for the second
uniform int resolution;
uniform float radiusMm;       // R: the dilation radius including the pixel margin (clip::ClipMeshSet::kernelRadiusMm)
uniform float pixelMm;
uniform bool backMap;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, ivec2(resolution)))) return;
    int reach = int(floor(radiusMm / pixelMm));
    const float infinity = uintBitsToFloat(0x7F800000u);
    float best = backMap ? -infinity : infinity;
    for (int i = -reach; i <= reach; ++i) {
        ivec2 q = p + i * direction;
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(resolution)))) continue;
        float t = float(i) * pixelMm;
        float offset = sqrt(max(radiusMm * radiusMm - t * t, 0.0)) - 0.5 * radiusMm;
        float z = texelFetch(sourceMaps, ivec3(q, sourceLayer), 0).r;
        best = backMap ? max(best, z + offset) : min(best, z - offset);
    }
    imageStore(destinationMaps, ivec3(p, destinationLayer), vec4(best));
}
