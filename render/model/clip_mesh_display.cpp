#include "render/model/clip_mesh_display.h"

#include <algorithm>
#include <array>

namespace curette {

glm::vec3 clipMeshColor(int index) {
    // Cool hues, far from the held mesh's yellow and from the protected structures' red.
    static constexpr std::array<glm::vec3, 6> kPalette{{
        {0.2f, 0.8f, 1.0f},   // cyan
        {0.75f, 0.45f, 1.0f}, // violet
        {0.3f, 1.0f, 0.55f},  // green
        {0.35f, 0.5f, 1.0f},  // blue
        {1.0f, 0.45f, 0.85f}, // pink
        {0.55f, 0.95f, 0.95f},// pale teal
    }};
    return kPalette[static_cast<std::size_t>(std::max(index, 0)) % kPalette.size()];
}

double heldFillOpacity(const ClipMeshDisplay& display) { return std::max(display.fillOpacity, std::min(0.6, 1.3 * display.fillOpacity)); }

double heldOutlineOpacity(const ClipMeshDisplay&) { return 1.0; }

}  // namespace curette
