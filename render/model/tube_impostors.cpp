#include "render/model/tube_impostors.h"

#include <algorithm>
#include <cmath>

namespace curette {

std::uint32_t packImpostorColor(glm::vec4 color, std::uint32_t flags) {
    auto byte = [](float c) { return static_cast<std::uint32_t>(std::lround(std::clamp(c, 0.0f, 1.0f) * 255.0f)); };
    return byte(color.r) | byte(color.g) << 8 | byte(color.b) << 16 | flags;
}

glm::vec3 unpackImpostorColor(std::uint32_t c) {
    return glm::vec3(float(c & 0xFFu), float(c >> 8 & 0xFFu), float(c >> 16 & 0xFFu)) / 255.0f;
}

void TubeImpostors::append(const TubeImpostors& other) {
    if (other.points.empty()) return;
    if (points.empty()) boundsMin = other.boundsMin, boundsMax = other.boundsMax;
    else boundsMin = glm::min(boundsMin, other.boundsMin), boundsMax = glm::max(boundsMax, other.boundsMax);
    std::size_t base = points.size();
    points.insert(points.end(), other.points.begin(), other.points.end());
    for (TubeImpostorBundle b : other.bundles) {
        b.firstPoint += base;
        bundles.push_back(b);
    }
    streamlines += other.streamlines;
}

}  // namespace curette
