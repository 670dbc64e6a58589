// The exact frame in slices (Renderer::advanceExact, docs/architecture.md "Preview and exact frames"): step V
// in slices of its recompute list and the ray cast in bands of tile rows give render()'s V_AO and image bit
// for bit; the image shown stays the last one until the exact frame is done; and when the scene moves while a
// step V is under way, it is abandoned, not finished, and CAO stays equal to a fresh renderer's (the exactness
// contract). The slab pass (dos, with and without tubes) in its view-aligned slices gives render()'s image too, with
// previews drawn between its slices.
#include "tests/render/moving_sphere_scene.h"
#include "render/model/tube_geometry.h"

#include <gtest/gtest.h>

#include <random>

namespace curette {
namespace {


using test::MovingSphereScene;
using test::sameImage;

// The fresh renderer's exact frame at pose n: what `curette render` gives.
MovingSphereScene freshAt(int n, ShadingMode mode = ShadingMode::Cao) {
    MovingSphereScene s(mode);
    s.moveTo(n);
    s.renderer->render(s.frame);
    return s;
}

// The index of `pass` in the plan `renderer` would run for `frame` (-1: not in it).
int passIndex(const Renderer& renderer, const FrameDescription& frame, Pass pass) {
    const FramePlan plan = renderer.plan(frame);
    for (std::size_t i = 0; i < plan.passes.size(); ++i)
        if (plan.passes[i].pass == pass) return static_cast<int>(i);
    return -1;
}

// Runs the exact frame of `s` in slices until its step IV is done (the passes before it one per call, step IV in
// one slice), without finishing the frame.
void advancePastStepIV(MovingSphereScene& s) {
    int stepIV = passIndex(*s.renderer, s.frame, Pass::VoxelClipping);
    ASSERT_GE(stepIV, 0);
    for (int i = 0; i <= stepIV; ++i) ASSERT_FALSE(s.renderer->advanceExact(s.frame, 0.0, ~0u));
}

TEST(ExactInSlices, EqualsOneRenderBitForBitAndShowsTheLastImageUntilDone) {
    for (ShadingMode mode : {ShadingMode::Cao, ShadingMode::Lao, ShadingMode::Phong}) {
        SCOPED_TRACE(shadingModeName(mode));
        MovingSphereScene sliced(mode), whole(mode);
        sliced.renderer->setCountSamples(true);   // the counters add up over the bands
        whole.renderer->setCountSamples(true);
        sliced.renderer->render(sliced.frame);   // step I and a first exact frame at pose 0
        whole.renderer->render(whole.frame);
        sliced.moveTo(3);
        whole.moveTo(3);
        // ... and the camera turns, so every pixel changes (a band left out would keep the last frame's).
        sliced.frame.camera.azimuthDeg = whole.frame.camera.azimuthDeg = 55;
        sliced.frame.camera.fit(glm::dvec3(0), 9.0);   // close up: the volume fills the image, its last tile rows too
        whole.frame.camera.fit(glm::dvec3(0), 9.0);
        // A preview at pose 3 (as the viewer shows while the mesh moves): it stays on screen until the exact
        // frame is done.
        FrameDescription small = sliced.frame;
        small.size = {24, 20};
        sliced.renderer->renderPreview(small);
        Image preview = sliced.renderer->readImage();
        whole.renderer->render(whole.frame);

        int calls = 0;
        double progress = 0;
        while (!sliced.renderer->advanceExact(sliced.frame, 0.0, 2)) {   // one slice per call: 2 groups of V, 2 bands
            ASSERT_LT(++calls, 100000);
            EXPECT_FALSE(sliced.renderer->showing(sliced.frame)) << "call " << calls;
            EXPECT_TRUE(sameImage(sliced.renderer->readImage(), preview)) << "call " << calls << ": the image shown changed before the exact frame was done";
            EXPECT_GE(sliced.renderer->exactProgress(), progress) << "call " << calls;
            EXPECT_LT(sliced.renderer->exactProgress(), 1.0);
            progress = sliced.renderer->exactProgress();
        }
        // phong: the ray cast's probe band, then two bands; cao/lao: step V's list too.
        EXPECT_GE(calls, mode == ShadingMode::Phong ? 1 : 10) << "the exact frame came in too few calls: nothing was sliced";
        EXPECT_TRUE(sliced.renderer->showing(sliced.frame));
        EXPECT_TRUE(sliced.renderer->lastFrameExact());
        EXPECT_DOUBLE_EQ(sliced.renderer->exactProgress(), 0.0) << "no exact frame under way after it is done";
        EXPECT_TRUE(sameImage(sliced.renderer->readImage(), whole.renderer->readImage())) << "the exact frame in slices differs from render()";
        EXPECT_EQ(sliced.renderer->samplesLastFrame(), whole.renderer->samplesLastFrame()) << "samples counted over every band";
        EXPECT_EQ(sliced.renderer->rayStepsLastFrame(), whole.renderer->rayStepsLastFrame());
        EXPECT_FALSE(sameImage(preview, whole.renderer->readImage())) << "the preview must differ for the test to mean something";
        Image exact = whole.renderer->readImage();
        int coveredInLastRows = 0;
        for (int y = exact.height - 8; y < exact.height; ++y)
            for (int x = 0; x < exact.width; ++x) coveredInLastRows += exact.pixels[std::size_t(y) * std::size_t(exact.width) + std::size_t(x)].a > 0.0f;
        EXPECT_GT(coveredInLastRows, exact.width * 4) << "the last tile row must show the volume for the test to mean something";
        if (mode != ShadingMode::Phong) {
            EXPECT_EQ(sliced.ambient(), whole.ambient()) << "V_AO in slices differs from render()'s";
            EXPECT_TRUE(sliced.renderer->lastFrameUpdatedAmbient());
        }
        // Asked again, it is already shown.
        EXPECT_TRUE(sliced.renderer->advanceExact(sliced.frame, 0.0, 2));
    }
}

TEST(ExactInSlices, StepVIsSlicedIntoManyDispatches) {
    // At 2 groups of 64 list entries per slice, the recompute list of a 5 mm sphere's update takes many calls;
    // with slices of any size the result is the same.
    MovingSphereScene a, b;
    a.renderer->render(a.frame);
    b.renderer->render(b.frame);
    a.moveTo(1);
    b.moveTo(1);
    int callsA = 0, callsB = 0;
    while (!a.renderer->advanceExact(a.frame, 0.0, 2)) ASSERT_LT(++callsA, 100000);
    while (!b.renderer->advanceExact(b.frame, 0.0, 13)) ASSERT_LT(++callsB, 100000);
    EXPECT_GT(callsA, callsB + 10) << "smaller slices, more calls";
    EXPECT_EQ(a.ambient(), b.ambient());
    EXPECT_TRUE(sameImage(a.renderer->readImage(), b.renderer->readImage()));
}

// The scene moves while an exact frame is under way: in the middle of step IV, after it (step V not begun), and
// in the middle of step V. The exact frame of the new pose equals a fresh renderer's, V_AO and image. Pose 0
// (the last exact frame), pose 3 (the frame left under way) and pose 4 (the last) lie so far apart that the
// bricks of poses 3 and 4 do not reach pose 0's: the update at pose 4 must also visit what the abandoned update
// at pose 3 visited (pose 0's bricks among them), or pose 0's LAO stays there (leaving them out fails it).
TEST(ExactInSlices, MotionDuringTheExactFrameAbandonsItsStepVAndStaysExact) {
    MovingSphereScene fresh = freshAt(4);
    struct Case {
        const char* name;
        bool pastStepIV;
        int extraSlices;   // of one brick (step IV) or one group of the list (step V)
    };
    for (Case c : {Case{"moved in the middle of step IV", false, 3}, Case{"moved right after step IV", true, 0},
                   Case{"moved in the middle of step V", true, 5}}) {
        SCOPED_TRACE(c.name);
        MovingSphereScene viewer;
        viewer.renderer->render(viewer.frame);
        viewer.moveTo(3);
        if (c.pastStepIV) {
            advancePastStepIV(viewer);
        } else {
            int stepIV = passIndex(*viewer.renderer, viewer.frame, Pass::VoxelClipping);
            for (int i = 0; i < stepIV; ++i) ASSERT_FALSE(viewer.renderer->advanceExact(viewer.frame, 0.0, 1));
        }
        for (int i = 0; i < c.extraSlices; ++i) ASSERT_FALSE(viewer.renderer->advanceExact(viewer.frame, 0.0, 1));
        // The mesh moves on, with a preview; then the exact frame of pose 4, in slices.
        viewer.moveTo(4);
        viewer.renderer->renderPreview(viewer.frame);
        int calls = 0;
        while (!viewer.renderer->advanceExact(viewer.frame, 0.0, 3)) ASSERT_LT(++calls, 100000);
        EXPECT_EQ(viewer.ambient(), fresh.ambient()) << "V_AO differs from a fresh renderer's at the same pose";
        EXPECT_TRUE(sameImage(viewer.renderer->readImage(), fresh.renderer->readImage()));
    }
    // The same with render() taking over from the exact frame in slices (a viewer switched to exact quality).
    MovingSphereScene viewer;
    viewer.renderer->render(viewer.frame);
    viewer.moveTo(3);
    advancePastStepIV(viewer);
    viewer.moveTo(4);
    viewer.renderer->render(viewer.frame);
    EXPECT_EQ(viewer.ambient(), fresh.ambient()) << "render() after an exact frame in slices left its step V half done";

    // Back to the pose of the last finished exact frame after an abandoned step V: IV and V run again.
    MovingSphereScene back;
    back.renderer->render(back.frame);
    back.moveTo(3);
    advancePastStepIV(back);
    for (int i = 0; i < 2; ++i) ASSERT_FALSE(back.renderer->advanceExact(back.frame, 0.0, 1));
    back.moveTo(0);
    back.renderer->render(back.frame);
    MovingSphereScene freshAt0 = freshAt(0);
    EXPECT_EQ(back.ambient(), freshAt0.ambient()) << "an abandoned step V left V_AO counted as the last exact frame's";
}

// An abandoned step V is not finished later: after its step IV, the next exact frame in slices takes as many
// slices as the same update from a renderer whose exact frame at the abandoned pose was finished (finishing it
// first, as before, took that step V's slices on top).
TEST(ExactInSlices, AnAbandonedStepVIsNotFinishedByTheNextExactFrame) {
    auto slicesAfterStepIV = [](MovingSphereScene& s) {
        advancePastStepIV(s);
        int calls = 1;
        while (!s.renderer->advanceExact(s.frame, 0.0, 3)) ++calls;
        return calls;
    };
    MovingSphereScene viewer;
    viewer.renderer->render(viewer.frame);
    viewer.moveTo(3);
    advancePastStepIV(viewer);
    ASSERT_FALSE(viewer.renderer->advanceExact(viewer.frame, 0.0, 1));   // step V's list
    viewer.moveTo(4);
    int abandoned = slicesAfterStepIV(viewer);

    MovingSphereScene finished;
    finished.renderer->render(finished.frame);
    finished.moveTo(3);
    slicesAfterStepIV(finished);
    finished.moveTo(4);
    int after = slicesAfterStepIV(finished);
    EXPECT_EQ(viewer.ambient(), finished.ambient());
    EXPECT_EQ(abandoned, after) << "the next exact frame also ran the abandoned step V";
}

// The exact frame in slices runs the plan of the frame it computes, not the last frame's: a scene that gained
// tubes after its last exact frame (so that frame ran no tube G-buffer) is rendered with them, in cao (the ray
// cast, sliced like steps IV and V, stops at the tubes and reads V_AO at them) and in ismos (pass 1 stops at them),
// and equals render() of the same state bit for bit. Each pass reading the plan it belongs to is what makes it
// so; a pass reading the renderer's last plan drew these frames without the tubes' occlusion.
TEST(ExactInSlices, TubesAndIsmosInASlicedFrameEqualRender) {
    for (ShadingMode mode : {ShadingMode::Cao, ShadingMode::Ismos}) {
        SCOPED_TRACE(shadingModeName(mode));
        TubeVertices tube = test::straightTube(glm::dvec3(0, -2, 0), glm::dvec3(0, 0, 1), 14.0, 2.0, glm::vec4(1, 0.4, 0.2, 1));
        MovingSphereScene sliced(mode), whole(mode);
        sliced.renderer->render(sliced.frame);   // no tubes yet: this plan has no tube G-buffer
        sliced.moveTo(2);
        whole.moveTo(2);
        sliced.renderer->setTubes(tube, TubeShading{});
        whole.renderer->setTubes(tube, TubeShading{});
        whole.renderer->render(whole.frame);
        ASSERT_TRUE(whole.renderer->lastPlan().runs(Pass::TubeGBuffer));
        int calls = 0;
        while (!sliced.renderer->advanceExact(sliced.frame, 0.0, 2)) ASSERT_LT(++calls, 100000);
        EXPECT_GE(calls, 3) << "nothing was sliced";
        EXPECT_TRUE(sliced.renderer->lastPlan().runs(Pass::TubeGBuffer));
        EXPECT_TRUE(sameImage(sliced.renderer->readImage(), whole.renderer->readImage()))
            << "the exact frame in slices differs from render() with tubes in view";
        // A preview between them changes neither: the next exact frame of another pose still equals render().
        sliced.moveTo(3);
        whole.moveTo(3);
        FrameDescription small = sliced.frame;
        small.size = {24, 20};
        sliced.renderer->renderPreview(small);
        while (!sliced.renderer->advanceExact(sliced.frame, 0.0, 3)) ASSERT_LT(++calls, 200000);
        whole.renderer->render(whole.frame);
        EXPECT_TRUE(sameImage(sliced.renderer->readImage(), whole.renderer->readImage())) << "after a preview";
    }
}

// On an image wider than a part (TileOrderPiece::kPartPixels), a slice of one part casts a run of columns of
// one band: after a mesh motion (the recast region's tile spans) and after a camera turn (every tile), the
// exact frame in such slices equals render() bit for bit; after the turn it takes more calls than there are bands.
TEST(ExactInSlices, TheRayCastInPartsOfBandsEqualsRender) {
    for (ShadingMode mode : {ShadingMode::Phong, ShadingMode::Cao}) {
        SCOPED_TRACE(shadingModeName(mode));
        MovingSphereScene sliced(mode), whole(mode);
        for (MovingSphereScene* s : {&sliced, &whole}) {
            s->frame.size = {420, 72};
            s->frame.camera.fit(glm::dvec3(0), 12.0);
            s->renderer->render(s->frame);
        }
        for (int step = 0; step < 2; ++step) {
            SCOPED_TRACE(step == 0 ? "after a mesh motion" : "after a camera turn");
            if (step == 0) {
                sliced.moveTo(2), whole.moveTo(2);
            } else {
                sliced.frame.camera.azimuthDeg = whole.frame.camera.azimuthDeg = 70;
            }
            whole.renderer->render(whole.frame);
            int calls = 0, onRayCast = 0;
            const std::string rayCast = passInfo(Pass::RayCast).activity;
            while (!sliced.renderer->advanceExact(sliced.frame, 0.0, 1)) {
                ASSERT_LT(++calls, 100000);
                onRayCast += sliced.renderer->exactProgressLabel() == rayCast;
            }
            const int bands = (72 / 8 + TileOrderPiece::defaultRowsPerBand() - 1) / TileOrderPiece::defaultRowsPerBand();
            if (step == 1) {
                EXPECT_GT(onRayCast, bands) << "the ray cast went in whole bands";
            }
            EXPECT_TRUE(sameImage(sliced.renderer->readImage(), whole.renderer->readImage())) << "the ray cast in parts differs from render()";
        }
    }
}

// 240 thin tubes crossing at random through the volume: over three G-buffer units of triangles, and fragments of
// many tubes meet at one pixel, so their depth order matters.
TubeVertices crossingTubes() {
    std::mt19937 random(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    TubeVertices all;
    for (int i = 0; i < 240; ++i) {
        glm::dvec3 centre = 12.0 * glm::dvec3(u(random), u(random), u(random)), axis(u(random), u(random), u(random));
        if (glm::length(axis) < 0.1) axis = glm::dvec3(1, 0, 0);
        TubeVertices t = test::straightTube(centre, axis, 18.0, 0.7, glm::vec4(0.5 + 0.5 * u(random), 0.6, 0.3, 1));
        const auto offset = static_cast<std::uint32_t>(all.positions.size());
        all.positions.insert(all.positions.end(), t.positions.begin(), t.positions.end());
        all.directions.insert(all.directions.end(), t.directions.begin(), t.directions.end());
        all.colors.insert(all.colors.end(), t.colors.begin(), t.colors.end());
        for (std::uint32_t index : t.indices) all.indices.push_back(offset + index);
    }
    return all;
}

// The tube G-buffer in slices of one unit (TubeSet::drawGBuffer over index ranges, in order) gives render()'s
// image bit for bit, in the ray cast's modes and in dos; the progress stays on the G-buffer for several calls.
TEST(ExactInSlices, TheTubeGBufferInSlicesEqualsOneDraw) {
    const TubeVertices tubes = crossingTubes();
    ASSERT_GT(tubes.indices.size() / 3, 3u * 16384u) << "enough triangles for several slices";
    for (ShadingMode mode : {ShadingMode::Phong, ShadingMode::Cao, ShadingMode::Dos}) {
        SCOPED_TRACE(shadingModeName(mode));
        MovingSphereScene sliced(mode), whole(mode);
        for (MovingSphereScene* s : {&sliced, &whole}) {
            s->frame.size = {64, 56};
            s->renderer->setTubes(tubes, TubeShading{});
        }
        whole.renderer->render(whole.frame);
        ASSERT_TRUE(whole.renderer->lastPlan().runs(Pass::TubeGBuffer));
        const std::string gbuffer = passInfo(Pass::TubeGBuffer).activity;
        int calls = 0, onGBuffer = 0;
        double progress = 0;
        while (!sliced.renderer->advanceExact(sliced.frame, 0.0, 1)) {
            ASSERT_LT(++calls, 200000);
            if (sliced.renderer->exactProgressLabel() == gbuffer) {
                ++onGBuffer;
                EXPECT_GE(sliced.renderer->exactProgress(), progress) << "the progress falls within the G-buffer";
                progress = sliced.renderer->exactProgress();
            }
        }
        EXPECT_GE(onGBuffer, 3) << "the G-buffer was not sliced";
        EXPECT_TRUE(sameImage(sliced.renderer->readImage(), whole.renderer->readImage())) << "the G-buffer in slices differs from one draw";
    }
}

// Impostor tubes: a slice is a range of points' quads, drawn over the earlier ranges' depth, so the sliced
// G-buffer equals one draw's.
TEST(ExactInSlices, TheImpostorGBufferInSlicesEqualsOneDraw) {
    std::mt19937 random(6);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    Tractogram tracts;
    tracts.source = "random polylines";
    for (int s = 0; s < 2400; ++s) {
        glm::dvec3 p = 12.0 * glm::dvec3(u(random), u(random), u(random)), step(u(random), u(random), u(random));
        for (int i = 0; i < 24; ++i, p += 0.6 * step + 0.2 * glm::dvec3(u(random), u(random), u(random))) tracts.points.emplace_back(glm::vec3(p));
        tracts.offsets.push_back(static_cast<std::uint32_t>(tracts.points.size()));
    }
    TubeSettings settings;
    settings.radiusMm = 0.4;
    settings.smoothing = TubeSettings::Smoothing::None;
    const TubeImpostors impostors = sweepTubeImpostors(tracts, settings);
    ASSERT_GT(impostors.points.size(), 3u * 16384u) << "enough points for several slices";
    for (ShadingMode mode : {ShadingMode::Phong, ShadingMode::Dos}) {
        SCOPED_TRACE(shadingModeName(mode));
        MovingSphereScene sliced(mode), whole(mode);
        for (MovingSphereScene* s : {&sliced, &whole}) {
            s->frame.size = {64, 56};
            s->renderer->setTubeImpostors(impostors, TubeShading{});
        }
        whole.renderer->render(whole.frame);
        ASSERT_TRUE(whole.renderer->lastPlan().runs(Pass::TubeGBuffer));
        const std::string gbuffer = passInfo(Pass::TubeGBuffer).activity;
        int calls = 0, onGBuffer = 0;
        while (!sliced.renderer->advanceExact(sliced.frame, 0.0, 1)) {
            ASSERT_LT(++calls, 200000);
            onGBuffer += sliced.renderer->exactProgressLabel() == gbuffer;
        }
        EXPECT_GE(onGBuffer, 3) << "the G-buffer was not sliced";
        EXPECT_TRUE(sameImage(sliced.renderer->readImage(), whole.renderer->readImage())) << "the G-buffer in slices differs from one draw";
    }
}

// The slab pass's scenes: dos alone (the clip maps, then the slab pass), and dos with a tube in view (G-buffer, slab pass,
// composite: seed 000).
struct SlabCase {
    const char* name;
    ShadingMode mode;
    bool tubes;
};
constexpr SlabCase kSlabCases[] = {{"dos", ShadingMode::Dos, false}, {"dos with tubes", ShadingMode::Dos, true}};

MovingSphereScene slabScene(const SlabCase& c) {
    MovingSphereScene s(c.mode);
    if (c.tubes) s.renderer->setTubes(test::straightTube(glm::dvec3(0, -2, 0), glm::dvec3(0, 0, 1), 14.0, 2.0, glm::vec4(1, 0.4, 0.2, 1)), TubeShading{});
    return s;
}

// Slices of any fixed size (one per call at a zero budget; a unit is a band of rows of one view-aligned slice,
// SlabRun) give render()'s image bit for bit, and a call runs no more units than the size: at 48 x 40 a slice is
// one band, at 48 x 200 three. The progress rises through the pass and names it.
TEST(ExactInSlices, TheSlabPassInSlicesOfAnySizeEqualsRender) {
    for (const SlabCase& c : kSlabCases)
      for (glm::ivec2 imageSize : {glm::ivec2(48, 40), glm::ivec2(48, 200)}) {
        SCOPED_TRACE(std::string(c.name) + " at " + std::to_string(imageSize.x) + "x" + std::to_string(imageSize.y));
        MovingSphereScene whole = slabScene(c);
        whole.frame.size = imageSize;
        whole.renderer->render(whole.frame);
        ASSERT_TRUE(whole.renderer->lastPlan().runs(Pass::SlabPass));
        const Image expected = whole.renderer->readImage();
        const int bands = SlabPass::bandsPerSlice(imageSize.y);
        EXPECT_EQ(bands, imageSize.y == 40 ? 1 : 3);
        const int slices = whole.renderer->slabPass().slicesLastFrame() * bands;   // units
        ASSERT_GT(slices, 40) << "enough units for the sizes below to mean something";
        const std::string slabActivity = passInfo(Pass::SlabPass).activity;
        for (std::uint32_t size : {1u, 7u, 64u, 100000u}) {
            SCOPED_TRACE("slices of " + std::to_string(size));
            MovingSphereScene sliced = slabScene(c);
            sliced.frame.size = imageSize;
            const int slabIndex = passIndex(*sliced.renderer, sliced.frame, Pass::SlabPass);
            ASSERT_GE(slabIndex, 0);
            int insideSlab = 0, calls = 0;
            double progress = 0;
            while (!sliced.renderer->advanceExact(sliced.frame, 0.0, size)) {
                ASSERT_LT(++calls, 100000);
                if (sliced.renderer->exactProgressLabel() == slabActivity) {
                    ++insideSlab;
                    EXPECT_GT(sliced.renderer->exactProgress(), progress) << "call " << calls;
                }
                EXPECT_GE(sliced.renderer->exactProgress(), progress);
                progress = sliced.renderer->exactProgress();
                EXPECT_FALSE(sliced.renderer->showing(sliced.frame));
            }
            // The calls that leave the slab pass under way: the one that ends the pass before it (the clip maps),
            // then each slice of `size` but the last.
            const int slicesCalls = (slices + int(size) - 1) / int(size);
            EXPECT_EQ(insideSlab, slicesCalls - 1 + (slabIndex > 0 ? 1 : 0)) << "each call ran " << size << " slices of " << slices;
            EXPECT_STREQ(sliced.renderer->exactProgressLabel(), "") << "nothing under way once done";
            EXPECT_TRUE(sliced.renderer->showing(sliced.frame));
            EXPECT_EQ(sliced.renderer->slabPass().slicesLastFrame() * bands, slices);
            EXPECT_TRUE(sameImage(sliced.renderer->readImage(), expected)) << "the slab pass in slices differs from render()";
        }
    }
}

// Previews drawn between the slab pass's slices (the window keeps drawing while the exact frame is computed): a
// preview at another size in the frame's own mode, and one in ismos, which with tubes redraws the tube G-buffer
// the exact frame's slab pass and compositor read, at the preview's size. Either restarts the exact frame (a
// preview is counted in the run: Renderer::exactJobCurrent), and the exact image stays render()'s bit for bit.
TEST(ExactInSlices, PreviewsBetweenSlabSlicesLeaveTheExactImageIdentical) {
    for (const SlabCase& c : kSlabCases) {
        SCOPED_TRACE(c.name);
        MovingSphereScene whole = slabScene(c), sliced = slabScene(c);
        whole.renderer->render(whole.frame);
        FrameDescription small = sliced.frame, ismos = sliced.frame;
        small.size = {24, 20};
        ismos.size = {30, 22};
        ismos.shading = ShadingMode::Ismos;
        int calls = 0;
        for (const FrameDescription* preview : {&small, &ismos, &small}) {
            for (int i = 0; i < 4; ++i) ASSERT_FALSE(sliced.renderer->advanceExact(sliced.frame, 0.0, 5)) << "the slab pass ended too soon";
            ASSERT_EQ(sliced.renderer->exactProgressLabel(), std::string(passInfo(Pass::SlabPass).activity));
            sliced.renderer->renderPreview(*preview);
            if (c.tubes && preview == &ismos) {
                ASSERT_TRUE(sliced.renderer->lastPlan().runs(Pass::TubeGBuffer)) << "the ismos preview redraws the G-buffer";
            }
        }
        while (!sliced.renderer->advanceExact(sliced.frame, 0.0, 5)) ASSERT_LT(++calls, 100000);
        EXPECT_TRUE(sameImage(sliced.renderer->readImage(), whole.renderer->readImage())) << "previews between slab slices changed the exact image";
    }
}

}  // namespace
}  // namespace curette
