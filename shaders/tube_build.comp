#version 450
// Tubes expanded on the GPU (render/passes/gpu_tube_builder.h): one invocation per swept ring writes its `sides`
// vertices (centre + radius (cos a N + sin a B), B = T x N, a = 2 pi k / sides), the 6 * sides indices of the
// quads to the next ring, and at an end ring with caps the cap's centre, rim and fan. The layout and the
// triangle order are expandTubeRings' (render/model/tube_geometry.cpp), the CPU oracle this is tested against.
#include "bindings.glsl"

layout(local_size_x = 64) in;

struct TubeRing {
    vec4 point;     // xyz: centre (world mm); w: the streamline's index, as uint bits
    vec4 tangent;   // xyz: unit tangent T
    vec4 normal;    // xyz: unit rotation-minimising normal N
    vec4 color;
};
struct TubeStreamline {
    uvec4 layout_;  // first ring, ring count, first vertex, first index
    vec4 shape;     // radius mm, sides, caps (0 or 1), unused
};
layout(std430, binding = SSBO_TUBE_RINGS) readonly buffer Rings { TubeRing rings[]; };
layout(std430, binding = SSBO_TUBE_STREAMLINES) readonly buffer Streamlines { TubeStreamline streamlines[]; };
layout(std430, binding = SSBO_TUBE_CIRCLE) readonly buffer Circle { vec2 circle[]; };
layout(std430, binding = SSBO_TUBE_POSITIONS) writeonly buffer Positions { float positions[]; };
layout(std430, binding = SSBO_TUBE_DIRECTIONS) writeonly buffer Directions { float directions[]; };
layout(std430, binding = SSBO_TUBE_COLORS) writeonly buffer Colors { vec4 colors[]; };
layout(std430, binding = SSBO_TUBE_INDICES) writeonly buffer Indices { uint indices[]; };

uniform uint ringCount;       // rings in this batch
uniform uint firstRing;       // the batch's first ring (rings[0] is ring firstRing of the whole set)
uniform uint firstVertex;     // the batch's first vertex and index
uniform uint firstIndex;
uniform uint positionSlack;   // floats of the bound position/direction ranges before firstVertex's (alignment)
uniform uint colorSlack;      // vec4s of the bound colour range before firstVertex's
uniform uint indexSlack;      // uints of the bound index range before firstIndex's

void writeVertex(uint vertex, vec3 position, vec3 direction, vec4 color) {
    uint f = positionSlack + 3u * (vertex - firstVertex);
    positions[f] = position.x, positions[f + 1u] = position.y, positions[f + 2u] = position.z;
    directions[f] = direction.x, directions[f + 1u] = direction.y, directions[f + 2u] = direction.z;
    colors[colorSlack + vertex - firstVertex] = color;
}

void writeIndex(uint index, uint value) { indices[indexSlack + index - firstIndex] = value; }

void main() {
    uint r = gl_GlobalInvocationID.x;
    if (r >= ringCount) return;
    TubeRing ring = rings[r];
    TubeStreamline line = streamlines[floatBitsToUint(ring.point.w)];
    uint i = firstRing + r - line.layout_.x, n = line.layout_.y, lineVertex = line.layout_.z, lineIndex = line.layout_.w;
    float radius = line.shape.x;
    uint sides = uint(line.shape.y);
    uint circleStart = sides * (sides - 1u) / 2u;
    vec3 c = ring.point.xyz, t = ring.tangent.xyz, nrm = ring.normal.xyz, b = cross(t, nrm);
    for (uint k = 0u; k < sides; ++k) {
        vec3 radial = circle[circleStart + k].x * nrm + circle[circleStart + k].y * b;
        writeVertex(lineVertex + i * sides + k, c + radius * radial, radial, ring.color);
    }
    if (i + 1u < n) {
        for (uint k = 0u; k < sides; ++k) {
            uint a = lineVertex + i * sides + k, bb = lineVertex + i * sides + (k + 1u) % sides;
            uint cc = a + sides, d = bb + sides, at = lineIndex + (i * sides + k) * 6u;
            writeIndex(at, a), writeIndex(at + 1u, bb), writeIndex(at + 2u, d);
            writeIndex(at + 3u, a), writeIndex(at + 4u, d), writeIndex(at + 5u, cc);
        }
    }
    bool start = i == 0u, end = i + 1u == n;
    if (line.shape.z > 0.5 && (start || end)) {
        // The start cap follows the rings, the end cap follows the start cap (a ring of two is both ends).
        for (uint e = start ? 0u : 1u; e <= (end ? 1u : 0u); ++e) {
            vec3 axis = e == 1u ? t : -t;
            uint centre = lineVertex + n * sides + e * (sides + 1u), rim = centre + 1u;
            writeVertex(centre, c, axis, ring.color);
            for (uint k = 0u; k < sides; ++k)
                writeVertex(rim + k, c + radius * (circle[circleStart + k].x * nrm + circle[circleStart + k].y * b), axis, ring.color);
            uint at = lineIndex + (n - 1u) * sides * 6u + e * 3u * sides;
            for (uint k = 0u; k < sides; ++k) {
                uint p = rim + k, q = rim + (k + 1u) % sides;
                writeIndex(at + 3u * k, centre);
                writeIndex(at + 3u * k + 1u, e == 1u ? p : q);
                writeIndex(at + 3u * k + 2u, e == 1u ? q : p);
            }
        }
    }
}
