#pragma once
// Where things sit in the viewer's window: the 3-D view and, beside it, one fixed side bar that holds every
// panel (status, plan, slices, settings), so no panel covers the volume. The side bar folds away (F2) and the
// view takes the window. Rectangles are in framebuffer pixels, origin at the top left.

#include <glm/glm.hpp>

namespace curette {

struct ViewRect {
    glm::ivec2 origin{0};
    glm::ivec2 size{0};
    long long area() const { return static_cast<long long>(size.x) * size.y; }
    bool contains(glm::dvec2 p) const {
        return p.x >= origin.x && p.y >= origin.y && p.x < origin.x + size.x && p.y < origin.y + size.y;
    }
    bool operator==(const ViewRect&) const = default;
};

struct ViewLayout {
    ViewRect view;      // the 3-D view: the image is rendered at this size
    ViewRect sidebar;   // empty when folded
};

// The side bar's width: a quarter of the window less a little (so the view keeps more than three quarters of
// a 1024x768 window), at least kMinSidebarPoints wide so the panels' widgets fit, and never more than half.
inline constexpr double kSidebarShare = 0.24;
inline constexpr double kMinSidebarPoints = 230;

ViewLayout viewLayout(glm::ivec2 framebuffer, double pixelsPerPoint, bool sidebarOpen);

}  // namespace curette
