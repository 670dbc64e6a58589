#include "render/model/volume_geometry.h"

#include <algorithm>

namespace curette {

glm::dmat4 VolumeGeometry::indexToTexture() const {
    glm::dvec3 inv = 1.0 / glm::dvec3(dims);
    glm::dmat4 m(1.0);
    m[0][0] = inv.x, m[1][1] = inv.y, m[2][2] = inv.z;
    m[3] = glm::dvec4(0.5 * inv, 1.0);
    return m;
}

glm::dvec3 VolumeGeometry::spacing() const {
    return {glm::length(glm::dvec3(indexToWorld[0])), glm::length(glm::dvec3(indexToWorld[1])),
            glm::length(glm::dvec3(indexToWorld[2]))};
}

double VolumeGeometry::minSpacing() const {
    glm::dvec3 s = spacing();
    return std::min({s.x, s.y, s.z});
}

double VolumeGeometry::cellDiagonalMm() const {
    glm::dmat3 a(indexToWorld);
    double longest = 0;
    for (int sx : {-1, 1})
        for (int sy : {-1, 1})
            for (int sz : {-1, 1}) longest = std::max(longest, glm::length(a * glm::dvec3(sx, sy, sz)));
    return longest;
}

std::array<glm::dvec3, 8> VolumeGeometry::worldCorners() const {
    std::array<glm::dvec3, 8> corners;
    glm::dmat4 t = textureToWorld();
    for (int c = 0; c < 8; ++c)
        corners[static_cast<std::size_t>(c)] = glm::dvec3(t * glm::dvec4(c & 1, (c >> 1) & 1, (c >> 2) & 1, 1.0));
    return corners;
}

glm::dvec3 VolumeGeometry::worldCenter() const { return glm::dvec3(textureToWorld() * glm::dvec4(0.5, 0.5, 0.5, 1.0)); }

double VolumeGeometry::boundingRadiusMm() const {
    double r = 0;
    glm::dvec3 c = worldCenter();
    for (const glm::dvec3& p : worldCorners()) r = std::max(r, glm::length(p - c));
    return r;
}

}  // namespace curette
