#pragma once
// The clipping camera of one mesh (CAO section 3.2 and step II): orthographic, attached to the mesh and
// looking along the mesh's local +z, fitted to the mesh's bounds plus a margin that holds the dilated shape
// (step III). Map coordinates: x, y in [0, 1] across the square map, depth = local z in millimetres.
// Because it is attached to the mesh, a rigid motion of the mesh changes only worldToMap.

#include "mesh/rigid_pose.h"

#include <glm/glm.hpp>

namespace curette::clip {

struct ClippingCamera {
    glm::dvec3 localMin{0.0}, localMax{0.0};  // the mesh's local bounds (scaled geometry)
    double hullRadiusMm = 0.0;                // the farthest (scaled) vertex from the bounds' centre: a ball
                                              // around it there holds the mesh's convex hull
    glm::dvec2 mapOrigin{0.0};                // local x, y of the map's corner (0, 0)
    double mapSizeMm = 1.0;                   // side of the square map in local millimetres
    int resolution = 256;                     // pixels per side
    double marginMm = 0.0;                    // space around the bounds for the dilated shape

    double pixelMm() const { return mapSizeMm / resolution; }
    // local -> map (x, y in [0,1], z = local z in mm)
    glm::dmat4 localToMap() const;
    glm::dmat4 worldToMap(const RigidPose& pose) const { return localToMap() * pose.inverseMatrix(); }
    // local -> GL clip space for rasterising step II (depth range: the bounds plus the margin).
    glm::dmat4 localToClip() const;
};

// Fits a camera to `localMin..localMax` with room for a dilation of `dilationRadiusMm` (plus the pixel
// margin the dilation adds, see ClipMeshSet::kernelRadiusMm) at `resolution` pixels.
ClippingCamera fitClippingCamera(glm::dvec3 localMin, glm::dvec3 localMax, double dilationRadiusMm, int resolution);

}  // namespace curette::clip
