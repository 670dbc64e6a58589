#pragma once
// The normal of a clip mesh's surface where a cut face lies (Weiskopf, Engel and Ertl 2003, sec. 5: the clip
// surface lights the face). A triangle mesh stands for a smooth surface with creases: at each corner of a
// triangle the normal is the area-weighted mean of the face normals around that vertex that turn less than
// the crease angle from this triangle's own, so an icosphere shades as a sphere and a box keeps its edges.
// The GPU draws these into the clip maps (render/passes/clip_mesh_set.cpp); the CPU twin reads them here.

#include "mesh/triangle_mesh.h"

#include <glm/glm.hpp>

#include <vector>

namespace curette::clip {

inline constexpr double kCreaseAngleDeg = 30.0;

// Three unit normals per triangle (triangle t's corners at 3t, 3t + 1, 3t + 2), of the mesh scaled by `scale`
// along its local axes (a non-uniform scale turns normals), pointing out.
std::vector<glm::vec3> cornerNormals(const TriangleMesh& mesh, glm::dvec3 scale, double creaseAngleDeg = kCreaseAngleDeg);

// The point of the scaled mesh's surface nearest `point` (scaled mesh-local millimetres) and the corner
// normals interpolated there (barycentric, unit length). A brute-force search: for oracles, not for frames.
struct SurfacePoint {
    glm::dvec3 point, normal;
};
SurfacePoint nearestSurfacePoint(const TriangleMesh& mesh, glm::dvec3 scale, const std::vector<glm::vec3>& corners, glm::dvec3 point);

}  // namespace curette::clip
