#pragma once
// The clipping camera of one mesh (CAO section 3.2 and step II): orthographic, attached to the mesh and
// looking along the mesh's local +z, fitted to the mesh's bounds plus a margin that holds the dilated shape
// (step III). Map coordinates: x, y in [0, 1] across the square map, depth = local z in millimetres.
// Because it is attached to the mesh, a rigid motion of the mesh changes only worldToMap.
// Two squares: the map square (bounds plus the dilation margin) holds the dilated maps; the depth square
// (the bounds and two depth pixels) holds the depth maps at their own, fine resolution, so a face across the
// map is placed to a depth pixel (a small fraction of a voxel) however wide the dilation margin is.

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
    glm::dvec2 depthOrigin{0.0};              // local x, y of the depth square's corner (0, 0)
    double depthSizeMm = 1.0;                 // its side in local millimetres (inside the map square)
    int depthResolution = 1024;               // its pixels per side

    double pixelMm() const { return mapSizeMm / resolution; }   // a dilated map's pixel
    double depthPixelMm() const { return depthSizeMm / depthResolution; }
    // Map x, y -> depth-map x, y (both in [0, 1] over their squares): (m - offset) * scale.
    glm::dvec2 depthOffset() const { return (depthOrigin - mapOrigin) / mapSizeMm; }
    double depthScale() const { return mapSizeMm / depthSizeMm; }
    // local -> map (x, y in [0,1], z = local z in mm)
    glm::dmat4 localToMap() const;
    glm::dmat4 worldToMap(const RigidPose& pose) const { return localToMap() * pose.inverseMatrix(); }
    // local -> GL clip space for rasterising step II over the depth square (depth range: the bounds plus the margin).
    glm::dmat4 localToClip() const;
};

// Fits a camera to `localMin..localMax` with room for a dilation of `dilationRadiusMm` (plus the pixel
// margin the dilation adds, see ClipMeshSet::kernelRadiusMm) at `resolution` pixels, and its depth square at
// `depthResolution` pixels.
ClippingCamera fitClippingCamera(glm::dvec3 localMin, glm::dvec3 localMax, double dilationRadiusMm, int resolution,
                                 int depthResolution);

}  // namespace curette::clip
