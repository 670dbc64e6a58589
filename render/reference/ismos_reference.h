#pragma once
// CPU double-precision oracles of ISMOS (seed 003):
//  - ismosOcclusionPixel: the twin of pass 2 (shaders/ismos_occlusion.comp) on the layers the GPU wrote,
//    read back; the kernel test compares the two tightly;
//  - physicalOcclusion: what the image-space model approximates. From the shaded point (the same world point
//    the layer front stands for) rays go to points on the same light disk in world space and march through
//    the real volume (trilinear, the TF, the opacity correction, an analytic clip test) and stop at tube
//    triangles (opaque); the occlusion is one minus their mean transmittance. With the light's own N samples
//    it isolates the height-field error; with many stratified points it is the exact soft shadow.

#include "base/transfer_function.h"
#include "base/volume.h"
#include "render/model/frame.h"
#include "render/model/ismos_model.h"
#include "render/model/tube_vertices.h"

#include <functional>
#include <vector>

namespace curette::reference {

struct IsmosPixel {
    bool shaded = false;          // a layer got occlusion (false: the pixel keeps its colour)
    double occlusion = 0;         // Occ, blended over the shaded layers
    glm::dvec3 light{1.0};        // eq. 15's light factor
    glm::dvec3 factor{1.0};       // what the colour is multiplied by: light * max(1 - Occ, I_amb)
};

class OccluderTriangles;

// The twin of pass 1's additions (shaders/ismos_layers.glsl) for one pixel without clip meshes: the same
// rays and sample lattice as reference::raycastPixel, the layers and the fit's beta. With `tubes` the ray
// stops before the first tube surface it meets, which becomes an opaque layer `tubeThicknessMm` thick
// (raycast.comp, ISMOS_TUBES).
struct IsmosLayersPixel {
    glm::dvec4 front{-1.0}, alpha{0.0}, back{-1.0};   // back -1e30: the ray terminated in the layer
    double beta = 0;
};
IsmosLayersPixel ismosLayersPixel(const VolumeData& volume, const TransferFunction& tf, const FrameDescription& frame, double stepMm,
                                  const IsmosSpace& space, glm::ivec2 pixel, const OccluderTriangles* tubes = nullptr,
                                  double tubeThicknessMm = 0.0);

// `stepDepth`: one ray-casting step in depth units (stepMm / (far - near)).
IsmosPixel ismosOcclusionPixel(const IsmosLayerImages& layers, const std::vector<IsmosLight>& lights, const IsmosSettings& settings,
                               const IsmosSpace& space, double stepDepth, glm::ivec2 pixel);

// The world point of a texture-space light point: the box's affine map at the volume centre's depth (the
// map that carries camera directions into the box, IsmosSpace::lightDirection), so a light's world
// direction is its phong direction.
glm::dvec3 lightPointWorld(const IsmosSpace& space, glm::dvec3 volumeCentre, glm::dvec3 tex);

// Opaque triangles in world mm (tubes: they are opaque in pass 1, so the reference treats them so), in a
// bounding-volume hierarchy (median splits, at most 4 triangles a leaf) for segment queries.
class OccluderTriangles {
public:
    OccluderTriangles() = default;
    explicit OccluderTriangles(const TubeVertices& tubes);   // illuminated lines have no area: no occluders
    bool empty() const { return triangles_.empty(); }
    std::size_t size() const { return triangles_.size(); }
    // The parameter t in (tMin, tMax] of the first crossing of a + t (b - a) with a triangle, or -1.
    double firstHit(glm::dvec3 a, glm::dvec3 b, double tMin = 0.0, double tMax = 1.0) const;
    bool blocks(glm::dvec3 a, glm::dvec3 b) const { return firstHit(a, b) >= 0.0; }

private:
    struct Triangle {
        glm::dvec3 p0, e1, e2;
    };
    struct Node {
        glm::dvec3 lo, hi;
        std::uint32_t first = 0, count = 0;   // count > 0: a leaf over triangles_[first, first + count)
        std::uint32_t left = 0, right = 0;
    };
    std::uint32_t build(std::uint32_t first, std::uint32_t count, std::vector<glm::dvec3>& centroids);
    std::vector<Triangle> triangles_;
    std::vector<Node> nodes_;
};

struct PhysicalSettings {
    double stepMm = 0.5;
    double startOffsetMm = 1.0;                       // leave the shaded surface's own sample behind
    std::function<bool(glm::dvec3)> insideClip;        // world mm; empty: no clipping
    const OccluderTriangles* tubes = nullptr;          // opaque occluders; null: none
};

// Eq. 13-14 and 16 with physical transmittance: one minus the mean transmittance from world point `p`
// (texture point `pTex`) to `points[j]` of every light j (texture space; lights outside their cone count as
// fully occluded). A path that crosses a tube triangle (beyond startOffsetMm) transmits nothing.
double physicalOcclusion(const VolumeData& volume, const TransferFunction& tf, const IsmosSpace& space, glm::dvec3 volumeCentre,
                         const std::vector<IsmosLight>& lights, const std::vector<std::vector<glm::dvec3>>& points, glm::dvec3 pTex,
                         const PhysicalSettings& settings);

}  // namespace curette::reference
