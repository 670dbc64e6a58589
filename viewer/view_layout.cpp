#include "viewer/view_layout.h"

#include <algorithm>
#include <cmath>

namespace curette {

ViewLayout viewLayout(glm::ivec2 framebuffer, double pixelsPerPoint, bool sidebarOpen) {
    ViewLayout layout;
    int width = 0;
    if (sidebarOpen) {
        double wanted = std::max(kSidebarShare * framebuffer.x, kMinSidebarPoints * pixelsPerPoint);
        width = static_cast<int>(std::lround(std::min(wanted, 0.5 * framebuffer.x)));
    }
    layout.view = {{0, 0}, {std::max(framebuffer.x - width, 1), std::max(framebuffer.y, 1)}};
    if (width > 0) layout.sidebar = {{framebuffer.x - width, 0}, {width, framebuffer.y}};
    return layout;
}

}  // namespace curette
