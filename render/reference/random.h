#pragma once
// CPU twin of shaders/random.glsl (PCG hash), bit for bit.

#include <glm/glm.hpp>

#include <cstdint>

namespace curette::reference {

inline std::uint32_t pcgHash(std::uint32_t v) {
    std::uint32_t state = v * 747796405u + 2891336453u;
    std::uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

inline double pixelRandom(glm::uvec2 pixel, std::uint32_t seed) {
    return static_cast<double>(pcgHash(pixel.x ^ pcgHash(pixel.y ^ pcgHash(seed))) >> 8u) * (1.0 / 16777216.0);
}

}  // namespace curette::reference
