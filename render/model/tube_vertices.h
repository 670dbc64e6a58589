#pragma once
// Tube and line geometry as the CPU builds it (render/model/tube_geometry.h) and how tubes are shaded: plain data,
// no GL, so scene/ and session/ can hold them; render/passes/tube_set.h puts them on the GPU.

#include "base/transfer_function.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace curette {

// Vertex streams as drawn: triangles for tubes, GL_LINES pairs for illuminated lines.
struct TubeVertices {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> directions;   // normals (tubes) or tangents (lines), unit
    std::vector<glm::vec4> colors;
    std::vector<std::uint32_t> indices;
    bool lines = false;
};

// How tubes take part in the combined occlusion (seed 000) and how they are lit.
struct TubeShading {
    double geometryOpacity = 0.9;      // opacity of one crossing of a tube in the occlusion buffer (Algorithm 3)
    double thicknessMm = 1.0;          // the view depth a tube fills behind its surface there (its diameter;
                                       // configureRenderer sets twice the scene's largest tube radius)
    double vicinityDistanceMm = 3.0;   // l_vicinity: the vicinity radius is l_vicinity tan(theta) (section 3.1.5)
    int vicinitySamples = 64;          // Poisson-disk samples (the paper: up to 118)
    double depthBiasMm = 0.5;          // an occluding neighbour must be this much nearer (Algorithm 5)
    double lineDiffuseExponent = 2.0;  // p of seed 004 eq. 3.15 (Banks: 4.8; the chapter: 2)
    TransferFunction::Material material{0.25, 0.75, 0.35, 32.0};
    bool operator==(const TubeShading&) const = default;
};

}  // namespace curette
