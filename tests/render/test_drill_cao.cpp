// Drilling and the CAO contract: with a removal accumulated stroke by stroke (plan/removal_volume.h), undone
// and redone, and a live mesh moving as well, CAO gives V_AO and images bit-identical to full LAO in a second
// renderer that never runs CAO, after every stroke step; and CAO visits only part of the volume to do it.
#include "mesh/primitives.h"
#include "plan/undo_history.h"
#include "plan/drill_sweep.h"
#include "render/renderer.h"
#include "tests/render/gl_test_support.h"

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include <cstring>
#include <random>

namespace curette {
namespace {

using test::glContext;

struct DrillScene {
    VolumeData volume;
    std::unique_ptr<Renderer> renderer;
    FrameDescription frame;
    explicit DrillScene(glm::ivec3 dims) {
        volume = test::makeVolume(dims, test::centredAffine(dims), ScalarType::UInt8, test::blobField);
        renderer = std::make_unique<Renderer>(glContext(), volume, test::rampTransferFunction(30, 180, 0.3));
        renderer->setLaoSettings(test::lightLao(4));   // reach 3 mm: most updates visit a box inside the 40^3 volume
        frame.camera.fit(glm::dvec3(0), 0.9 * glm::length(glm::dvec3(dims)) / 2);
        frame.camera.azimuthDeg = 30;
        frame.camera.elevationDeg = 20;
        frame.size = {48, 48};
    }
    using Result = test::AmbientAndImage;
    Result render(ShadingMode mode) {
        frame.shading = mode;
        return test::renderAmbientAndImage(*renderer, frame);
    }
};

void expectBitIdentical(const DrillScene::Result& lao, const DrillScene::Result& cao, const std::string& what) {
    test::expectSameAmbientAndImage(lao.ambient, lao.image, cao.ambient, cao.image, what);
}

TEST(DrillCao, EqualsFullLaoAfterEveryStrokeStepWithUndoAndRedo) {
    glContext();
    const glm::ivec3 dims(40);
    DrillScene cao(dims), lao(dims);
    auto removal = std::make_shared<plan::RemovalVolume>(dims, test::centredAffine(dims));
    cao.renderer->setRemoval(removal);
    lao.renderer->setRemoval(removal);
    // The CAO side casts again only the pixels drilling and the mesh can change (render/recast_region.h); the
    // LAO side casts every pixel, so a region that misses a changed pixel fails too.
    lao.renderer->setRecastOnlyChangedPixels(false);
    auto sphere = std::make_shared<const clip::TriangleMesh>(clip::makeSphere(4.0, 3));
    for (Renderer* r : {cao.renderer.get(), lao.renderer.get()}) r->clipMeshes().add(sphere, glm::dvec3(1.0), {}, "live sphere");
    auto setLivePose = [&](const clip::RigidPose& p) {
        for (Renderer* r : {cao.renderer.get(), lao.renderer.get()}) r->clipMeshes().setPose(0, p);
    };
    setLivePose(clip::RigidPose{glm::dvec3(30, 0, 0), {}});   // outside at first
    cao.render(ShadingMode::Cao);

    std::mt19937 random(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    plan::UndoHistory history;
    int compared = 0, partial = 0, undos = 0, redos = 0, recastPart = 0;
    auto compare = [&](const std::string& what) {
        DrillScene::Result c = cao.render(ShadingMode::Cao), l = lao.render(ShadingMode::Lao);
        const AmbientOcclusionStats& stats = cao.renderer->ambientOcclusion()->lastStats();
        partial += stats.dispatched < stats.voxels;
        recastPart += cao.renderer->lastRecastShare() < 1.0;
        ++compared;
        expectBitIdentical(l, c, what);
    };
    for (int stroke = 0; stroke < 10 && !HasFailure(); ++stroke) {
        bool erase = stroke % 4 == 3;
        plan::DrillTool tool{clip::SolidShape{stroke % 3 == 2 ? clip::SolidShape::Kind::Cylinder : clip::SolidShape::Kind::Sphere,
                                              erase ? 3.5 : 1.5 + 0.5 * (stroke % 3), 4.0}};
        clip::RigidPose pose{12.0 * glm::dvec3(u(random), u(random), u(random)),
                             glm::angleAxis(3.0 * u(random), glm::normalize(glm::dvec3(u(random), u(random), u(random)) + 1e-9))};
        history.beginStroke();
        for (int step = 0; step < 3 && !HasFailure(); ++step) {
            clip::RigidPose next = pose;
            next.position += 4.0 * glm::dvec3(u(random), u(random), u(random));
            next.orientation = glm::normalize(pose.orientation * glm::angleAxis(0.3 * u(random), glm::dvec3(1, 0, 0)));
            plan::DrillSweep sweep(tool, pose, next);
            plan::applySweep(*removal, sweep, erase, history.before());
            pose = next;
            if (step == 1) setLivePose(clip::RigidPose{10.0 * glm::dvec3(u(random), u(random), u(random)), {}});
            compare("stroke " + std::to_string(stroke) + " step " + std::to_string(step));
        }
        history.endStroke(*removal);
        if (stroke % 3 == 2) {
            ASSERT_TRUE(history.undo(*removal));
            ++undos;
            compare("undo after stroke " + std::to_string(stroke));
            if (stroke % 2 == 0) {
                ASSERT_TRUE(history.redo(*removal));
                ++redos;
                compare("redo after stroke " + std::to_string(stroke));
            }
        }
    }
    EXPECT_GT(undos, 1);
    EXPECT_GT(redos, 0);
    EXPECT_GT(partial, compared / 2) << "most CAO updates must visit less than the volume for the test to mean something";
    EXPECT_FALSE(removal->empty());
    EXPECT_GT(recastPart, 0) << "some exact frames must cast only part of the image for the test to mean something";
}

// After drilling alone, an exact frame casts only the pixels the changed bricks can reach (the drilled
// fraction a cell diagonal around them, V_AO within R more in lao/cao) and keeps the rest: bit for bit the
// image of a renderer that casts every pixel, in cao and phong, for short strokes in a larger volume where the
// region is a small part of the image.
TEST(DrillCao, ExactFramesAfterDrillingCastOnlyTheReachedPixelsAndEqualFullCasts) {
    glContext();
    const glm::ivec3 dims(64);
    for (ShadingMode mode : {ShadingMode::Cao, ShadingMode::Phong}) {
        DrillScene region(dims), full(dims);
        for (DrillScene* s : {&region, &full}) {
            s->frame.size = {96, 96};
            s->frame.camera.fit(glm::dvec3(0), 0.5 * glm::length(glm::dvec3(dims)) / 2);
        }
        full.renderer->setRecastOnlyChangedPixels(false);
        auto removal = std::make_shared<plan::RemovalVolume>(dims, test::centredAffine(dims));
        region.renderer->setRemoval(removal);
        full.renderer->setRemoval(removal);
        plan::DrillTool burr{clip::SolidShape{clip::SolidShape::Kind::Sphere, 1.5}};
        glm::dvec3 at(-4, 2, 5);
        double smallest = 1.0;
        for (int step = 0; step < 8; ++step) {
            glm::dvec3 next = at + glm::dvec3(1.0, -0.5, 0.3);
            plan::DrillSweep sweep(burr, clip::RigidPose{at, {}}, clip::RigidPose{next, {}});
            plan::applySweep(*removal, sweep, false);
            at = next;
            DrillScene::Result r = region.render(mode), f = full.render(mode);
            if (step > 0) smallest = std::min(smallest, region.renderer->lastRecastShare());
            EXPECT_EQ(0, std::memcmp(r.image.pixels.data(), f.image.pixels.data(), r.image.pixels.size() * sizeof(glm::vec4)))
                << shadingModeName(mode) << " step " << step << ": images differ (recast share " << region.renderer->lastRecastShare() << ")";
        }
        // cao's region is wider by the LAO reach R.
        EXPECT_LT(smallest, mode == ShadingMode::Cao ? 0.8 : 0.4) << shadingModeName(mode) << ": the drilled region must be part of the image";
    }
}

// The drilled removal changes the image: a stroke through the blobs opens them in every mode.
TEST(DrillCao, ADrilledStrokeChangesTheImageInEveryMode) {
    glContext();
    const glm::ivec3 dims(40);
    DrillScene scene(dims);
    auto removal = std::make_shared<plan::RemovalVolume>(dims, test::centredAffine(dims));
    scene.renderer->setRemoval(removal);
    for (ShadingMode mode : {ShadingMode::Solid, ShadingMode::Phong, ShadingMode::Cao, ShadingMode::Dos}) {
        removal->clear();
        Image before = scene.render(mode).image;
        plan::DrillSweep sweep({clip::SolidShape{clip::SolidShape::Kind::Sphere, 4.0}}, clip::RigidPose{glm::dvec3(-15, -3, 2), {}},
                               clip::RigidPose{glm::dvec3(15, 4, -3), {}});
        plan::applySweep(*removal, sweep, false);
        Image after = scene.render(mode).image;
        std::size_t changed = 0;
        for (std::size_t i = 0; i < before.pixels.size(); ++i) changed += before.pixels[i] != after.pixels[i];
        EXPECT_GT(changed, before.pixels.size() / 20) << shadingModeName(mode);
    }
}

}  // namespace
}  // namespace curette
