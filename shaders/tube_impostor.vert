#version 450
// Impostor tubes into the G-buffer (render/model/tube_impostors.h; seed 000 section 3.1.1's G-buffer): four
// vertices per point (two indexed triangles), made from gl_VertexID without vertex attributes. A point that starts a segment becomes
// a quad that bounds the segment's capsule (its cylinder and the balls at both ends) as seen from the eye;
// tube_impostor.frag intersects the pixel's ray with the exact tube on it. Other points are culled.
//
// The quad lies in the plane through the segment's midpoint facing the eye (normal v, distance D). Seen from
// the eye E, a point X of the ball of radius r around c projects onto that plane within
//     |P(X) - P(c)| <= D r |c - E| / ((z - r) z),   z = (c - E) . v,
// (write X - E = (c - E) + e with |e| <= r; the in-plane part of D ((X - E) / z_X - (c - E) / z) is bounded by
// Cauchy-Schwarz), and the projection of the capsule is the convex hull of its two balls' projections (a
// central projection keeps segments straight), which the rectangle around both discs holds.
#include "bindings.glsl"
layout(binding = BINDING_TUBE_IMPOSTOR_POINTS) uniform usamplerBuffer impostorPoints;
uniform mat4 viewProjection;
uniform vec3 eyeWorld;
uniform float radiusMm;
uniform uint firstPoint;     // the bundle's point drawn at gl_VertexID 0, within the bound texel range
flat out vec3 segmentStart;
flat out vec3 segmentEnd;
flat out uvec2 endColors;    // the two points' colour and flags (TubeImpostorPoint::colorAndFlags)
out vec3 quadWorld;          // the quad's world point: the pixel's ray passes through it

const uint SEGMENT_STARTS = 1u << 24;   // kImpostorSegmentStarts

const vec2 kCorners[4] = vec2[4](vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, 1));

void main() {
    int point = int(firstPoint) + gl_VertexID / 4;
    uvec4 a = texelFetch(impostorPoints, point);
    vec3 p0 = uintBitsToFloat(a.xyz);
    segmentStart = p0;
    endColors.x = a.w;
    if ((a.w & SEGMENT_STARTS) == 0u) {   // a streamline's last point: no segment
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
        segmentEnd = p0, endColors.y = 0u, quadWorld = p0;
        return;
    }
    uvec4 b = texelFetch(impostorPoints, point + 1);
    vec3 p1 = uintBitsToFloat(b.xyz);
    segmentEnd = p1;
    endColors.y = b.w;
    vec3 mid = 0.5 * (p0 + p1);
    float D = length(mid - eyeWorld);
    vec3 v = (mid - eyeWorld) / D;
    float r = radiusMm, d0 = length(p0 - eyeWorld), d1 = length(p1 - eyeWorld);
    float z0 = dot(p0 - eyeWorld, v), z1 = dot(p1 - eyeWorld, v);
    if (min(z0, z1) <= 1.001 * r) {   // the capsule reaches the eye's side of the plane: not drawn
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
        quadWorld = p0;
        return;
    }
    vec3 c0 = eyeWorld + (p0 - eyeWorld) * (D / z0), c1 = eyeWorld + (p1 - eyeWorld) * (D / z1);
    // A small margin for rounding: coverage is decided at pixel centres against this quad.
    float rho = 1.001 * max(D * r * d0 / ((z0 - r) * z0), D * r * d1 / ((z1 - r) * z1)) + 1e-5 * D;
    vec3 u = c1 - c0;
    float along = length(u);
    if (along > 1e-6 * rho) u /= along;
    else u = normalize(cross(v, abs(v.x) < 0.9 ? vec3(1, 0, 0) : vec3(0, 1, 0)));
    vec3 w = cross(v, u);
    vec2 corner = kCorners[gl_VertexID % 4];
    quadWorld = (corner.x < 0.0 ? c0 - rho * u : c1 + rho * u) + corner.y * rho * w;
    gl_Position = viewProjection * vec4(quadWorld, 1.0);
    // One pixel grid with the ray caster, row 0 at the top (tube_gbuffer.vert).
    gl_Position.y = -gl_Position.y;
}
