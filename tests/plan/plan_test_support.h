#pragma once
// Synthetic scans, transfer functions and analytic clip regions for the planning tests.

#include "base/transfer_function.h"
#include "base/volume.h"
#include "plan/removal_field.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <numbers>

namespace curette::plan::testing {

constexpr double kPi = std::numbers::pi;

// An axis-aligned grid with spacing `spacing` whose voxel centres span about [-halfExtent, halfExtent] mm.
inline glm::dmat4 gridAffine(glm::dvec3 spacing, glm::ivec3 dims) {
    glm::dmat4 m(1.0);
    for (int a = 0; a < 3; ++a) m[a][a] = spacing[a];
    m[3] = glm::dvec4(-0.5 * spacing * glm::dvec3(dims - 1), 1.0);
    return m;
}

inline glm::ivec3 dimsFor(glm::dvec3 spacing, double halfExtentMm) {
    return glm::ivec3(glm::ceil(2.0 * halfExtentMm / spacing)) + 1;
}

// Every voxel stores `value` (UNorm8, physical = stored).
inline VolumeData uniformVolume(glm::ivec3 dims, const glm::dmat4& indexToWorld, std::uint8_t value) {
    VolumeData v;
    v.dims = dims;
    v.indexToWorld = indexToWorld;
    v.format = StorageFormat::UNorm8;
    v.voxels.assign(v.voxelCount(), value);
    v.valueScale = 255.0;
    v.minValue = v.maxValue = value;
    v.source = "<synthetic>";
    return v;
}

// Transparent up to 100, opaque from 101 (physical values).
inline TransferFunction stepTf() {
    TransferFunction tf;
    tf.name = "step";
    tf.color = {{0.0, glm::dvec3(1.0)}};
    tf.opacity = {{0.0, 0.0}, {100.0, 0.0}, {101.0, 1.0}};
    return tf;
}

inline InsideTest sphere(glm::dvec3 centre, double radius) {
    return [=](glm::dvec3 p) { return glm::dot(p - centre, p - centre) < radius * radius; };
}

// A box of half-sizes `half`, rotated by `angleDeg` about `axis`, centred at `centre`.
inline InsideTest rotatedBox(glm::dvec3 centre, glm::dvec3 half, glm::dvec3 axis, double angleDeg) {
    glm::dmat3 rotation(glm::rotate(glm::dmat4(1.0), angleDeg * kPi / 180.0, glm::normalize(axis)));
    glm::dmat3 inverse = glm::transpose(rotation);
    return [=](glm::dvec3 p) {
        glm::dvec3 l = glm::abs(inverse * (p - centre));
        return l.x < half.x && l.y < half.y && l.z < half.z;
    };
}

// A torus about the z axis through `centre`: ring radius R, tube radius a.
inline InsideTest torus(glm::dvec3 centre, double R, double a) {
    return [=](glm::dvec3 p) {
        glm::dvec3 d = p - centre;
        double ring = std::sqrt(d.x * d.x + d.y * d.y) - R;
        return ring * ring + d.z * d.z < a * a;
    };
}

}  // namespace curette::plan::testing
