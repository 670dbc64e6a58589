#pragma once
// How the clip meshes themselves are drawn over the image (render/clip_mesh_overlay.h): the planner's tools
// made visible. Plain data: the scene reader fills it ("clip_mesh_display", scene/scene.h), the overlay reads
// it. The overlay is presentation, never part of the renderer's image (docs/architecture.md, "Preview and
// exact frames").

#include <glm/glm.hpp>

namespace curette {

struct ClipMeshDisplay {
    double fillOpacity = 0.22;      // the nearest mesh surface, in the mesh's own colour
    double outlineOpacity = 0.9;    // its silhouette and creases
    bool operator==(const ClipMeshDisplay&) const = default;
};

// Mesh `index`'s colour (a palette of hues, repeating), never the held mesh's.
glm::vec3 clipMeshColor(int index);
// The held mesh (the one a device or the keyboard moves): this colour, and more opaque.
inline constexpr glm::vec3 kHeldClipMeshColor{1.0f, 0.82f, 0.1f};
// The opacities of the held mesh, from the display's: its fill a little more opaque (up to 0.6, never
// less than the others'; not so much that it hides the cut it makes), its outline opaque.
double heldFillOpacity(const ClipMeshDisplay& display);
double heldOutlineOpacity(const ClipMeshDisplay& display);

}  // namespace curette
