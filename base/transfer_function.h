#pragma once
// A transfer function: piecewise-linear colour and opacity over the physical data value (and optionally an
// opacity factor over gradient magnitude, as 3D Slicer's volume properties have). Outside the first and last
// point the end values hold (as VTK clamps).
//
// Opacity is defined per unit length: `opacity` is the alpha of a slab `unitLengthMm` thick. A ray segment of
// length d takes alpha_d = 1 - (1 - alpha)^(d / unitLengthMm) (shaders/opacity.glsl).

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace curette {

struct TransferFunction {
    struct ColorPoint {
        double value;
        glm::dvec3 rgb;
    };
    struct ScalarPoint {
        double value;
        double y;
    };
    // Phong material carried by Slicer .vp files; used by `phong` shading when present.
    struct Material {
        double ambient = 0.2, diffuse = 0.8, specular = 0.3, specularPower = 20.0;
        bool operator==(const Material&) const = default;
    };

    std::string name;
    std::vector<ColorPoint> color;            // sorted by value, at least one point
    std::vector<ScalarPoint> opacity;         // sorted by value, at least one point, y in [0, 1]
    std::vector<ScalarPoint> gradientOpacity; // over |gradient| (value units per mm); empty means 1
    double unitLengthMm = 1.0;
    Material material;

    glm::dvec3 evaluateColor(double value) const;
    double evaluateOpacity(double value) const;
    double evaluateGradientOpacity(double gradientMagnitude) const;
    bool hasGradientOpacity() const;   // false when empty or constant 1
    // Smallest and largest value at which any point is defined (colour or opacity).
    double domainMin() const;
    double domainMax() const;
    // Checks sortedness, ranges and finiteness; throws InputError naming `file` and the offending field.
    void validate(const std::string& file) const;
};

}  // namespace curette
