#pragma once
// The slice views (3D Slicer's four-up): axial, coronal and sagittal reslices of the scan through a
// crosshair, in world RAS millimetres (not voxel index: the grid may be oblique or anisotropic), with the
// removed region, label outlines, the clip meshes' cross-sections, the crosshair and orientation letters
// drawn in. One function makes them for the viewer's slice panel and for `curette render --slices`, so
// the two show the same pixels.
//
// Display orientation (radiological, as Slicer shows it; RAS: +x Right, +y Anterior, +z Superior):
//   axial     anterior at the top, the patient's Left on the image's right (seen from the feet)
//   coronal   superior at the top, the patient's Left on the image's right (seen from the front)
//   sagittal  superior at the top, anterior on the image's left (seen from the patient's Left)
// Pixels are square, the scan's smallest spacing wide; each image covers the scan's world bounding box
// (its voxels' outer corners) projected on its plane. Grey values are trilinear samples of the physical
// value through the inverse affine; a sample outside the grid or touching a voxel without data is black
// (the ray caster's no-data rule: such a sample is transparent). Overlays read the voxel nearest the pixel
// centre (labels and the removed region are voxel sets, never interpolated).

#include "base/label_map.h"
#include "base/volume.h"
#include "plan/removal_field.h"
#include "render/model/image.h"

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

namespace curette {

enum class SliceAxis { Axial, Coronal, Sagittal };
inline constexpr std::array<SliceAxis, 3> kSliceAxes{SliceAxis::Axial, SliceAxis::Coronal, SliceAxis::Sagittal};
const char* sliceAxisName(SliceAxis axis);   // "axial", "coronal", "sagittal"

// The grey-level window: physical values lo and below are black, hi and above white.
struct GreyWindow {
    double lo = 0, hi = 1;
    bool operator==(const GreyWindow&) const = default;
};

// A slice's pixel grid on its plane. Pixel coordinates are continuous: (0, 0) is the image's top-left
// corner, pixel (i, j) (column i, row j, row 0 at the top) has its centre at (i + 0.5, j + 0.5).
struct SlicePlane {
    SliceAxis axis = SliceAxis::Axial;
    glm::ivec2 sizePx{0};
    double pixelMm = 1.0;
    glm::dvec3 topLeft{0.0};   // world point at pixel coordinates (0, 0), on the plane
    glm::dvec3 right{0.0};     // unit world direction of the image's +x
    glm::dvec3 down{0.0};      // unit world direction of the image's +y (down the rows)
    glm::dvec3 normal{0.0};    // unit world axis across the plane: +S (axial), +A (coronal), +R (sagittal)
    bool operator==(const SlicePlane&) const = default;

    glm::dvec3 worldAt(glm::dvec2 pixel) const { return topLeft + pixelMm * (pixel.x * right + pixel.y * down); }
    // The world point's pixel coordinates (its projection onto the plane).
    glm::dvec2 pixelAt(glm::dvec3 world) const {
        glm::dvec3 d = world - topLeft;
        return {glm::dot(d, right) / pixelMm, glm::dot(d, down) / pixelMm};
    }
    // Signed distance of a world point from the plane, along `normal`.
    double offsetMm(glm::dvec3 world) const { return glm::dot(world - topLeft, normal); }
};

// The plane of `axis` through `crosshair` (world RAS mm) over a grid's world bounding box, pixels of the
// grid's smallest spacing (plan::gridSpacingMm).
SlicePlane slicePlane(glm::ivec3 dims, const glm::dmat4& indexToWorld, SliceAxis axis, glm::dvec3 crosshair);


// A label set as the slices outline it: the labels on the scan grid and, by id, the outline colour
// (alpha 1: outlined, 0: not).
struct SliceLabelSet {
    const LabelMap* labels = nullptr;   // on the scan grid; must outlive the call
    std::vector<glm::vec4> outlineById;
};
// The outlines of a set: the ids it shows in their table colour, the protected ids (shown or not) red.
SliceLabelSet sliceLabelSet(const LabelMap& onScanGrid, const LabelTable& table, const std::vector<bool>& shownById,
                            const std::vector<int>& protectedIds);

struct SliceMesh {
    plan::PosedMesh mesh;
    bool held = false;   // the mesh the user moves: drawn brighter
};

struct SliceOverlays {
    // The removed region on the scan grid (plan::removedRegionOnGrid, the voxels removed.nii.gz marks: 1 =
    // removed), or null. Must outlive the call.
    const std::vector<std::uint8_t>* removedRegion = nullptr;
    std::vector<SliceLabelSet> labelSets;
    std::vector<SliceMesh> meshes;
    bool crosshairLines = true;
    bool orientationLetters = true;
};

// The colours the overlays are drawn in (tests and the viewer's legend read them).
inline constexpr glm::vec3 kRemovedColor{1.0f, 0.55f, 0.1f};    // fill at kRemovedFillAlpha, outline opaque
inline constexpr float kRemovedFillAlpha = 0.4f;
inline constexpr glm::vec3 kProtectedColor{1.0f, 0.1f, 0.1f};
inline constexpr glm::vec3 kMeshColor{0.1f, 0.6f, 0.9f};
inline constexpr glm::vec3 kHeldMeshColor{0.55f, 1.0f, 1.0f};
inline constexpr glm::vec3 kCrosshairColor{0.3f, 0.9f, 0.3f};
inline constexpr float kCrosshairAlpha = 0.6f;
inline constexpr glm::vec3 kLetterColor{1.0f, 0.85f, 0.3f};

struct SliceImage {
    SlicePlane plane;
    glm::dvec3 crosshair{0.0};
    GreyWindow window;
    Image image;   // opaque RGBA, row 0 at the top
};

// The reslice of `axis` through `crosshair` with the overlays drawn in this order: grey levels, removed
// region (fill, then outline: removed pixels with a 4-neighbour not removed), label outlines (the pixels of
// an outlined id with a 4-neighbour of another id), mesh cross-sections (1-pixel lines), crosshair lines,
// orientation letters (5x7 pixels at the middle of each edge).
SliceImage renderSlice(const VolumeData& volume, SliceAxis axis, glm::dvec3 crosshair, GreyWindow window, const SliceOverlays& overlays);

// A posed mesh's cross-section with the plane: one segment (world points) per triangle that crosses it.
std::vector<std::pair<glm::dvec3, glm::dvec3>> meshCrossSection(const plan::PosedMesh& mesh, const SlicePlane& plane);

// The voxel whose centre is nearest a world point, or nothing outside the grid.
std::optional<glm::ivec3> nearestVoxel(glm::ivec3 dims, const glm::dmat4& worldToIndex, glm::dvec3 world);

}  // namespace curette
