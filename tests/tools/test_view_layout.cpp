// The viewer's layout (viewer/view_layout.h) and orientation marker (viewer/orientation_marker.h): the side bar
// leaves the 3-D view more than three quarters of a 1024x768 window and never overlaps it; the marker's
// letters point where the patient's sides are.
#include "viewer/orientation_marker.h"
#include "viewer/view_layout.h"

#include <gtest/gtest.h>

namespace curette {
namespace {

TEST(ViewLayout, TheViewKeepsThreeQuartersOfTheWindowAndNoPanelCoversIt) {
    for (glm::ivec2 window : {glm::ivec2(1024, 768), glm::ivec2(1280, 1024), glm::ivec2(1920, 1080), glm::ivec2(800, 600)}) {
        ViewLayout l = viewLayout(window, 1.0, true);
        // From 1024 pixels wide the bar is a share of the window; below, its widgets' minimum width.
        if (window.x >= 1024) EXPECT_GE(static_cast<double>(l.view.area()), 0.75 * window.x * window.y) << window.x << "x" << window.y;
        else EXPECT_EQ(l.sidebar.size.x, static_cast<int>(kMinSidebarPoints));
        EXPECT_EQ(l.view.origin, glm::ivec2(0));
        EXPECT_EQ(l.view.size.x + l.sidebar.size.x, window.x);
        EXPECT_EQ(l.sidebar.origin.x, l.view.size.x);   // beside it, not over it
        EXPECT_GE(l.sidebar.size.x, kMinSidebarPoints);
    }
    ViewLayout folded = viewLayout({1024, 768}, 1.0, false);
    EXPECT_EQ(folded.view.size, glm::ivec2(1024, 768));
    EXPECT_EQ(folded.sidebar.area(), 0);
    // On a high-density screen the widgets need more pixels: the bar grows, but never past half the window.
    ViewLayout dense = viewLayout({800, 600}, 2.0, true);
    EXPECT_EQ(dense.sidebar.size.x, 400);
}

char axisAt(const std::array<MarkerAxis, 6>& axes, glm::dvec2 direction) {
    for (const MarkerAxis& a : axes)
        if (glm::dot(a.screen, direction) > 0.9) return a.label;
    return '?';
}

TEST(OrientationMarker, LettersPointToThePatientsSides) {
    OrbitCamera camera;
    camera.target = {5, -3, 2};
    // From the front: the patient's right on screen left, superior up (screen y grows down).
    auto front = orientationMarker(viewedFrom(camera, StandardView::Anterior));
    EXPECT_EQ(axisAt(front, {-1, 0}), 'R');
    EXPECT_EQ(axisAt(front, {1, 0}), 'L');
    EXPECT_EQ(axisAt(front, {0, -1}), 'S');
    EXPECT_EQ(axisAt(front, {0, 1}), 'I');
    EXPECT_EQ(front.back().label, 'A');   // pointing at the camera: drawn last
    EXPECT_EQ(front.front().label, 'P');
    auto left = orientationMarker(viewedFrom(camera, StandardView::Left));
    EXPECT_EQ(axisAt(left, {-1, 0}), 'A');
    EXPECT_EQ(left.back().label, 'L');
    auto top = orientationMarker(viewedFrom(camera, StandardView::Superior));
    EXPECT_EQ(axisAt(top, {0, -1}), 'A');
    EXPECT_EQ(axisAt(top, {1, 0}), 'R');
    for (std::size_t i = 1; i < top.size(); ++i) EXPECT_LE(top[i - 1].depth, top[i].depth);
}

}  // namespace
}  // namespace curette
