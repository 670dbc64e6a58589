#pragma once
// A clip mesh's geometry: triangles in mesh-local millimetres, counter-clockwise seen from outside. Clip
// meshes must be closed (CAO section 3.1: the inside is where the depth intervals say, so there must be an
// inside); validateClosed checks it.

#include "mesh/solid_shape.h"

#include <glm/glm.hpp>

#include <optional>

#include <string>
#include <vector>

namespace curette::clip {

struct TriangleMesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::uvec3> triangles;
    std::string source;  // file or primitive description, for messages
    std::optional<SolidShape> solid;   // the analytic solid a primitive approximates (a drill burr removes it)

    glm::dvec3 boundsMin() const;
    glm::dvec3 boundsMax() const;
    double signedVolume() const;   // > 0 when the triangles face outwards
    double surfaceArea() const;
};

// Merges vertices closer than `tolerance` (glTF exporters split vertices along seams) and drops triangles
// that became degenerate.
void weldVertices(TriangleMesh& mesh, double tolerance);

// Throws InputError(source, "mesh", ...) unless every edge is shared by exactly two triangles, once in each
// direction (a closed, consistently oriented surface), and there is at least one triangle.
void validateClosed(const TriangleMesh& mesh);

// Flips every triangle when the mesh faces inwards (negative signed volume).
void orientOutward(TriangleMesh& mesh);

// Inside test by the generalised winding number (solid angles, Van Oosterom & Strackee 1983): exact for
// closed meshes away from the surface; the CPU oracle for the GPU clip test.
bool containsPoint(const TriangleMesh& mesh, glm::dvec3 point);

}  // namespace curette::clip
