#pragma once
// Procedural clip meshes, centred at the origin, parameters in millimetres, axis along +z where there is one;
// closed and outward-facing. Bad parameters (not positive and finite, a torus tube wider than its ring, too
// few segments) are InputErrors naming the parameter.

#include "mesh/triangle_mesh.h"

namespace curette::clip {

TriangleMesh makeSphere(double radiusMm, int subdivisions = 4);                 // icosphere
TriangleMesh makeBox(glm::dvec3 sizeMm);
TriangleMesh makeCylinder(double radiusMm, double heightMm, int segments = 64);
TriangleMesh makeCone(double radiusMm, double heightMm, int segments = 64);     // base at -height/2
TriangleMesh makeCapsule(double radiusMm, double cylinderLengthMm, int segments = 48);
TriangleMesh makeTorus(double majorRadiusMm, double minorRadiusMm, int majorSegments = 96, int minorSegments = 48);

}  // namespace curette::clip
