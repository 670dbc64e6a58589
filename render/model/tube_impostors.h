#pragma once
// Impostor tubes (issue 32): the GPU keeps only each streamline's swept points, 16 bytes a point, and the
// G-buffer pass (shaders/tube_impostor.comp) bounds every segment's capsule on the screen and intersects each
// pixel's ray there with the exact tube. No vertex rings:
// a 100k whole-brain set is about 1 kB per streamline instead of 25 kB of triangles.
//
// The tube of a bundle is the union, per segment between consecutive points p_i, p_i+1, of the cylinder of
// radius r around it and, where the streamline goes on (p_i+1 is not its last point), the ball of radius r at
// p_i+1, so a bend has no gap. Its ends are open like the triangle tubes without caps, or closed by flat discs
// with caps. The points are the ones the triangle tubes put their rings at (sweepCurve: the same cleaning,
// Catmull-Rom resampling and colours), so the two differ only by the prism's facets and the joints.

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace curette {

// One point: world position and its colour with two flags, RGB8 in the low bytes and the flags in the high one.
struct TubeImpostorPoint {
    glm::vec3 position;
    std::uint32_t colorAndFlags = 0;
};
static_assert(sizeof(TubeImpostorPoint) == 16);

// Flags (bits 24-31 of colorAndFlags): whether a segment starts at the point (it is not its streamline's last)
// and whether one ends there (it is not the first). The GPU takes a segment per point; a point without a
// segment starting there is passed over.
inline constexpr std::uint32_t kImpostorSegmentStarts = 1u << 24;
inline constexpr std::uint32_t kImpostorSegmentEnds = 1u << 25;

std::uint32_t packImpostorColor(glm::vec4 color, std::uint32_t flags);   // RGB to 8 bits, rounded
glm::vec3 unpackImpostorColor(std::uint32_t colorAndFlags);

// A scene entry's points with its radius and caps (a draw each).
struct TubeImpostorBundle {
    std::size_t firstPoint = 0, pointCount = 0;
    double radiusMm = 0.5;
    bool caps = false;
};

struct TubeImpostors {
    std::vector<TubeImpostorPoint> points;
    std::vector<TubeImpostorBundle> bundles;
    std::size_t streamlines = 0;
    glm::dvec3 boundsMin{0.0}, boundsMax{0.0};   // a world box holding every tube (points widened by the radius)
    // Appends `other`'s bundles after these.
    void append(const TubeImpostors& other);
    std::size_t bytes() const { return points.size() * sizeof(TubeImpostorPoint); }
};

}  // namespace curette
