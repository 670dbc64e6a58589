#pragma once
// CPU double-precision twin of GL texture sampling: trilinear filtering with clamp-to-edge (or a zero
// border) over texture coordinates, exactly as the GL specification defines it (OpenGL 4.5 core, 8.14.2).
// Used by every CPU reference so GPU kernels and oracles agree on what "a sample" is.

#include <glm/glm.hpp>

#include <functional>
#include <vector>

namespace curette::reference {

enum class Wrap { ClampToEdge, ZeroBorder };

// f(i, j, k) gives the texel at integer coordinates inside the grid.
double sampleTrilinear(const std::function<double(int, int, int)>& texel, glm::ivec3 dims, glm::dvec3 tex, Wrap wrap);

// A dense double grid with trilinear sampling.
struct Grid {
    glm::ivec3 dims{0};
    std::vector<double> values;  // i fastest
    double at(int i, int j, int k) const {
        return values[(static_cast<std::size_t>(k) * static_cast<std::size_t>(dims.y) + static_cast<std::size_t>(j)) *
                          static_cast<std::size_t>(dims.x) + static_cast<std::size_t>(i)];
    }
    double& at(int i, int j, int k) {
        return values[(static_cast<std::size_t>(k) * static_cast<std::size_t>(dims.y) + static_cast<std::size_t>(j)) *
                          static_cast<std::size_t>(dims.x) + static_cast<std::size_t>(i)];
    }
    double sample(glm::dvec3 tex, Wrap wrap) const;
};

}  // namespace curette::reference
