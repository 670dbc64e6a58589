// The clip-mesh overlay (render/clip_mesh_overlay.h): a sphere mesh's drawn pixels are the analytic disc the
// camera's pixel rays see (reference::cameraRay, the ray caster's own rays), in both targets (an image read
// back, rows from the top; a window's framebuffer, rows from the bottom, into a view rectangle); the held mesh
// is drawn in the highlight colour and more opaque; and the renderer's own image is the same before and after.
#include "render/clip_mesh_overlay.h"

#include "mesh/primitives.h"
#include "render/reference/camera_ray.h"
#include "render/renderer.h"
#include "tests/render/gl_test_support.h"
#include "tests/render/moving_sphere_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

namespace curette {
namespace {

using test::glContext;

constexpr double kRadiusMm = 10.0;

// How far (mm) the ray through `pixel` passes from `centre`.
double rayDistanceMm(const FrameDescription& frame, glm::ivec2 pixel, glm::dvec3 centre) {
    reference::CameraRay ray = reference::cameraRay(frame, pixel);
    glm::dvec3 toCentre = centre - ray.origin;
    return glm::length(toCentre - glm::dot(toCentre, ray.direction) * ray.direction);
}

// One pixel's width in mm at the distance of `point` from the eye.
double pixelMm(const FrameDescription& frame, glm::dvec3 point) {
    return glm::length(point - frame.camera.position()) / frame.camera.pixelsPerMmAtUnitDepth(frame.size.y);
}

struct OverlayScene {
    std::shared_ptr<const clip::TriangleMesh> sphere = std::make_shared<const clip::TriangleMesh>(clip::makeSphere(kRadiusMm, 5));
    clip::ClipMeshSet meshes;
    FrameDescription frame;
    glm::dvec3 centre{6.0, -4.0, 9.0};   // off the view's centre, across and up, so a mirrored or shifted drawing misses
    OverlayScene() {
        glContext();
        clip::RigidPose pose;
        pose.position = centre;
        pose.orientation = clip::orientationFromDegrees({20, -35, 50});   // the pose's rotation must not move a sphere
        meshes.add(sphere, glm::dvec3(1.0), pose, "sphere");
        frame.camera.fit(glm::dvec3(0.0), 30.0);
        frame.camera.azimuthDeg = 30;
        frame.camera.elevationDeg = 20;
        frame.size = {160, 120};
    }
};

// A transparent RGBA32F image of `size` (an empty ray-cast image).
gl::Texture transparentImage(glm::ivec2 size) {
    gl::Texture t = gl::createTexture(GL_TEXTURE_2D);
    glTextureStorage2D(t.name(), 1, GL_RGBA32F, size.x, size.y);
    const float zero[4] = {0, 0, 0, 0};
    glClearTexImage(t.name(), 0, GL_RGBA, GL_FLOAT, zero);
    return t;
}

// Compares the covered pixels with the analytic disc: their intersection over union, and that every pixel
// farther than `bandPx` pixels (along the sphere's silhouette) from the disc's edge is on the right side of it.
struct DiscAgreement {
    double iou = 0;
    int wrongBeyondBand = 0;
};
template <typename Covered>
DiscAgreement compareWithDisc(const FrameDescription& frame, glm::dvec3 centre, Covered covered, double bandPx) {
    const double band = bandPx * pixelMm(frame, centre);
    int both = 0, either = 0, wrong = 0;
    for (int y = 0; y < frame.size.y; ++y)
        for (int x = 0; x < frame.size.x; ++x) {
            double d = rayDistanceMm(frame, {x, y}, centre);
            bool inDisc = d < kRadiusMm, drawn = covered(x, y);
            both += inDisc && drawn;
            either += inDisc || drawn;
            if ((drawn && d > kRadiusMm + band) || (!drawn && d < kRadiusMm - band)) ++wrong;
        }
    return {either ? double(both) / either : 0.0, wrong};
}

TEST(ClipMeshOverlay, ASphereCoversItsAnalyticDiscInAnImage) {
    OverlayScene s;
    gl::Texture empty = transparentImage(s.frame.size);
    ClipMeshOverlay overlay;
    Image image = overlay.drawOver(empty.name(), s.frame.size, s.meshes, s.frame, ClipMeshDisplay{}, -1);
    ASSERT_EQ(image.width, s.frame.size.x);
    int covered = 0;
    DiscAgreement a = compareWithDisc(s.frame, s.centre, [&](int x, int y) {
        bool drawn = image.at(x, y).a > 0.0f;
        covered += drawn;
        return drawn;
    }, 1.0);
    std::printf("[ overlay  ] image: %d pixels drawn, IoU with the analytic disc %.4f\n", covered, a.iou);
    EXPECT_GT(covered, 500) << "the sphere is drawn at a size worth comparing";
    EXPECT_GT(a.iou, 0.97);
    EXPECT_EQ(a.wrongBeyondBand, 0) << "a pixel more than one pixel from the disc's edge is on the wrong side";
}

TEST(ClipMeshOverlay, ASphereCoversItsAnalyticDiscInAWindowsViewRectangle) {
    OverlayScene s;
    // A "window" of 400 x 300 with the view at (17, 9) from its top left, the view twice the image's size (the
    // presenter stretches the image to the view).
    const glm::ivec2 window(400, 300), origin(17, 9), view = 2 * s.frame.size;
    gl::Texture color = gl::createTexture(GL_TEXTURE_2D);
    glTextureStorage2D(color.name(), 1, GL_RGBA8, window.x, window.y);
    gl::Framebuffer framebuffer = gl::createFramebuffer();
    glNamedFramebufferTexture(framebuffer.name(), GL_COLOR_ATTACHMENT0, color.name(), 0);
    const float grey[4] = {0.25f, 0.25f, 0.25f, 1.0f};
    glClearNamedFramebufferfv(framebuffer.name(), GL_COLOR, 0, grey);
    ClipMeshOverlay overlay;
    overlay.draw(s.meshes, s.frame, ClipMeshDisplay{}, -1, origin, view, window, framebuffer.name());
    std::vector<std::uint8_t> pixels(static_cast<std::size_t>(window.x) * window.y * 4);
    glGetTextureImage(color.name(), 0, GL_RGBA, GL_UNSIGNED_BYTE, static_cast<GLsizei>(pixels.size()), pixels.data());
    // GL's row 0 is the window's bottom: window pixel (x, y from the top) is row window.y - 1 - y.
    auto changed = [&](int x, int y) {
        const std::uint8_t* p = &pixels[(static_cast<std::size_t>(window.y - 1 - y) * window.x + x) * 4];
        return p[0] != 64 || p[1] != 64 || p[2] != 64;
    };
    int outside = 0;
    for (int y = 0; y < window.y; ++y)
        for (int x = 0; x < window.x; ++x)
            if (changed(x, y) && (x < origin.x || y < origin.y || x >= origin.x + view.x || y >= origin.y + view.y)) ++outside;
    EXPECT_EQ(outside, 0) << "nothing is drawn outside the view rectangle";
    // In the view's own pixels: the frame at the view's size sees the same disc (the projection depends on the
    // aspect alone).
    FrameDescription viewFrame = s.frame;
    viewFrame.size = view;
    DiscAgreement a = compareWithDisc(viewFrame, s.centre, [&](int x, int y) { return changed(origin.x + x, origin.y + y); }, 1.0);
    std::printf("[ overlay  ] window: IoU with the analytic disc %.4f\n", a.iou);
    EXPECT_GT(a.iou, 0.97);
    EXPECT_EQ(a.wrongBeyondBand, 0);
}

TEST(ClipMeshOverlay, TheHeldMeshIsDrawnInTheHighlightColourAndMoreOpaque) {
    OverlayScene s;
    clip::RigidPose second;
    second.position = glm::dvec3(-14.0, 6.0, -6.0);
    s.meshes.add(s.sphere, glm::dvec3(1.0), second, "second sphere");
    gl::Texture empty = transparentImage(s.frame.size);
    ClipMeshOverlay overlay;
    const ClipMeshDisplay display;
    for (int held : {0, 1}) {
        Image image = overlay.drawOver(empty.name(), s.frame.size, s.meshes, s.frame, display, held);
        for (int mesh : {0, 1}) {
            glm::dvec3 centre = s.meshes.pose(mesh).position;
            glm::dvec4 clip = s.frame.camera.viewProjection(s.frame.size) * glm::dvec4(centre, 1.0);
            glm::dvec2 ndc = glm::dvec2(clip) / clip.w;
            glm::ivec2 pixel(int((ndc.x + 1) / 2 * s.frame.size.x), int((1 - ndc.y) / 2 * s.frame.size.y));
            // The disc's centre: the fill facing the camera (no rim term), premultiplied over nothing.
            glm::vec4 middle = image.at(pixel.x, pixel.y);
            double fill = mesh == held ? heldFillOpacity(display) : display.fillOpacity;
            EXPECT_NEAR(middle.a, fill, 2e-3) << "mesh " << mesh << ", held " << held;
            glm::vec3 hue = glm::vec3(middle) / middle.a, expected = mesh == held ? kHeldClipMeshColor : clipMeshColor(mesh);
            EXPECT_NEAR(hue.r / hue.g, expected.r / expected.g, 0.02) << "mesh " << mesh << ", held " << held;
            EXPECT_NEAR(hue.b / hue.g, expected.b / expected.g, 0.02) << "mesh " << mesh << ", held " << held;
            // Its outline: the pixels along the row from the centre outwards, the last covered one.
            int x = pixel.x;
            while (x + 1 < image.width && image.at(x + 1, pixel.y).a > 0.0f) ++x;
            glm::vec4 edge = image.at(x, pixel.y);
            double outline = mesh == held ? heldOutlineOpacity(display) : display.outlineOpacity;
            EXPECT_NEAR(edge.a, outline, 1.0 / 255.0) << "mesh " << mesh << ", held " << held;
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(edge[c] / edge.a, expected[c], 1.0 / 255.0 + 1e-4) << "mesh " << mesh << ", held " << held;
        }
    }
    EXPECT_GT(heldFillOpacity(display), display.fillOpacity);
}

TEST(ClipMeshOverlay, TheRenderersImageIsTheSameBeforeAndAfterAndChangesOnlyOnTheMesh) {
    test::MovingSphereScene scene(ShadingMode::Phong);
    Renderer& renderer = *scene.renderer;
    scene.frame.size = {96, 80};
    renderer.render(scene.frame);
    const Image before = renderer.readImage();
    const std::string hashBefore = imageHash(toRgba8(before, glm::vec4(0, 0, 0, 1)));
    ClipMeshOverlay overlay;
    Image over = overlay.drawOver(renderer.outputTexture(), renderer.outputSize(), renderer.clipMeshes(), scene.frame, ClipMeshDisplay{}, 0);
    // And into a window-sized framebuffer, as the viewer does after presenting.
    gl::Texture color = gl::createTexture(GL_TEXTURE_2D);
    glTextureStorage2D(color.name(), 1, GL_RGBA8, 128, 100);
    gl::Framebuffer framebuffer = gl::createFramebuffer();
    glNamedFramebufferTexture(framebuffer.name(), GL_COLOR_ATTACHMENT0, color.name(), 0);
    overlay.draw(renderer.clipMeshes(), scene.frame, ClipMeshDisplay{}, 0, {4, 4}, scene.frame.size, {128, 100}, framebuffer.name());

    EXPECT_TRUE(renderer.showing(scene.frame)) << "the overlay changes nothing the renderer's image stamp covers";
    const Image after = renderer.readImage();
    EXPECT_TRUE(test::sameImage(before, after));
    EXPECT_EQ(imageHash(toRgba8(after, glm::vec4(0, 0, 0, 1))), hashBefore);

    // The image with the overlay differs from the renderer's only on the mesh's disc (plus a pixel).
    glm::dvec3 centre = renderer.clipMeshes().pose(0).position;
    const double radius = 5.0 + pixelMm(scene.frame, centre);
    int changed = 0, changedOff = 0;
    for (int y = 0; y < over.height; ++y)
        for (int x = 0; x < over.width; ++x)
            if (over.at(x, y) != before.at(x, y)) {
                ++changed;
                changedOff += rayDistanceMm(scene.frame, {x, y}, centre) > radius;
            }
    EXPECT_GT(changed, 20);
    EXPECT_EQ(changedOff, 0);
}

}  // namespace
}  // namespace curette
