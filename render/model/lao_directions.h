#pragma once
// Ray directions for Local Ambient Occlusion (CAO eq. 3). The paper's patterns come from the 26-neighbourhood
// of a voxel: 6 (face neighbours, Manhattan distance 1), 14 (faces and corners, Manhattan 1 and 3), 26 (all
// neighbours), 54 (the centres of the 9 facelets of each face of a Rubik's cube); any K from the spherical
// Fibonacci lattice (K = 512 is the ground truth of Tables 5 and 6). The patterns are jittered by a small
// deterministic amount (the paper: "with a jittering factor added to increase the randomness").

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace curette {

struct LaoDirection {
    glm::dvec3 direction;  // unit, world space
    double weight;         // w_k of eq. 3, normalised so the weights average 1
};

enum class LaoPattern { Neighbourhood6, Neighbourhood14, Neighbourhood26, Rubik54, Fibonacci };

struct LaoDirectionSet {
    LaoPattern pattern = LaoPattern::Neighbourhood26;
    int count = 26;              // K of the Fibonacci lattice (>= 1); the other patterns have their own K and ignore it
    double jitter = 0.025;       // per-component uniform jitter in [-jitter, jitter], then renormalised
    std::uint32_t seed = 1;
    bool skyWeighting = false;   // w_k = 0.5 + 0.5 * d_k.z (light from superior), normalised; else uniform

    std::vector<LaoDirection> build() const;   // K directions: K is the list's length, whatever `count` says
    std::string describe() const;  // e.g. "26 (neighbourhood, jitter 0.025)", with the built list's K
};

// Parses "6", "14", "26", "54", or "fibonacci:K" (also "fib512"). Returns false when not one of these.
bool parseLaoPattern(const std::string& text, LaoDirectionSet& out);

}  // namespace curette
