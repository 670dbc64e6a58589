#pragma once
// The ruler: a distance between two points a planner picks, in the 3-D view (on the first visible surface,
// render/model/surface_pick.h) or on a slice (the slice's pixel centre). Each point carries how far it may lie
// from where the planner meant it (half a ray step along the ray, half a slice pixel), so the distance is
// shown with its uncertainty. No GL call.

#include <glm/glm.hpp>

#include <optional>

namespace curette {

struct RulerPoint {
    glm::dvec3 world{0.0};        // RAS mm
    double uncertaintyMm = 0;     // the point lies within this of the surface or pixel it was picked on
};

struct RulerLength {
    double mm = 0;
    double uncertaintyMm = 0;     // the two points' uncertainties added (the triangle inequality)
};

class Ruler {
public:
    // The first point, then the second; a third starts a new measurement from it.
    void place(const RulerPoint& p);
    void clear() { a_.reset(), b_.reset(); }
    const std::optional<RulerPoint>& first() const { return a_; }
    const std::optional<RulerPoint>& second() const { return b_; }
    std::optional<RulerLength> length() const;

private:
    std::optional<RulerPoint> a_, b_;
};

}  // namespace curette
