#version 450
// Step III's source: one depth-map layer reduced to the dilated maps' coarser pixels. A dilated-map pixel
// takes the nearest front (min) or farthest back (max) of every depth-map pixel its square meets, widened by
// one depth pixel against rounding, so every point the depth maps call inside lies within the interval of
// the coarse pixel holding it: the premise of the dilation radius (ClipMeshSet::kernelRadiusMm).
#include "bindings.glsl"

layout(local_size_x = 16, local_size_y = 16) in;
layout(binding = BINDING_CLIP_DEPTH) uniform sampler2DArray depthMaps;
layout(r32f, binding = IMAGE_DILATION) uniform writeonly image2DArray reducedMap;

uniform int sourceLayer;
uniform int resolution;        // the dilated maps' pixels per side
uniform int depthResolution;   // the depth maps'
uniform vec2 depthOffset;      // map x, y -> depth-square x, y: (m - depthOffset) * depthScale
uniform float depthScale;
uniform bool backMap;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, ivec2(resolution)))) return;
    const float infinity = uintBitsToFloat(0x7F800000u);
    float best = backMap ? -infinity : infinity;
    vec2 lo = (vec2(p) / float(resolution) - depthOffset) * depthScale * float(depthResolution);
    vec2 hi = (vec2(p + 1) / float(resolution) - depthOffset) * depthScale * float(depthResolution);
    ivec2 first = max(ivec2(floor(lo)) - 1, ivec2(0));
    ivec2 last = min(ivec2(floor(hi)) + 1, ivec2(depthResolution - 1));
    for (int y = first.y; y <= last.y; ++y)
        for (int x = first.x; x <= last.x; ++x) {
            float z = texelFetch(depthMaps, ivec3(x, y, sourceLayer), 0).r;
            best = backMap ? max(best, z) : min(best, z);
        }
    imageStore(reducedMap, ivec3(p, 0), vec4(best));
}
