// Preview and exact frames (docs/architecture.md): step I in slices equals step I in one dispatch bit for bit;
// a preview (steps I, IV, V left out) writes nothing an exact frame reads, so the exact frame after any number
// of previews equals a fresh renderer's; a preview during step I is the phong frame; a preview never runs the
// slab pass (dos previews as phong, tubes are left out but in ismos).
#include "tests/render/moving_sphere_scene.h"

#include <gtest/gtest.h>

namespace curette {
namespace {


using test::MovingSphereScene;
using test::sameImage;

bool runs(const FramePlan& plan, Pass pass) { return plan.runs(pass); }

TEST(Preview, StepIInSlicesEqualsStepIInOneDispatch) {
    MovingSphereScene whole, sliced;
    whole.renderer->render(whole.frame);   // step I in one dispatch per phase, then IV, V, VI
    ASSERT_TRUE(runs(whole.renderer->lastPlan(), Pass::LaoPrecompute));
    std::vector<std::uint16_t> expected = whole.renderer->ambientOcclusion()->readPrecomputed();

    // Slices of 7 bricks of the 12 x 10 x 11 = 1320: neither a brick row nor a z-slab, the last one short.
    EXPECT_TRUE(sliced.renderer->precomputePending(sliced.frame));
    int slices = 0;
    double progress = 0;
    while (sliced.renderer->precomputePending(sliced.frame)) {
        double now = sliced.renderer->advancePrecompute(0.0, 7);
        EXPECT_GT(now, progress) << "slice " << slices << " advances step I";
        EXPECT_DOUBLE_EQ(now, sliced.renderer->precomputeProgress());
        progress = now;
        ASSERT_LT(++slices, 1000);
    }
    EXPECT_EQ(slices, 2 * 189) << "189 slices of voxel clipping, then 189 of LAO";
    EXPECT_DOUBLE_EQ(progress, 1.0);
    EXPECT_EQ(sliced.renderer->ambientOcclusion()->readPrecomputed(), expected) << "V_PAO in slices differs from one dispatch";
    // The exact frame after it runs no step I and equals the one-dispatch renderer's.
    sliced.renderer->render(sliced.frame);
    EXPECT_FALSE(runs(sliced.renderer->lastPlan(), Pass::LaoPrecompute));
    EXPECT_EQ(sliced.ambient(), whole.ambient());
    EXPECT_TRUE(sameImage(sliced.renderer->readImage(), whole.renderer->readImage()));
}

TEST(Preview, AnExactFrameDuringStepIInSlicesFinishesItAndEqualsOneDispatch) {
    MovingSphereScene whole, sliced;
    whole.renderer->render(whole.frame);
    for (int i = 0; i < 300; ++i) sliced.renderer->advancePrecompute(0.0, 5);   // phase 1 done (264 slices), phase 2 begun
    ASSERT_TRUE(sliced.renderer->precomputePending(sliced.frame));
    sliced.renderer->render(sliced.frame);
    EXPECT_FALSE(sliced.renderer->precomputePending(sliced.frame));
    EXPECT_EQ(sliced.renderer->ambientOcclusion()->readPrecomputed(), whole.renderer->ambientOcclusion()->readPrecomputed());
    EXPECT_TRUE(sameImage(sliced.renderer->readImage(), whole.renderer->readImage()));
}

TEST(Preview, APreviewDuringStepIIsThePhongFrame) {
    MovingSphereScene scene, phong;
    scene.renderer->advancePrecompute(0.0, 3);
    ASSERT_TRUE(scene.renderer->precomputePending(scene.frame));
    EXPECT_EQ(scene.renderer->previewAmbient(), Renderer::PreviewAmbient::None);
    scene.renderer->renderPreview(scene.frame);
    EXPECT_FALSE(scene.renderer->lastFrameExact());
    EXPECT_FALSE(scene.renderer->showing(scene.frame)) << "a preview is not the exact frame";
    EXPECT_TRUE(scene.renderer->showingPreview(scene.frame));
    for (const PlannedPass& p : scene.renderer->lastPlan().passes)
        EXPECT_FALSE(passInfo(p.pass).ambientOcclusion) << passInfo(p.pass).name << " in a preview";
    FrameDescription phongFrame = phong.frame;
    phongFrame.shading = ShadingMode::Phong;
    phong.renderer->render(phongFrame);
    EXPECT_TRUE(sameImage(scene.renderer->readImage(), phong.renderer->readImage())) << "the preview is not the phong frame";
    EXPECT_GT(scene.renderer->precomputeProgress(), 0.0);
    EXPECT_LT(scene.renderer->precomputeProgress(), 1.0) << "a preview runs no step I";
}

// The exactness contract across previews: an exact frame, previews at other poses and sizes (shading with the
// last exact V_AO, and with V_PAO before any exact frame), and the exact frame of the last pose equals a fresh
// renderer's for that pose (what `curette render` gives), V_AO and image bit for bit.
TEST(Preview, NeverChangesTheExactFrame) {
    for (bool exactFirst : {true, false}) {
        SCOPED_TRACE(exactFirst ? "previews after an exact frame" : "previews straight after step I");
        MovingSphereScene viewer, fresh;
        if (exactFirst) {
            viewer.renderer->render(viewer.frame);
            EXPECT_EQ(viewer.renderer->previewAmbient(), Renderer::PreviewAmbient::LastExact);
        } else {
            while (viewer.renderer->precomputePending(viewer.frame)) viewer.renderer->advancePrecompute(1e9);
            EXPECT_EQ(viewer.renderer->previewAmbient(), Renderer::PreviewAmbient::Precomputed);
        }
        Image lastPreview;
        for (int n = 1; n <= 4; ++n) {
            viewer.moveTo(n);
            FrameDescription small = viewer.frame;
            small.size = {24 + n, 20};
            viewer.renderer->renderPreview(small);
            EXPECT_FALSE(runs(viewer.renderer->lastPlan(), Pass::VoxelClipping)) << "pose " << n;
            EXPECT_FALSE(runs(viewer.renderer->lastPlan(), Pass::LaoRecompute)) << "pose " << n;
            EXPECT_TRUE(runs(viewer.renderer->lastPlan(), Pass::RayCast)) << "pose " << n;
            EXPECT_TRUE(viewer.renderer->showingPreview(small));
            EXPECT_FALSE(viewer.renderer->showing(small));
            lastPreview = viewer.renderer->readImage();
        }
        // The motion stops at pose 4; a full-size preview there too, then the exact frame.
        viewer.renderer->renderPreview(viewer.frame);
        Image preview = viewer.renderer->readImage();
        viewer.renderer->render(viewer.frame);
        EXPECT_TRUE(viewer.renderer->lastFrameExact());
        EXPECT_TRUE(viewer.renderer->showing(viewer.frame));
        EXPECT_TRUE(runs(viewer.renderer->lastPlan(), Pass::LaoRecompute)) << "the exact frame runs step V";
        fresh.moveTo(4);
        fresh.renderer->render(fresh.frame);
        EXPECT_EQ(viewer.ambient(), fresh.ambient()) << "V_AO after previews differs from a fresh renderer's";
        EXPECT_TRUE(sameImage(viewer.renderer->readImage(), fresh.renderer->readImage())) << "the exact image differs";
        EXPECT_FALSE(sameImage(preview, fresh.renderer->readImage())) << "the preview must differ for the test to mean something";
        EXPECT_EQ(viewer.renderer->previewAmbient(), Renderer::PreviewAmbient::LastExact);
    }
}

// The slab pass costs seconds at any preview size on a software renderer, so no preview runs it: dos previews as
// the phong frame does, and with tubes in view a preview leaves them out (its image pass is the ray cast) in every
// mode but ismos, whose pass 1 stops at the tubes without the slab pass and keeps them (the G-buffer costs what
// its triangles cost at any preview size). The exact frame after the previews is still the frame's own (dos: the
// slab pass, with tubes G-buffer, slab pass, composite; phong and solid with tubes: G-buffer and ray cast).
TEST(Preview, NeverRunsTheSlabPass) {
    TubeVertices tube = test::straightTube(glm::dvec3(0, -2, 0), glm::dvec3(0, 0, 1), 14.0, 2.0, glm::vec4(1, 0.4, 0.2, 1));
    struct Case {
        ShadingMode mode;
        bool tubes;
        ShadingMode previewedAs;   // the preview's image equals this mode's preview without tubes
    };
    for (Case c : {Case{ShadingMode::Dos, false, ShadingMode::Phong}, Case{ShadingMode::Dos, true, ShadingMode::Phong},
                   Case{ShadingMode::Phong, true, ShadingMode::Phong}, Case{ShadingMode::Solid, true, ShadingMode::Solid}}) {
        SCOPED_TRACE(std::string(shadingModeName(c.mode)) + (c.tubes ? " with tubes" : ""));
        MovingSphereScene scene(c.mode), reference(c.previewedAs);
        if (c.tubes) scene.renderer->setTubes(tube, TubeShading{});
        FrameDescription small = scene.frame;
        small.size = {24, 20};
        scene.renderer->renderPreview(small);
        EXPECT_TRUE(scene.renderer->showingPreview(small));
        for (Pass p : {Pass::SlabPass, Pass::TubeGBuffer, Pass::Composite})
            EXPECT_FALSE(runs(scene.renderer->lastPlan(), p)) << passInfo(p).name << " in a preview";
        EXPECT_TRUE(runs(scene.renderer->lastPlan(), Pass::RayCast));
        FrameDescription referenceFrame = reference.frame;
        referenceFrame.size = small.size;
        reference.renderer->renderPreview(referenceFrame);
        EXPECT_TRUE(sameImage(scene.renderer->readImage(), reference.renderer->readImage())) << "the preview is not the ray cast of " << shadingModeName(c.previewedAs);
        // The exact frame is the frame's own, equal to a fresh renderer's.
        MovingSphereScene fresh(c.mode);
        if (c.tubes) fresh.renderer->setTubes(tube, TubeShading{});
        fresh.renderer->render(fresh.frame);
        scene.renderer->render(scene.frame);
        EXPECT_EQ(runs(scene.renderer->lastPlan(), Pass::SlabPass), c.mode == ShadingMode::Dos);
        EXPECT_EQ(runs(scene.renderer->lastPlan(), Pass::TubeGBuffer), c.tubes);
        EXPECT_TRUE(sameImage(scene.renderer->readImage(), fresh.renderer->readImage()));
        EXPECT_FALSE(sameImage(scene.renderer->readImage(), [&] {
            reference.renderer->render(reference.frame);
            return reference.renderer->readImage();
        }())) << "the exact frame must differ from the preview's mode for the test to mean something";
    }
    // ismos keeps its tubes in a preview (no slab pass in its plan).
    MovingSphereScene ismos(ShadingMode::Ismos);
    ismos.renderer->setTubes(tube, TubeShading{});
    ismos.renderer->renderPreview(ismos.frame);
    EXPECT_TRUE(runs(ismos.renderer->lastPlan(), Pass::TubeGBuffer));
    EXPECT_FALSE(runs(ismos.renderer->lastPlan(), Pass::SlabPass));
}

}  // namespace
}  // namespace curette
