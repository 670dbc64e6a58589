#pragma once
// Streamlines (fiber tracts) in world millimetres RAS, as the volume: one point array, one offset per
// streamline, and optional per-point scalars and per-streamline properties (TrackVis names them).

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace curette {

struct Tractogram {
    std::vector<glm::vec3> points;
    std::vector<std::uint32_t> offsets{0};    // streamline s spans points[offsets[s], offsets[s + 1])
    std::vector<std::string> scalarNames;     // per point; scalars.size() == points.size() * scalarNames.size()
    std::vector<float> scalars;
    std::vector<std::string> propertyNames;   // per streamline
    std::vector<float> properties;
    std::string source;

    std::size_t streamlineCount() const { return offsets.size() - 1; }
    std::size_t pointCount(std::size_t s) const { return offsets[s + 1] - offsets[s]; }
    // Appends `other`'s streamlines (scalars/properties kept only when both have the same names).
    void append(const Tractogram& other);
};

}  // namespace curette
