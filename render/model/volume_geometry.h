#pragma once
// Where a volume sits in the world and how world millimetres map to texture coordinates. This is the one
// place texture coordinates are derived from the affine (world space is RAS millimetres); every pass and
// every CPU reference uses it.

#include <glm/glm.hpp>

#include <array>

namespace curette {

struct VolumeGeometry {
    glm::ivec3 dims{1};
    glm::dmat4 indexToWorld{1.0};  // voxel centre (i,j,k) -> world mm

    glm::dmat4 worldToIndex() const { return glm::inverse(indexToWorld); }
    // texture = (index + 0.5) / dims: (0,0,0)..(1,1,1) spans the voxel cells.
    glm::dmat4 indexToTexture() const;
    glm::dmat4 worldToTexture() const { return indexToTexture() * worldToIndex(); }
    glm::dmat4 textureToWorld() const { return glm::inverse(worldToTexture()); }
    // Maps an index-space gradient (value per voxel step) to a world gradient (value per mm).
    glm::dmat3 gradientIndexToWorld() const { return glm::transpose(glm::inverse(glm::dmat3(indexToWorld))); }

    glm::dvec3 spacing() const;          // mm per index step along i, j, k
    double minSpacing() const;
    // Longest world length of a half-open voxel cell's diagonal: max over sign vectors s of |A s|, the
    // farthest any point within one voxel step (Chebyshev, index space) can be from a voxel centre.
    double cellDiagonalMm() const;
    // The eight world corners of the volume box (the cells' outer faces).
    std::array<glm::dvec3, 8> worldCorners() const;
    glm::dvec3 worldCenter() const;
    double boundingRadiusMm() const;     // radius of the sphere around worldCenter holding every corner
};

}  // namespace curette
