// Stereo pairs (render/model/stereo.h, render/stereo_render.h) and the matching of surface points between the eyes
// (render/reference/stereo_match.h): the off-axis rig's geometry on the CPU, the pair the GPU renders against the rig's
// projection, and that a point the right eye cannot see is never matched.
#include "render/reference/camera_ray.h"
#include "render/model/stereo.h"
#include "render/reference/stereo_match.h"
#include "render/stereo_render.h"
#include "tests/render/gl_test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace curette {
namespace {

FrameDescription centreFrame(glm::ivec2 size = {64, 48}) {
    FrameDescription f;
    f.camera.target = glm::dvec3(3, -2, 5);
    f.camera.distanceMm = 400;
    f.camera.azimuthDeg = 30;
    f.camera.elevationDeg = 10;
    f.camera.fovYDeg = 30;
    f.camera.nearMm = 100;
    f.camera.farMm = 900;
    f.size = size;
    return f;
}

TEST(Stereo, TheEyesLookAlongTheCameraAxisFromEitherSideOfIt) {
    FrameDescription centre = centreFrame();
    StereoRig rig = stereoRig(centre, 65.0);
    FrameDescription left = rig.eyeFrame(Eye::Left), right = rig.eyeFrame(Eye::Right);
    for (const FrameDescription* eye : {&left, &right}) {
        EXPECT_LT(glm::length(eye->camera.forward() - centre.camera.forward()), 1e-12) << "parallel axes, not toed in";
        EXPECT_LT(glm::length(eye->camera.up() - centre.camera.up()), 1e-12);
        EXPECT_EQ(eye->size, glm::ivec2(centre.size.x + 2 * rig.marginColumns, centre.size.y));
    }
    glm::dvec3 baseline = right.camera.position() - left.camera.position();
    EXPECT_LT(glm::length(baseline - 65.0 * centre.camera.right()), 1e-9) << "the right eye is to the right";
    EXPECT_LT(glm::length(0.5 * (left.camera.position() + right.camera.position()) - centre.camera.position()), 1e-9);
    EXPECT_GT(rig.marginColumns, 0);
    // k rounds s H / (2 D tan(fovy / 2)) = 32.5 * 48 / (800 tan 15 deg) = 7.28 to 7, so zero parallax moves to 416 mm.
    EXPECT_EQ(rig.marginColumns, 7);
    EXPECT_NEAR(rig.convergenceMm, 32.5 * 48 / (2 * 7 * std::tan(glm::radians(15.0))), 1e-9);
    EXPECT_TRUE(std::isinf(stereoRig(centre, 0.0).convergenceMm));
}

// The kept pixels of both eyes are the off-axis frusta: the same pixel of each eye looks at the same point of
// the plane at the convergence distance, and no point has vertical parallax.
TEST(Stereo, TheSamePixelOfBothEyesMeetsAtTheConvergenceDistance) {
    FrameDescription centre = centreFrame();
    StereoRig rig = stereoRig(centre, 65.0);
    FrameDescription left = rig.eyeFrame(Eye::Left), right = rig.eyeFrame(Eye::Right);
    const glm::dvec3 forward = centre.camera.forward();
    auto onConvergencePlane = [&](const FrameDescription& eye, int column, int row) {
        reference::CameraRay ray = reference::cameraRay(eye, {column, row});
        return ray.origin + rig.convergenceMm / glm::dot(ray.direction, forward) * ray.direction;
    };
    for (int row : {0, 17, 47})
        for (int column : {0, 1, 31, 63}) {
            glm::dvec3 l = onConvergencePlane(left, column + rig.firstColumn(Eye::Left), row);
            glm::dvec3 r = onConvergencePlane(right, column + rig.firstColumn(Eye::Right), row);
            EXPECT_LT(glm::length(l - r), 1e-6 * rig.convergenceMm) << "column " << column << ", row " << row;
        }
    std::mt19937 random(3);
    std::uniform_real_distribution<double> u(-60, 60);
    for (int i = 0; i < 20; ++i) {
        glm::dvec3 p = centre.camera.target + glm::dvec3(u(random), u(random), u(random));
        EXPECT_NEAR(projectToPixel(left, p).y, projectToPixel(right, p).y, 1e-9) << "vertical parallax";
    }
}

TEST(Stereo, SideBySidePutsTheLeftEyeLeftAndTheAnaglyphTakesRedFromIt) {
    Image left, right;
    left.width = right.width = 2;
    left.height = right.height = 1;
    left.pixels = {glm::vec4(0.8f, 0.1f, 0.2f, 1.0f), glm::vec4(0.0f)};
    right.pixels = {glm::vec4(0.3f, 0.6f, 0.7f, 1.0f), glm::vec4(0.25f, 0.25f, 0.25f, 0.5f)};
    Image both = sideBySide(left, right);
    ASSERT_EQ(both.width, 4);
    EXPECT_EQ(both.at(0, 0), left.at(0, 0));
    EXPECT_EQ(both.at(2, 0), right.at(0, 0));
    const glm::vec4 background(0.0f, 0.0f, 1.0f, 1.0f);
    Image red = anaglyph(left, right, background);
    EXPECT_EQ(red.at(0, 0), glm::vec4(0.8f, 0.6f, 0.7f, 1.0f));
    // Pixel 1: the left eye shows only the background (red 0), the right half its colour over blue.
    EXPECT_EQ(red.at(1, 0), glm::vec4(0.0f, 0.25f, 0.75f, 1.0f));
    EXPECT_EQ(parseStereoMode("side-by-side"), StereoMode::SideBySide);
    EXPECT_EQ(nextStereoMode(StereoMode::Anaglyph), StereoMode::Off);
}

TEST(Stereo, ProjectingAPointOnAPixelRayGivesThatPixelsCentre) {
    FrameDescription f = centreFrame();
    for (glm::ivec2 pixel : {glm::ivec2(0, 0), glm::ivec2(63, 47), glm::ivec2(20, 31)}) {
        reference::CameraRay ray = reference::cameraRay(f, pixel);
        glm::dvec2 q = projectToPixel(f, ray.origin + 380.0 * ray.direction);
        EXPECT_NEAR(q.x, pixel.x + 0.5, 1e-9);
        EXPECT_NEAR(q.y, pixel.y + 0.5, 1e-9);
    }
}

TEST(Stereo, ShadeDifferenceIsTheLargestChannelDifferencePerPoint) {
    Image a, b;
    a.width = b.width = 2;
    a.height = b.height = 1;
    a.pixels = {glm::vec4(0.5f, 0.5f, 0.5f, 1.0f), glm::vec4(0.2f, 0.2f, 0.2f, 1.0f)};
    b.pixels = {glm::vec4(0.5f, 0.25f, 0.375f, 1.0f), glm::vec4(0.2f, 0.2f, 0.2f, 1.0f)};
    ShadeDifference d = shadeDifference(a, b, {StereoMatch{{0, 0}, {0, 0}, false, 0.0}, StereoMatch{{1, 0}, {1, 0}, false, 0.0}});
    EXPECT_EQ(d.points, 2);
    EXPECT_DOUBLE_EQ(d.max, 0.25);
    EXPECT_DOUBLE_EQ(d.mean, 0.125);
    EXPECT_DOUBLE_EQ(d.rms, std::sqrt(0.25 * 0.25 / 2));
    EXPECT_NEAR(d.meanShade, 0.35, 1e-7);   // (0.5 + 0.2) / 2 in float
    EXPECT_DOUBLE_EQ(d.relativeRms(), d.rms / d.meanShade);
}

// Two small blobs: one at the target (zero parallax), one 20 mm nearer and higher (crossed parallax). In each
// GPU eye image a blob sits where the rig's projection puts its centre.
TEST(Stereo, TheGpuPairShowsEachPointWhereTheRigProjectsIt) {
    gl::Context& context = test::glContext();
    glm::ivec3 dims(48);
    const glm::dvec3 atTarget(0, 0, -10), nearer(0, 20, 10);
    auto blobs = [&](glm::dvec3 p) {
        auto blob = [&](glm::dvec3 c) { return std::exp(-glm::dot(p - c, p - c) / (2 * 2.0 * 2.0)); };
        return 255.0 * std::min(1.0, blob(atTarget) + blob(nearer));
    };
    VolumeData volume = test::makeVolume(dims, test::centredAffine(dims), ScalarType::UInt8, blobs);
    Renderer renderer(context, volume, test::rampTransferFunction(30, 200, 0.8));
    FrameDescription centre;
    centre.camera.target = glm::dvec3(0.0);
    centre.camera.distanceMm = 150;   // looking along -y from +y: up is +z
    centre.camera.nearMm = 50;
    centre.camera.farMm = 300;
    centre.size = {64, 64};
    centre.shading = ShadingMode::Solid;
    StereoPair pair = renderStereoPair(renderer, centre, 30.0);
    ASSERT_EQ(pair.left.width, 64);
    ASSERT_EQ(pair.rig.marginColumns, 12);
    // Alpha-weighted centroid column of the upper (nearer blob) or lower (blob at the target) half.
    auto centroidColumn = [](const Image& image, bool upper) {
        double sum = 0, weight = 0;
        for (int y = upper ? 0 : 32; y < (upper ? 32 : 64); ++y)
            for (int x = 0; x < image.width; ++x) {
                sum += image.at(x, y).a * (x + 0.5);
                weight += image.at(x, y).a;
            }
        return sum / weight;
    };
    for (Eye eye : {Eye::Left, Eye::Right}) {
        const Image& image = eye == Eye::Left ? pair.left : pair.right;
        FrameDescription f = pair.rig.eyeFrame(eye);
        for (bool upper : {true, false}) {
            double expected = projectToPixel(f, upper ? nearer : atTarget).x - pair.rig.firstColumn(eye);
            EXPECT_NEAR(centroidColumn(image, upper), expected, 0.35) << (eye == Eye::Left ? "left" : "right") << (upper ? " nearer" : " at target");
        }
    }
    // Crossed parallax of the nearer blob: 2k (D' / z - 1) = 24 (148.8 / 130 - 1), about 3.5 pixels.
    EXPECT_GT(centroidColumn(pair.left, true) - centroidColumn(pair.right, true), 3.0);
    EXPECT_NEAR(centroidColumn(pair.left, false), centroidColumn(pair.right, false), 0.35);
}

// A vertical bar in front of a wall, eyes far apart: some wall points the left eye sees are behind the bar for
// the right eye. None of them may be matched.
TEST(StereoMatch, APointTheRightEyeCannotSeeIsNotMatched) {
    glm::ivec3 dims(48);
    auto inBox = [](glm::dvec3 p, glm::dvec3 lo, glm::dvec3 hi) { return glm::all(glm::greaterThanEqual(p, lo)) && glm::all(glm::lessThanEqual(p, hi)); };
    // The wall is slanted (its depth changes across the image), so its points' disparities take every fraction of a pixel.
    const glm::dvec3 barLo(-2, 8, -30), barHi(2, 11, 30);
    auto inWall = [](glm::dvec3 p) { return p.y >= -12 + 0.3 * p.x && p.y <= -9 + 0.3 * p.x; };
    VolumeData volume = test::makeVolume(dims, test::centredAffine(dims), ScalarType::UInt8,
                                         [&](glm::dvec3 p) { return inBox(p, barLo, barHi) || inWall(p) ? 255.0 : 0.0; });
    TransferFunction tf = test::rampTransferFunction(100, 200, 0.99);
    FrameDescription centre;
    centre.camera.target = glm::dvec3(0.0);
    centre.camera.distanceMm = 150;
    centre.camera.nearMm = 50;
    centre.camera.farMm = 300;
    centre.size = {96, 64};
    StereoRig rig = stereoRig(centre, 60.0);
    EyeView left{rig.eyeFrame(Eye::Left), {}}, right{rig.eyeFrame(Eye::Right), {}};
    SurfaceScene scene{volume, tf, {}, 0.5};
    MatchSettings settings;
    settings.stride = 1;
    settings.maxColumnOffsetPx = 0.25;
    MatchCounts counts;
    std::vector<StereoMatch> matches = matchSurfacePoints(scene, left, right, settings, &counts);
    EXPECT_GT(counts.matched, 150) << counts.tried << " tried, " << counts.surfaces << " surfaces, " << counts.outside << " outside, " << counts.offCentre << " off centre, " << counts.hidden << " hidden";
    EXPECT_GT(counts.hidden, 10) << "the scene must hide some points from the right eye";
    // Whether the bar (shrunk by half a voxel: its surface is blurred by the trilinear filter) blocks the segment.
    auto blockedByBar = [&](glm::dvec3 from, glm::dvec3 to) {
        glm::dvec3 lo = barLo + 0.5, hi = barHi - 0.5, d = to - from;
        double t0 = 0, t1 = 1;
        for (int a = 0; a < 3; ++a) {
            double ta = (lo[a] - from[a]) / d[a], tb = (hi[a] - from[a]) / d[a];
            t0 = std::max(t0, std::min(ta, tb));
            t1 = std::min(t1, std::max(ta, tb));
        }
        return t0 < t1;
    };
    int onWall = 0;
    for (const StereoMatch& m : matches) {
        std::optional<SurfacePoint> p = surfacePoint(scene, left, m.left);
        ASSERT_TRUE(p);
        if (p->world.y > 0) continue;   // on the bar (the wall lies below y = -1.8)
        ++onWall;
        EXPECT_FALSE(blockedByBar(right.frame.camera.position(), p->world))
            << "left pixel " << m.left.x << "," << m.left.y << " matched, but its wall point is behind the bar for the right eye";
    }
    EXPECT_GT(onWall, 100);
}

// A pixel's surface is the first of: where the volume's opacity reaches 0.5 (outside the clip region), and the
// tube surface the G-buffer holds (a tube is opaque).
TEST(StereoMatch, ASurfacePointIsTheNearerOfTheVolumesHalfOpacityAndTheTube) {
    glm::ivec3 dims(32);
    // An opaque slab y < -4 facing the camera (which looks along -y from +y).
    VolumeData volume = test::makeVolume(dims, test::centredAffine(dims), ScalarType::UInt8, [](glm::dvec3 p) { return p.y < -4 ? 255.0 : 0.0; });
    TransferFunction tf = test::rampTransferFunction(100, 200, 0.99);
    EyeView eye;
    eye.frame.camera.target = glm::dvec3(0.0);
    eye.frame.camera.distanceMm = 100;
    eye.frame.size = {8, 8};
    const glm::ivec2 pixel(4, 4);
    SurfaceScene scene{volume, tf, {}, 0.5};
    std::optional<SurfacePoint> slab = surfacePoint(scene, eye, pixel);
    ASSERT_TRUE(slab);
    EXPECT_FALSE(slab->tube);
    EXPECT_NEAR(slab->world.y, -4.5, 0.6) << "the slab's face, within a step and the trilinear blur";
    // A tube 90 mm in front of the eye (view depth), before the slab at ~104 mm.
    eye.tubeViewDepth.assign(64, 0.0f);
    eye.tubeViewDepth[4 * 8 + 4] = 90.0f;
    std::optional<SurfacePoint> tube = surfacePoint(scene, eye, pixel);
    ASSERT_TRUE(tube);
    EXPECT_TRUE(tube->tube);
    EXPECT_NEAR(glm::dot(tube->world - eye.frame.camera.position(), eye.frame.camera.forward()), 90.0, 1e-9);
    // A tube behind the slab is hidden by it.
    eye.tubeViewDepth[4 * 8 + 4] = 120.0f;
    EXPECT_FALSE(surfacePoint(scene, eye, pixel)->tube);
    // Clipping the slab's front away moves the surface back to the clip region's wall.
    eye.tubeViewDepth.clear();
    scene.clipped = [](glm::dvec3 p) { return p.y > -9; };
    EXPECT_NEAR(surfacePoint(scene, eye, pixel)->world.y, -9.0, 0.6);
}

}  // namespace
}  // namespace curette
