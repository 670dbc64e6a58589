#version 450
// Impostor tubes, fragment: the pixel's ray against the exact tube of one segment (render/model/tube_impostors.h):
// the cylinder of radius r around [p0, p1] (both of its crossings: an open end shows the inner wall, as the
// triangle tubes without caps do), the ball at p1 where the streamline goes on, flat discs at its ends with
// caps. The nearest crossing not inside a mesh that clips tubes is the surface (the triangle path clips each
// surface fragment the same way, tube_gbuffer.frag), written as tube_gbuffer.frag writes it: colour, world
// normal + kind, view depth, and its window depth for the depth test. No crossing: discard.
#include "bindings.glsl"
#include "clip_test.glsl"
flat in vec3 segmentStart;
flat in vec3 segmentEnd;
flat in uvec2 endColors;
in vec3 quadWorld;
layout(location = 0) out vec4 colorOut;
layout(location = 1) out vec4 normalOut;
layout(location = 2) out float depthOut;
uniform mat4 viewProjection;
uniform vec3 eyeWorld;
uniform vec3 viewForward;
uniform float radiusMm;
uniform bool caps;

const uint SEGMENT_STARTS = 1u << 24;   // kImpostorSegmentStarts
const uint SEGMENT_ENDS = 1u << 25;     // kImpostorSegmentEnds

vec3 unpackColor(uint c) { return vec3(float(c & 0xFFu), float((c >> 8) & 0xFFu), float((c >> 16) & 0xFFu)) / 255.0; }

// The nearest accepted crossing so far: ray parameter from q, outward normal, fraction along the segment.
float bestT = 1e30;
vec3 bestNormal;
float bestAlong;
vec3 rayOrigin, rayDirection;

void consider(float t, vec3 normal, float along) {
    if (t >= bestT) return;
    if (clipMeshCount > 0 && insideAnyTubeClippingMesh(rayOrigin + t * rayDirection)) return;
    bestT = t, bestNormal = normal, bestAlong = along;
}

void main() {
    vec3 p0 = segmentStart, p1 = segmentEnd;
    float r = radiusMm;
    vec3 dir = normalize(quadWorld - eyeWorld);
    // Solve near the segment, not at the eye: with the eye hundreds of millimetres away, |q - p|^2 - r^2 in
    // float would lose the radius to rounding.
    float tm = dot(0.5 * (p0 + p1) - eyeWorld, dir);
    vec3 q = eyeWorld + tm * dir;
    rayOrigin = q, rayDirection = dir;
    vec3 axis = p1 - p0;
    float L = length(axis);
    axis /= L;

    // Cylinder: |(q + t dir - p0) x axis| = r with 0 <= (q + t dir - p0) . axis <= L.
    vec3 oc = q - p0;
    float oa = dot(oc, axis), da = dot(dir, axis);
    vec3 ocPerp = oc - oa * axis, dirPerp = dir - da * axis;
    float A = dot(dirPerp, dirPerp), B = dot(ocPerp, dirPerp), C = dot(ocPerp, ocPerp) - r * r;
    float disc = B * B - A * C;
    if (A > 1e-12 && disc >= 0.0) {
        float s = sqrt(disc);
        for (int k = 0; k < 2; ++k) {
            float t = (-B + (k == 0 ? -s : s)) / A;
            float y = oa + t * da;
            if (y >= 0.0 && y <= L) consider(t, (ocPerp + t * dirPerp) / r, y / L);
        }
    }
    // The ball at p1 where the streamline goes on (the next segment starts there): the joint.
    if ((endColors.y & SEGMENT_STARTS) != 0u) {
        vec3 o1 = q - p1;
        float b = dot(o1, dir), c = dot(o1, o1) - r * r, d = b * b - c;
        if (d >= 0.0) {
            float t = -b - sqrt(d);
            consider(t, (o1 + t * dir) / r, 1.0);
        }
    }
    // Flat discs at a streamline's ends, with caps.
    if (caps && abs(da) > 1e-8) {
        if ((endColors.x & SEGMENT_ENDS) == 0u) {
            float t = -oa / da;
            vec3 h = oc + t * dir;
            if (dot(h, h) <= r * r) consider(t, -axis, 0.0);
        }
        if ((endColors.y & SEGMENT_STARTS) == 0u) {
            float t = (L - oa) / da;
            vec3 h = oc + t * dir - L * axis;
            if (dot(h, h) <= r * r) consider(t, axis, 1.0);
        }
    }
    if (bestT >= 1e30 || tm + bestT <= 0.0) discard;
    vec3 hit = q + bestT * dir;
    colorOut = vec4(mix(unpackColor(endColors.x), unpackColor(endColors.y), clamp(bestAlong, 0.0, 1.0)), 1.0);
    normalOut = vec4(normalize(bestNormal), SURFACE_TUBE);
    depthOut = (tm + bestT) * dot(dir, viewForward);
    vec4 clip = viewProjection * vec4(hit, 1.0);
    gl_FragDepth = 0.5 * clip.z / clip.w + 0.5;
}
