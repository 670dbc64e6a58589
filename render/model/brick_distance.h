#pragma once
// The distance map the ray caster skips empty space with: per brick, the Chebyshev distance (in bricks) to
// the nearest brick a visible sample can lie in. A brick at distance d > 0 is the centre of a cube of
// (2d - 1)^3 bricks that are all empty, so a ray in it may jump to where it leaves that cube without passing
// a sample that could be visible (shaders/raycast.comp). CPU only, no GL.

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace curette {

// `occupied` holds one flag per brick (x fastest over `grid`); the result one distance per brick: 0 for an
// occupied brick, else the Chebyshev distance to the nearest occupied one, capped at `cap` (also where no
// brick is occupied). The 26-neighbour breadth-first search gives the Chebyshev metric exactly.
std::vector<std::uint8_t> chebyshevBrickDistance(const std::vector<bool>& occupied, glm::ivec3 grid, int cap);

}  // namespace curette
