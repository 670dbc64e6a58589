#version 450
// Impostor tubes into the G-buffer without the rasterizer (render/model/tube_impostors.h; seed 000 section
// 3.1.1's G-buffer). llvmpipe pays about 200 ns to set up and bin a triangle, whatever its fragments cost, and a
// whole-brain set is millions of segments a few pixels each; so every invocation takes one segment, bounds its
// capsule on the screen and intersects each pixel's ray in that box with the exact tube. Three phases give what a
// depth-tested draw gives, ties to the first segment:
//   0, per segment: the nearest view depth at each pixel (imageAtomicMin on the float's bits: a positive float
//      orders as its unsigned bits);
//   1, per segment: of the segments at exactly that depth, the first (imageAtomicMin on the global point index);
//   2, per pixel: that segment's surface written as tube_gbuffer.frag writes it: colour, world normal + kind,
//      view depth.
// Phases 0 and 1 run the same code on the same inputs, so "exactly that depth" is bit for bit.
//
// The tube of a bundle: per segment between consecutive points p0, p1, the cylinder of radius r around it (both
// of its crossings: an open end shows the inner wall, as the triangle tubes without caps do), the ball at p1
// where the streamline goes on, flat discs at its ends with caps. The nearest crossing not inside a mesh that
// clips tubes is the surface.
//
// The box: the capsule seen from the eye E lies within a rectangle in the plane through the segment's midpoint
// facing the eye (normal v, distance D). A point X of the ball of radius r around c projects onto that plane
// within
//     |P(X) - P(c)| <= D r |c - E| / ((z - r) z),   z = (c - E) . v,
// (write X - E = (c - E) + e with |e| <= r; the in-plane part of D ((X - E) / z_X - (c - E) / z) is bounded by
// Cauchy-Schwarz), and the projection of the capsule is the convex hull of its two balls' projections (a
// central projection keeps segments straight), which the rectangle around both discs holds. The pixels whose
// centres the rectangle's projected corners bound are tested.
#include "bindings.glsl"
#include "pixel_ray.glsl"
#include "clip_test.glsl"

layout(local_size_x = 64) in;
layout(binding = BINDING_TUBE_IMPOSTOR_POINTS) uniform usamplerBuffer impostorPoints;
layout(r32ui, binding = IMAGE_TUBE_NEAREST_DEPTH) uniform coherent uimage2D nearestDepth;
layout(r32ui, binding = IMAGE_TUBE_NEAREST_SEGMENT) uniform coherent uimage2D nearestSegment;
layout(std430, binding = SSBO_TUBE_CANDIDATES) coherent buffer Candidates { uint candidates[]; };
layout(rgba16f, binding = IMAGE_TUBE_COLOR) uniform writeonly image2D surfaceColor;
layout(rgba16f, binding = IMAGE_TUBE_NORMAL) uniform writeonly image2D surfaceNormal;
layout(r32f, binding = IMAGE_TUBE_DEPTH) uniform writeonly image2D surfaceDepth;
uniform mat4 viewProjection;
uniform vec3 viewForward;
uniform float radiusMm;
uniform bool caps;
uniform int phase;            // 0, 1 or 2 (above)
uniform uint globalBase;      // the global point index of the bound texel range's texel 0
uniform uint firstPoint;      // the texel of the first point this dispatch takes (phase 2: whose segment it writes)
uniform uint pointCount;      // the points from there

const uint SEGMENT_STARTS = 1u << 24;   // kImpostorSegmentStarts
const uint SEGMENT_ENDS = 1u << 25;     // kImpostorSegmentEnds

vec3 unpackColor(uint c) { return vec3(float(c & 0xFFu), float((c >> 8) & 0xFFu), float((c >> 16) & 0xFFu)) / 255.0; }

struct Segment {
    vec3 p0, p1;
    uvec2 colors;   // the two points' colour and flags (TubeImpostorPoint::colorAndFlags)
};

// The nearest accepted crossing of the ray from the eye along `dir`: distance from the eye, outward normal,
// fraction along the segment. False when none lies in front of the eye.
bool hitSegment(Segment s, vec3 dir, out float distance, out vec3 normal, out float along) {
    vec3 p0 = s.p0, p1 = s.p1;
    float r = radiusMm;
    // Solve near the segment, not at the eye: with the eye hundreds of millimetres away, |q - p|^2 - r^2 in
    // float would lose the radius to rounding.
    float tm = dot(0.5 * (p0 + p1) - eyeWorld, dir);
    vec3 q = eyeWorld + tm * dir;
    vec3 axis = p1 - p0;
    float L = length(axis);
    axis /= L;
    float bestT = 1e30;
    normal = vec3(0.0), along = 0.0;
#define CONSIDER(T, NORMAL, ALONG)                                                                              \
    if ((T) < bestT && !(clipMeshCount > 0 && insideAnyTubeClippingMesh(q + (T) * dir)))                      \
        bestT = (T), normal = (NORMAL), along = (ALONG);

    // Cylinder: |(q + t dir - p0) x axis| = r with 0 <= (q + t dir - p0) . axis <= L.
    vec3 oc = q - p0;
    float oa = dot(oc, axis), da = dot(dir, axis);
    vec3 ocPerp = oc - oa * axis, dirPerp = dir - da * axis;
    float A = dot(dirPerp, dirPerp), B = dot(ocPerp, dirPerp), C = dot(ocPerp, ocPerp) - r * r;
    float disc = B * B - A * C;
    if (A > 1e-12 && disc >= 0.0) {
        float root = sqrt(disc);
        for (int k = 0; k < 2; ++k) {
            float t = (-B + (k == 0 ? -root : root)) / A;
            float y = oa + t * da;
            if (y >= 0.0 && y <= L) { CONSIDER(t, (ocPerp + t * dirPerp) / r, y / L) }
        }
    }
    // The ball at p1 where the streamline goes on (the next segment starts there): the joint.
    if ((s.colors.y & SEGMENT_STARTS) != 0u) {
        vec3 o1 = q - p1;
        float b = dot(o1, dir), c = dot(o1, o1) - r * r, d = b * b - c;
        if (d >= 0.0) {
            float t = -b - sqrt(d);
            CONSIDER(t, (o1 + t * dir) / r, 1.0)
        }
    }
    // Flat discs at a streamline's ends, with caps.
    if (caps && abs(da) > 1e-8) {
        if ((s.colors.x & SEGMENT_ENDS) == 0u) {
            float t = -oa / da;
            vec3 h = oc + t * dir;
            if (dot(h, h) <= r * r) { CONSIDER(t, -axis, 0.0) }
        }
        if ((s.colors.y & SEGMENT_STARTS) == 0u) {
            float t = (L - oa) / da;
            vec3 h = oc + t * dir - L * axis;
            if (dot(h, h) <= r * r) { CONSIDER(t, axis, 1.0) }
        }
    }
#undef CONSIDER
    distance = tm + bestT;
    return bestT < 1e30 && distance > 0.0;
}

Segment fetchSegment(int texel) {
    uvec4 a = texelFetch(impostorPoints, texel), b = texelFetch(impostorPoints, texel + 1);
    return Segment(uintBitsToFloat(a.xyz), uintBitsToFloat(b.xyz), uvec2(a.w, b.w));
}

// A world point to pixel coordinates, pixel centres at integers (pixel_ray.glsl's grid: row 0 at the top); false
// for a point not in front of the eye.
bool toPixel(vec3 world, out vec2 pixel) {
    vec4 clip = viewProjection * vec4(world, 1.0);
    pixel = vec2(0.0);
    if (!(clip.w > 1e-6)) return false;
    vec2 ndc = clip.xy / clip.w;
    pixel = vec2(0.5 * ndc.x + 0.5, 0.5 - 0.5 * ndc.y) * vec2(outputSize) - 0.5;
    return true;
}

// The rectangle around the capsule of radius r about [p0, p1] (the box above) as a convex quadrilateral in pixel
// coordinates; false when the capsule reaches the eye's side of the midpoint's plane or a corner is not in
// front of the eye (drawSegment then bounds the capsule piece by piece).
bool screenQuad(vec3 p0, vec3 p1, out vec2 corners[4]) {
    vec3 mid = 0.5 * (p0 + p1);
    float D = length(mid - eyeWorld);
    vec3 v = (mid - eyeWorld) / D;
    float r = radiusMm, d0 = length(p0 - eyeWorld), d1 = length(p1 - eyeWorld);
    float z0 = dot(p0 - eyeWorld, v), z1 = dot(p1 - eyeWorld, v);
    if (min(z0, z1) <= 1.001 * r) return false;
    vec3 c0 = eyeWorld + (p0 - eyeWorld) * (D / z0), c1 = eyeWorld + (p1 - eyeWorld) * (D / z1);
    float rho = 1.001 * max(D * r * d0 / ((z0 - r) * z0), D * r * d1 / ((z1 - r) * z1)) + 1e-5 * D;
    vec3 u = c1 - c0;
    float alongPlane = length(u);
    if (alongPlane > 1e-6 * rho) u /= alongPlane;
    else u = normalize(cross(v, abs(v.x) < 0.9 ? vec3(1, 0, 0) : vec3(0, 1, 0)));
    vec3 w = cross(v, u);
    bool inFront = toPixel(c0 - rho * u - rho * w, corners[0]);
    inFront = toPixel(c0 - rho * u + rho * w, corners[1]) && inFront;
    inFront = toPixel(c1 + rho * u + rho * w, corners[2]) && inFront;
    inFront = toPixel(c1 + rho * u - rho * w, corners[3]) && inFront;
    return inFront;
}

// pixel_ray.glsl's ray through a pixel centre, unnormalised, as base + ndc.x alongX + ndc.y alongY: the point it
// takes on the far plane, M (ndc, 1, 1) with M the inverse view-projection, is affine in the ndc because the
// inverse of a perspective projection keeps w the same across the image. Taken from M's columns, not as a
// difference of far points (which would lose the step to rounding).
struct PixelRays {
    vec3 base, alongX, alongY;
};
PixelRays pixelRays() {
    mat4 M = inverseViewProjection;
    float w = M[2].w + M[3].w;
    return PixelRays((M[2].xyz + M[3].xyz) / w - eyeWorld, M[0].xyz / w, M[1].xyz / w);
}
float ndcX(int x) { return (float(x) + 0.5) / float(outputSize.x) * 2.0 - 1.0; }
float ndcY(int y) { return 1.0 - (float(y) + 0.5) / float(outputSize.y) * 2.0; }
// The one expression every phase takes a pixel's ray by (walkQuad hoists its row part), so their depths agree
// bit for bit.
vec3 pixelRay(PixelRays rays, ivec2 pixel) { return rays.base + ndcY(pixel.y) * rays.alongY + ndcX(pixel.x) * rays.alongX; }

// Phases 0 and 1 for one segment over the pixels of a quadrilateral that bounds (a piece of) its capsule.
// Phase 0 marks the segment a candidate when it was the nearest at a pixel as it tested it (the depth stored
// then was not nearer): a segment at the final nearest depth of a pixel was so at its turn, since the stored
// depth only falls to that value; so phase 1 needs the candidates alone.
void walkQuad(Segment s, uint global, vec2 corners[4], inout bool candidate) {
    float top = min(min(corners[0].y, corners[1].y), min(corners[2].y, corners[3].y));
    float bottom = max(max(corners[0].y, corners[1].y), max(corners[2].y, corners[3].y));
    PixelRays rays = pixelRays();
    // No point of the capsule lies nearer than this view depth (less a margin for rounding): where a nearer
    // surface is already stored, the pixel is passed over without its crossings, as a depth test before
    // shading would. The stored depth only falls, so a stale read passes over less, never more.
    float nearest = min(dot(s.p0 - eyeWorld, viewForward), dot(s.p1 - eyeWorld, viewForward)) - radiusMm;
    uint nearestKey = floatBitsToUint(max(nearest * (1.0 - 1e-5) - 1e-4, 0.0));
    for (int y = max(int(ceil(top)), 0); y <= min(int(floor(bottom)), outputSize.y - 1); ++y) {
        // The quadrilateral's span on this row of pixel centres (a little wider for rounding).
        float left = 1e30, right = -1e30;
        for (int e = 0; e < 4; ++e) {
            vec2 p = corners[e], q = corners[(e + 1) & 3];
            float lowY = min(p.y, q.y), highY = max(p.y, q.y);
            if (float(y) < lowY || float(y) > highY) continue;
            float x = highY > lowY ? p.x + (float(y) - p.y) * (q.x - p.x) / (q.y - p.y) : p.x;
            left = min(left, highY > lowY ? x : min(p.x, q.x));
            right = max(right, highY > lowY ? x : max(p.x, q.x));
        }
        vec3 row = rays.base + ndcY(y) * rays.alongY;   // pixelRay's expression, its row part once
        for (int x = max(int(ceil(left - 1e-3)), 0); x <= min(int(floor(right + 1e-3)), outputSize.x - 1); ++x) {
            ivec2 pixel = ivec2(x, y);
            uint stored = imageLoad(nearestDepth, pixel).x;
            if (stored < nearestKey) continue;
            vec3 dir = normalize(row + ndcX(x) * rays.alongX);
            float distance, along;
            vec3 normal;
            if (!hitSegment(s, dir, distance, normal, along)) continue;
            uint key = floatBitsToUint(distance * dot(dir, viewForward));
            if (phase == 0) candidate = imageAtomicMin(nearestDepth, pixel, key) >= key || candidate;
            else if (stored == key) imageAtomicMin(nearestSegment, pixel, global);
        }
    }
}

// A segment whose capsule comes near the eye's plane has no one rectangle in front of the eye: it is bounded
// in kPieces pieces, each tested for the whole segment's crossings; a piece within about a radius of the eye,
// or across the plane of the eye, is left out, as the near plane clips triangle tubes.
const int kPieces = 8;

void drawSegment(Segment s, uint global) {
    vec2 corners[4];
    bool candidate = false, whole = screenQuad(s.p0, s.p1, corners);
    for (int k = 0, pieces = whole ? 1 : kPieces; k < pieces; ++k) {
        if (!whole && !screenQuad(mix(s.p0, s.p1, float(k) / float(kPieces)), mix(s.p0, s.p1, float(k + 1) / float(kPieces)), corners)) continue;
        walkQuad(s, global, corners, candidate);
    }
    if (candidate) atomicOr(candidates[global / 32u], 1u << (global % 32u));
}

void main() {
    if (phase == 2) {
        ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
        if (outsideImage(pixel)) return;
        uint winner = imageLoad(nearestSegment, pixel).x;
        if (winner < globalBase + firstPoint || winner - (globalBase + firstPoint) >= pointCount) return;
        Segment s = fetchSegment(int(winner - globalBase));
        PixelRays rays = pixelRays();
        vec3 dir = normalize(pixelRay(rays, pixel));
        float distance, along;
        vec3 normal;
        if (!hitSegment(s, dir, distance, normal, along)) return;
        imageStore(surfaceColor, pixel, vec4(mix(unpackColor(s.colors.x), unpackColor(s.colors.y), clamp(along, 0.0, 1.0)), 1.0));
        imageStore(surfaceNormal, pixel, vec4(normalize(normal), SURFACE_TUBE));
        imageStore(surfaceDepth, pixel, vec4(distance * dot(dir, viewForward)));
        return;
    }
    // Phase 1 takes the candidates only: a word of 32 points an invocation, its set bits in turn.
    uint index = gl_GlobalInvocationID.x;
    uint bits = 1u, firstOfWord = index;
    if (phase == 1) {
        uint word = (globalBase + firstPoint) / 32u + index;
        firstOfWord = word * 32u;
        if (firstOfWord >= globalBase + firstPoint + pointCount) return;
        bits = candidates[word];
        // Only the points of this dispatch's range [globalBase + firstPoint, + pointCount).
        uint from = globalBase + firstPoint, to = from + pointCount;
        if (from > firstOfWord) bits &= ~0u << (from - firstOfWord);
        if (to < firstOfWord + 32u) bits &= (1u << (to - firstOfWord)) - 1u;
        firstOfWord -= globalBase;   // as a texel
    } else if (index >= pointCount) {
        return;
    } else {
        firstOfWord = firstPoint + index;
    }
    while (bits != 0u) {
        int bit = findLSB(bits);
        bits &= bits - 1u;
        int texel = int(firstOfWord) + bit;
        uvec4 a = texelFetch(impostorPoints, texel);
        if ((a.w & SEGMENT_STARTS) == 0u) continue;   // a streamline's last point: no segment
        drawSegment(fetchSegment(texel), globalBase + uint(texel));
    }
}
