// Pixels an exact frame casts again (render/recast_region.h): after rigid motions of clip meshes alone, the exact
// frame casts only the pixels the motions can change and keeps the others, and the image is a fresh renderer's
// bit for bit; anything else casts every pixel. The projection of a box covers every pixel whose centre ray
// meets it (against the CPU camera ray and a double-precision slab test).
#include "render/recast_region.h"
#include "render/reference/camera_ray.h"
#include "tests/render/moving_sphere_scene.h"

#include <gtest/gtest.h>

#include <random>

namespace curette {
namespace {

using test::MovingSphereScene;
using test::sameImage;

// Whether the ray (from its origin on) meets the box [lo, hi] of the frame `toWorld` places (double slab test).
bool rayMeetsBox(const reference::CameraRay& ray, const glm::dmat4& toWorld, glm::dvec3 lo, glm::dvec3 hi) {
    glm::dmat4 toLocal = glm::inverse(toWorld);
    glm::dvec3 o(toLocal * glm::dvec4(ray.origin, 1.0)), d(toLocal * glm::dvec4(ray.direction, 0.0));
    double near = 0.0, far = 1e300;
    for (int a = 0; a < 3; ++a) {
        if (std::abs(d[a]) < 1e-300) {
            if (o[a] < lo[a] || o[a] > hi[a]) return false;
            continue;
        }
        double t0 = (lo[a] - o[a]) / d[a], t1 = (hi[a] - o[a]) / d[a];
        near = std::max(near, std::min(t0, t1));
        far = std::min(far, std::max(t0, t1));
    }
    return far >= near;
}

bool rayMeetsBall(const reference::CameraRay& ray, const WorldBall& ball) {
    glm::dvec3 toCentre = ball.centre - ray.origin;
    double along = std::max(glm::dot(toCentre, ray.direction), 0.0);
    return glm::length(toCentre - along * ray.direction) <= ball.radius;
}

// A point within 40 mm of the origin along every axis.
glm::dvec3 randomPosition(std::mt19937& random) {
    std::uniform_real_distribution<double> u(-40.0, 40.0);
    return {u(random), u(random), u(random)};
}

FrameDescription randomFrame(std::mt19937& random) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    FrameDescription frame;
    frame.size = {40 + int(60 * unit(random)), 30 + int(50 * unit(random))};
    frame.camera.fit(glm::dvec3(0), 50.0);
    frame.camera.azimuthDeg = 360 * unit(random);
    frame.camera.elevationDeg = -80 + 160 * unit(random);
    frame.camera.fovYDeg = 20 + 40 * unit(random);
    return frame;
}

// Every pixel whose centre ray meets the shape (`meets`) lies in the region; returns how many do.
template <typename Meets>
std::int64_t checkCovers(const PixelRegion& region, const FrameDescription& frame, Meets meets, int trial) {
    std::int64_t meeting = 0;
    for (int y = 0; y < frame.size.y; ++y)
        for (int x = 0; x < frame.size.x; ++x) {
            if (!meets(reference::cameraRay(frame, {x, y}))) continue;
            ++meeting;
            EXPECT_TRUE(region.contains({x, y})) << "trial " << trial << ": pixel " << x << "," << y << " meets the shape outside the region";
        }
    return meeting;
}

TEST(RecastRegion, TheProjectionOfABoxCoversEveryPixelWhoseRayMeetsIt) {
    std::mt19937 random(7);
    std::uniform_real_distribution<double> unit(0.0, 1.0), signed_(-1.0, 1.0);
    int tight = 0;
    for (int trial = 0; trial < 200; ++trial) {
        FrameDescription frame = randomFrame(random);
        clip::RigidPose pose{randomPosition(random), {}};
        pose.orientation = glm::normalize(glm::dquat(signed_(random), signed_(random), signed_(random), signed_(random)));
        glm::dvec3 half(1 + 20 * unit(random), 1 + 20 * unit(random), 1 + 20 * unit(random));
        ConvexCorners box;
        for (int c = 0; c < 8; ++c)
            box.emplace_back(pose.matrix() * glm::dvec4((c & 1) ? half.x : -half.x, (c & 2) ? half.y : -half.y, (c & 4) ? half.z : -half.z, 1.0));
        std::optional<PixelRegion> region = pixelsMeeting(box, frame);
        if (!region) continue;   // the box reaches the eye's plane: every pixel
        std::int64_t meeting = checkCovers(*region, frame, [&](const reference::CameraRay& ray) { return rayMeetsBox(ray, pose.matrix(), -half, half); }, trial);
        if (meeting > 0 && region->area() < std::int64_t(frame.size.x) * frame.size.y) ++tight;
    }
    EXPECT_GT(tight, 50) << "most regions must leave pixels out for the test to mean something";
    // A box around the eye has no bounded projection.
    FrameDescription frame;
    frame.camera.fit(glm::dvec3(0), 50.0);
    glm::dvec3 eye = frame.camera.position();
    ConvexCorners around;
    for (int c = 0; c < 8; ++c) around.push_back(eye + glm::dvec3((c & 1) ? 5.0 : -5.0, (c & 2) ? 5.0 : -5.0, (c & 4) ? 5.0 : -5.0));
    EXPECT_FALSE(pixelsMeeting(around, frame).has_value());
}

// A rod's changed regions in pieces (changedRegions): every pixel whose centre ray passes within the ambient reach
// of its clip box at either pose (points along the ray every 0.05 mm, their distance to the box in double) lies in
// the region, and so does every pixel whose ray meets the clip box; and the pieces leave out pixels one ball
// around the rod would take.
TEST(RecastRegion, ARodsPiecesCoverEveryRayWithinReachOfItsBox) {
    std::mt19937 random(13);
    std::uniform_real_distribution<double> unit(0.0, 1.0), signed_(-1.0, 1.0);
    std::int64_t pieces = 0, wholeBall = 0;
    for (int trial = 0; trial < 40; ++trial) {
        FrameDescription frame = randomFrame(random);
        const glm::dvec3 half(1.5 + 2 * unit(random), 1.5 + 2 * unit(random), 10 + 15 * unit(random));
        const double reach = 2 + 6 * unit(random);
        ClipMeshReach rod;
        rod.clipLo = -half;
        rod.clipHi = half;
        rod.ambientLo = -half - reach;
        rod.ambientHi = half + reach;
        rod.centre = glm::dvec3(0.0);
        rod.clipRadius = glm::length(half);
        rod.ambientRadius = glm::length(half) + reach;
        rod.ambientReachMm = reach;
        ClipSnapshot before, now;
        clip::RigidPose poses[2];
        for (clip::RigidPose& p : poses) {
            p.position = randomPosition(random);
            p.orientation = glm::normalize(glm::dquat(signed_(random), signed_(random), signed_(random), signed_(random)));
        }
        rod.pose = poses[0];
        before.meshes.push_back(rod);
        rod.pose = poses[1];
        now.meshes.push_back(rod);
        std::optional<std::vector<ChangedRegion>> regions = changedRegions(before, now, true);
        ASSERT_TRUE(regions.has_value());
        std::optional<PixelRegion> region = pixelsMeeting(*regions, frame);
        if (!region) continue;   // a region reaches the eye's plane
        pieces += region->area();
        // One ball around each pose's whole reach, as a region without pieces would be bounded by.
        PixelRegion balls = PixelRegion::none(frame.size);
        for (const clip::RigidPose& p : poses)
            if (std::optional<PixelRegion> b = pixelsMeeting(WorldBall{p.position, rod.ambientRadius}, frame)) balls.unite(*b);
        wholeBall += balls.area();
        checkCovers(*region, frame, [&](const reference::CameraRay& ray) {
            for (const clip::RigidPose& p : poses) {
                if (rayMeetsBox(ray, p.matrix(), -half, half)) return true;
                glm::dvec3 toCentre = p.position - ray.origin;
                double along = glm::dot(toCentre, ray.direction), span = glm::length(half) + reach;
                for (double t = std::max(along - span, 0.0); t <= along + span; t += 0.05) {
                    glm::dvec3 q(p.inverseMatrix() * glm::dvec4(ray.origin + t * ray.direction, 1.0));
                    if (glm::length(glm::max(glm::abs(q) - half, glm::dvec3(0.0))) <= reach) return true;
                }
            }
            return false;
        }, trial);
    }
    EXPECT_LT(pieces * 10, wholeBall * 9) << "the pieces must leave out pixels a ball around the rod takes";
}

TEST(RecastRegion, TheProjectionOfABallCoversEveryPixelWhoseRayMeetsItAndLittleMore) {
    std::mt19937 random(9);
    std::uniform_real_distribution<double> radius(2.0, 27.0);
    int measured = 0;
    for (int trial = 0; trial < 200; ++trial) {
        FrameDescription frame = randomFrame(random);
        WorldBall ball{randomPosition(random), radius(random)};
        std::optional<PixelRegion> region = pixelsMeeting(ball, frame);
        if (!region) {
            EXPECT_LE(glm::length(ball.centre - frame.camera.position()), ball.radius * (1 + 1e-6)) << "trial " << trial;
            continue;
        }
        std::int64_t meeting = checkCovers(*region, frame, [&](const reference::CameraRay& ray) { return rayMeetsBall(ray, ball); }, trial);
        // The octagonal pyramid adds 5 % to the disk, the margin a pixel or two per row end.
        if (meeting > 150) {
            ++measured;
            std::int64_t rows = 0;
            for (glm::ivec2 run : region->rows) rows += run.y > run.x;
            EXPECT_LE(static_cast<double>(region->area()), 1.1 * static_cast<double>(meeting) + 4.0 * static_cast<double>(rows))
                << "trial " << trial << ": the region is loose";
        }
    }
    EXPECT_GT(measured, 30);
}

// A random rigid pose near the blobs: a translation within the volume and any rotation.
clip::RigidPose randomPose(std::mt19937& random) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    clip::RigidPose p;
    p.position = glm::dvec3(14 * u(random), 12 * u(random), 12 * u(random));
    p.orientation = glm::normalize(glm::dquat(u(random), u(random), u(random), u(random)));
    return p;
}

// A second clip mesh that stays where it is: its pixels are kept when the sphere moves elsewhere.
void addStillBox(MovingSphereScene& s) {
    clip::RigidPose p;
    p.position = glm::dvec3(12, -10, -6);
    s.renderer->clipMeshes().add(std::make_shared<const clip::TriangleMesh>(clip::makeBox(glm::dvec3(6, 4, 5))), glm::dvec3(1.0), p, "box");
}

// LAO rays of 12 mm: V_AO changes up to 12 mm and more from a mesh, far beyond its depth box.
void farReachingLao(MovingSphereScene& s) {
    LaoSettings lao = s.renderer->laoSettings();
    lao.samples = 9;
    lao.stepMm = 1.5;
    s.renderer->setLaoSettings(lao);
}

TEST(RecastRegion, ExactFramesAfterMeshMotionsEqualAFreshRenderersBitForBit) {
    for (ShadingMode mode : {ShadingMode::Cao, ShadingMode::Lao, ShadingMode::Phong, ShadingMode::Solid}) {
        SCOPED_TRACE(shadingModeName(mode));
        std::mt19937 random(11);
        MovingSphereScene viewer(mode);
        farReachingLao(viewer);
        addStillBox(viewer);
        viewer.frame.size = {96, 80};
        viewer.renderer->render(viewer.frame);
        double leastShare = 1.0;
        for (int step = 0; step < 6; ++step) {
            SCOPED_TRACE("step " + std::to_string(step));
            clip::RigidPose pose = randomPose(random);
            // Small motions too: the region is then mostly the mesh's own boxes.
            if (step % 2 == 1) pose.position = viewer.renderer->clipMeshes().pose(0).position + glm::dvec3(1.5, -1.0, 0.5);
            viewer.renderer->clipMeshes().setPose(0, pose);
            if (step % 3 == 2) {
                // The viewer's way: a preview, then the exact frame in slices (one band of the ray cast each).
                viewer.renderer->renderPreview(viewer.frame);
                int calls = 0;
                while (!viewer.renderer->advanceExact(viewer.frame, 0.0, 1)) ASSERT_LT(++calls, 100000);
            } else {
                viewer.renderer->render(viewer.frame);
            }
            leastShare = std::min(leastShare, viewer.renderer->lastRecastShare());

            MovingSphereScene fresh(mode);
            farReachingLao(fresh);
            addStillBox(fresh);
            fresh.frame = viewer.frame;
            fresh.renderer->clipMeshes().setPose(0, pose);
            fresh.renderer->render(fresh.frame);
            ASSERT_DOUBLE_EQ(fresh.renderer->lastRecastShare(), 1.0) << "a fresh renderer has no image to keep";
            ASSERT_TRUE(sameImage(viewer.renderer->readImage(), fresh.renderer->readImage()))
                << "the exact frame after the motion differs from a fresh renderer's (recast share "
                << viewer.renderer->lastRecastShare() << ")";
        }
        // (In the AO modes the regions reach far: the LAO rays' 12 mm on every side.)
        EXPECT_LT(leastShare, traits(mode).ambientOcclusion ? 0.5 : 0.2) << "some motion must keep pixels for the test to mean something";
    }
}

// A rod's regions come in pieces along it (recastRegion's pushPieces): a turned rod, long against its width,
// moved and turned about, in cao and lao (where the regions reach farthest), whole and in slices, keeps fewer
// pixels than one ball around it would and still equals a fresh renderer bit for bit.
TEST(RecastRegion, ARodMovedInPiecesEqualsAFreshRenderersFrames) {
    auto rod = std::make_shared<const clip::TriangleMesh>(clip::makeCylinder(2.0, 26.0, 24));
    for (ShadingMode mode : {ShadingMode::Cao, ShadingMode::Lao, ShadingMode::Phong}) {
        SCOPED_TRACE(shadingModeName(mode));
        std::mt19937 random(23);
        auto scene = [&](const clip::RigidPose& pose) {
            auto s = std::make_unique<MovingSphereScene>(mode);
            farReachingLao(*s);
            s->renderer->clipMeshes().clear();
            s->renderer->clipMeshes().add(rod, glm::dvec3(1.0), pose, "rod");
            addStillBox(*s);
            s->frame.size = {96, 80};
            return s;
        };
        std::unique_ptr<MovingSphereScene> viewer = scene(randomPose(random));
        viewer->renderer->render(viewer->frame);
        double leastShare = 1.0;
        for (int step = 0; step < 5; ++step) {
            SCOPED_TRACE("step " + std::to_string(step));
            clip::RigidPose pose = randomPose(random);
            if (step % 2 == 1) pose.position = viewer->renderer->clipMeshes().pose(0).position + glm::dvec3(1.0, 0.5, -1.5);
            viewer->renderer->clipMeshes().setPose(0, pose);
            if (step % 3 == 2) {
                viewer->renderer->renderPreview(viewer->frame);
                int calls = 0;
                while (!viewer->renderer->advanceExact(viewer->frame, 0.0, 1)) ASSERT_LT(++calls, 100000);
            } else {
                viewer->renderer->render(viewer->frame);
            }
            leastShare = std::min(leastShare, viewer->renderer->lastRecastShare());
            std::unique_ptr<MovingSphereScene> fresh = scene(pose);
            fresh->renderer->render(fresh->frame);
            ASSERT_TRUE(sameImage(viewer->renderer->readImage(), fresh->renderer->readImage()))
                << "the exact frame after the rod's motion differs from a fresh renderer's (recast share " << viewer->renderer->lastRecastShare() << ")";
        }
        EXPECT_LT(leastShare, 0.6) << "some motion must keep pixels for the test to mean something";
    }
}

TEST(RecastRegion, AnythingButAMeshMotionCastsEveryPixel) {
    MovingSphereScene s;
    s.frame.size = {96, 80};
    s.renderer->render(s.frame);
    s.moveTo(1);
    s.renderer->render(s.frame);
    ASSERT_LT(s.renderer->lastRecastShare(), 1.0);
    // Nothing changed: render() is asked for the same frame on purpose (a benchmark timing it), so it runs whole.
    s.renderer->render(s.frame);
    EXPECT_DOUBLE_EQ(s.renderer->lastRecastShare(), 1.0);

    // Each change comes with a motion of the sphere (to pose 2, back to 1, ...), which alone would keep pixels.
    int moves = 0;
    auto everyPixelAfter = [&](const char* what, auto change) {
        SCOPED_TRACE(what);
        s.moveTo(++moves % 2 == 1 ? 2 : 1);
        change();
        s.renderer->render(s.frame);
        EXPECT_DOUBLE_EQ(s.renderer->lastRecastShare(), 1.0);
    };
    everyPixelAfter("the camera turned", [&] { s.frame.camera.azimuthDeg += 5; });
    everyPixelAfter("the TF changed", [&] { s.renderer->setTransferFunction(test::rampTransferFunction(40, 170, 0.3)); });
    everyPixelAfter("the mesh was scaled", [&] { s.renderer->clipMeshes().setScale(0, glm::dvec3(1.1)); });
    everyPixelAfter("a mesh was added", [&] { addStillBox(s); });
    everyPixelAfter("the mode changed", [&] { s.frame.shading = ShadingMode::Phong; });
    everyPixelAfter("the jitter changed", [&] { s.frame.raycast.jitterSeed = 5; });
    everyPixelAfter("samples are counted", [&] { s.renderer->setCountSamples(true); });
    // A mesh motion alone keeps pixels again; a preview in between keeps the exact image, so it still does.
    s.moveTo(3);
    s.renderer->render(s.frame);
    EXPECT_LT(s.renderer->lastRecastShare(), 1.0);
    s.moveTo(2);
    s.renderer->renderPreview(s.frame);
    s.renderer->render(s.frame);
    EXPECT_LT(s.renderer->lastRecastShare(), 1.0);
    // Off: every pixel.
    s.renderer->setRecastOnlyChangedPixels(false);
    s.moveTo(4);
    s.renderer->render(s.frame);
    EXPECT_DOUBLE_EQ(s.renderer->lastRecastShare(), 1.0);
}

// An exact frame in slices abandoned in the middle of its ray cast has overwritten part of the exact image: the
// next exact frame must not keep pixels of it.
TEST(RecastRegion, AnExactFrameAbandonedInItsRayCastLeavesNoPixelsToKeep) {
    MovingSphereScene viewer(ShadingMode::Phong);
    viewer.frame.size = {96, 80};
    viewer.renderer->render(viewer.frame);
    viewer.moveTo(5);
    // The ray cast's probe band, written into the exact image, and then back to the pose of that image: were
    // its record kept, nothing would be cast and the band of pose 5 would stay.
    ASSERT_FALSE(viewer.renderer->advanceExact(viewer.frame, 0.0, 1));
    ASSERT_GT(viewer.renderer->exactProgress(), 0.0);
    viewer.moveTo(0);
    viewer.renderer->render(viewer.frame);
    EXPECT_DOUBLE_EQ(viewer.renderer->lastRecastShare(), 1.0);
    MovingSphereScene fresh(ShadingMode::Phong);
    fresh.frame = viewer.frame;
    fresh.renderer->render(fresh.frame);
    EXPECT_TRUE(sameImage(viewer.renderer->readImage(), fresh.renderer->readImage()));
}

}  // namespace
}  // namespace curette
