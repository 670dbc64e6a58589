// A mode switch in the viewer's iteration (viewer/viewer_driver.h: what the window and `bench view` run) never
// leaves the window without a frame, said as work per iteration rather than time: the first frame of a scene is
// a preview; pressing 5 (dos) previews at once without the slab pass; then each iteration runs at most one slice's
// worth of the dos frame's slab pass (units: bands of rows of its view-aligned slices) and presents the preview with the progress, until the exact frame is shown,
// which is a fresh renderer's dos image. The slices' size is fixed and the budget is so small that every
// iteration runs one slice; no time is asserted.
#include "session/interaction.h"
#include "session/loaded_scene.h"
#include "session/session_step.h"
#include "viewer/viewer_driver.h"
#include "render/label_overlay.h"
#include "render/renderer.h"

#include <gtest/gtest.h>

#include <cmath>

namespace curette {
namespace {

const std::string kSource = CURETTE_SOURCE_DIR;

TEST(ViewerDriver, ASwitchToDosPresentsEveryIterationAndNeverRunsTheWholeSlabPass) {
    LoadedScene loaded = loadSceneWithVolume(kSource + "/assets/scenes/head.json");
    auto context = gl::createHeadlessContext();
    Renderer renderer(*context, loaded.volume, loaded.scene.transferFunction);
    configureRenderer(loaded, renderer);
    SessionStep step(InteractionState::fromScene(loaded.scene), initialFrame(loaded.scene, renderer.geometry()));
    ASSERT_EQ(step.state().shading, ShadingMode::Phong);
    FrameLoopSettings settings;
    settings.quality = ViewQuality::Adaptive;
    settings.exactBudgetMs = 1e-6;    // one slice an iteration
    constexpr std::uint32_t kSlices = 40;
    settings.exactSliceUnits = kSlices;
    ViewerState viewer(settings);
    const glm::ivec2 size{64, 48};
    const glm::vec4 background(loaded.scene.background);
    double now = 0;
    auto iterate = [&](bool moved) {
        now += 1.0;   // a second an iteration: a motion has settled by the next one
        return stepViewer(viewer, renderer, step, loaded.tracts, size, now, moved, background);
    };

    // The first frame of the scene: a preview before any slice of the exact frame.
    ViewerIteration first = iterate(false);
    EXPECT_EQ(first.decision.render, FrameKind::Preview) << "the first frame of a scene presents a preview first";
    EXPECT_TRUE(first.rendered);
    for (int i = 0; i < 1000 && !viewer.shownExact; ++i) ASSERT_TRUE(iterate(false).rendered);
    ASSERT_TRUE(viewer.shownExact);

    // 5: dos.
    step.state().shading = ShadingMode::Dos;
    ViewerIteration switched = iterate(true);
    EXPECT_EQ(switched.decision.render, FrameKind::Preview);
    EXPECT_TRUE(switched.rendered);
    EXPECT_FALSE(renderer.lastPlan().runs(Pass::SlabPass)) << "the preview of dos runs no slab pass";

    int iterations = 0, slabIterations = 0;
    long slabSlices = 0;
    double progress = 0;
    bool done = false;
    while (!done) {
        ASSERT_LT(++iterations, 100000);
        ViewerIteration it = iterate(false);
        ASSERT_EQ(it.decision.render, FrameKind::Exact);
        EXPECT_TRUE(it.rendered) << "iteration " << iterations << " presented nothing";
        done = it.exactCompleted;
        if (done) break;
        EXPECT_FALSE(viewer.shownExact) << "the preview stays on screen while the exact frame is computed";
        EXPECT_FALSE(renderer.lastFrameExact());
        if (renderer.exactProgressLabel() != std::string(passInfo(Pass::SlabPass).activity)) continue;
        ++slabIterations;
        slabSlices = renderer.slabPass().slicesLastFrame() * SlabPass::bandsPerSlice(size.y);   // units: bands of slices
        // The dos frame's plan is the clip maps (none here) and the slab pass: its progress is the slices done.
        double slicesRun = (renderer.exactProgress() - progress) * double(slabSlices);
        EXPECT_LE(std::lround(slicesRun), long(kSlices)) << "iteration " << iterations << " ran more than a slice";
        progress = renderer.exactProgress();
    }
    ASSERT_GT(slabSlices, long(2 * kSlices)) << "the slab pass must be longer than a few slices for the test to mean something";
    EXPECT_EQ(slabIterations, (slabSlices + kSlices - 1) / kSlices - 1) << "one slice an iteration, the last one finishing the frame";
    EXPECT_TRUE(viewer.shownExact);
    EXPECT_TRUE(renderer.lastPlan().runs(Pass::SlabPass));

    // The exact frame is what a fresh renderer gives for the dos frame.
    Image shown = renderer.readImage();
    Renderer fresh(*context, loaded.volume, loaded.scene.transferFunction);
    configureRenderer(loaded, fresh);
    FrameDescription frame = viewerFrame(viewer, step, size);
    ASSERT_EQ(frame.shading, ShadingMode::Dos);
    fresh.render(frame);
    Image expected = fresh.readImage();
    ASSERT_EQ(shown.pixels.size(), expected.pixels.size());
    EXPECT_TRUE(std::equal(shown.pixels.begin(), shown.pixels.end(), expected.pixels.begin(),
                           [](const glm::vec4& a, const glm::vec4& b) { return a == b; }))
        << "the exact frame in slices differs from a fresh render";
}


// A labelled scene's first frame builds the label field in slices of a few planes, presenting each (the window
// shows the progress, no image yet); then the preview and the exact frame follow, and the exact frame is what a
// renderer that built the field whole shows. A label style edit builds it again in slices, the image kept.
TEST(ViewerDriver, ALabelledScenesFirstFrameBuildsTheLabelFieldInSlices) {
    LoadedScene loaded = loadSceneWithVolume(kSource + "/assets/scenes/head.json");
    const glm::ivec3 dims = loaded.volume.dims;
    std::vector<std::uint16_t> ids(std::size_t(dims.x) * dims.y * dims.z, 0);
    for (int k = 0; k < dims.z; ++k)
        for (int j = 0; j < dims.y; ++j)
            for (int i = 0; i < dims.x; ++i)
                if (glm::length(glm::dvec3(i, j, k) - glm::dvec3(dims) * 0.5) < 25.0) ids[(std::size_t(k) * dims.y + j) * dims.x + i] = 1;
    const std::vector<glm::vec4> styles{glm::vec4(0), glm::vec4(0.9f, 0.2f, 0.2f, 0.6f)};
    auto context = gl::createHeadlessContext();
    Renderer renderer(*context, loaded.volume, loaded.scene.transferFunction);
    configureRenderer(loaded, renderer);
    renderer.setLabels(std::make_unique<LabelOverlay>(dims, ids, styles));
    SessionStep step(InteractionState::fromScene(loaded.scene), initialFrame(loaded.scene, renderer.geometry()));
    FrameLoopSettings settings;
    settings.quality = ViewQuality::Adaptive;
    constexpr int kPlanes = 8;
    settings.labelSlicePlanes = kPlanes;
    ViewerState viewer(settings);
    const glm::ivec2 size{64, 48};
    const glm::vec4 background(loaded.scene.background);
    double now = 0;
    auto iterate = [&] {
        now += 1.0;
        return stepViewer(viewer, renderer, step, loaded.tracts, size, now, false, background);
    };
    // Classify, blur along x, y and z, pack: each over the planes of k; then one upload.
    const int expectedSlices = 5 * ((dims.z + kPlanes - 1) / kPlanes) + 1;
    auto buildInSlices = [&](const char* when) {
        int slices = 0;
        double progress = renderer.labelFieldProgress();
        while (renderer.labelFieldPending()) {
            ASSERT_LT(++slices, 10 * expectedSlices);
            ViewerIteration it = iterate();
            EXPECT_TRUE(it.preparing) << when;
            EXPECT_TRUE(it.rendered) << when << ": slice " << slices << " presented nothing";
            EXPECT_EQ(it.decision.render, FrameKind::None) << when << ": nothing is drawn while the field is built";
            EXPECT_LE(renderer.labelFieldProgress() - progress, double(kPlanes) / (5.0 * dims.z + 1.0) + 1e-9) << when;
            progress = renderer.labelFieldProgress();
        }
        EXPECT_EQ(slices, expectedSlices) << when << ": one slice an iteration";
    };
    ASSERT_TRUE(renderer.labelFieldPending());
    buildInSlices("first frame");
    EXPECT_FALSE(renderer.showsAnImage());
    ViewerIteration first = iterate();
    EXPECT_EQ(first.decision.render, FrameKind::Preview) << "the first image after the field is a preview";
    for (int i = 0; i < 1000 && !viewer.shownExact; ++i) ASSERT_FALSE(iterate().preparing);
    ASSERT_TRUE(viewer.shownExact);

    auto renderWhole = [&](const std::vector<glm::vec4>& s) {
        Renderer fresh(*context, loaded.volume, loaded.scene.transferFunction);
        configureRenderer(loaded, fresh);
        fresh.setLabels(std::make_unique<LabelOverlay>(dims, ids, s));
        fresh.render(viewerFrame(viewer, step, size));
        return fresh.readImage();
    };
    auto same = [](const Image& a, const Image& b) {
        return a.pixels.size() == b.pixels.size() &&
               std::equal(a.pixels.begin(), a.pixels.end(), b.pixels.begin(), [](const glm::vec4& x, const glm::vec4& y) { return x == y; });
    };
    EXPECT_TRUE(same(renderer.readImage(), renderWhole(styles))) << "the field built in slices differs from one built whole";

    // A style edit: built again in slices while the exact image stays on screen.
    const std::vector<glm::vec4> green{glm::vec4(0), glm::vec4(0.1f, 0.9f, 0.2f, 0.8f)};
    renderer.setLabelStyles(green);
    buildInSlices("after a style edit");
    EXPECT_TRUE(renderer.showsAnImage());
    for (int i = 0; i < 1000 && !(viewer.shownExact && renderer.showing(viewerFrame(viewer, step, size))); ++i) iterate();
    EXPECT_TRUE(same(renderer.readImage(), renderWhole(green)));
}


// A scene with several tools draws their clip maps a mesh an iteration, presenting each; the last mesh's maps come
// with the first image. The exact frame is a fresh render's.
TEST(ViewerDriver, SeveralToolsClipMapsAreDrawnAMeshAnIteration) {
    LoadedScene loaded = loadSceneWithVolume(kSource + "/assets/scenes/head-carved.json");
    auto context = gl::createHeadlessContext();
    Renderer renderer(*context, loaded.volume, loaded.scene.transferFunction);
    configureRenderer(loaded, renderer);
    SessionStep step(InteractionState::fromScene(loaded.scene), initialFrame(loaded.scene, renderer.geometry()));
    step.state().shading = ShadingMode::Phong;   // no step I: the test is about the maps
    ViewerState viewer(FrameLoopSettings{});
    viewer.loop.setQuality(ViewQuality::Adaptive);
    const glm::ivec2 size{64, 48};
    const glm::vec4 background(loaded.scene.background);
    double now = 0;
    auto iterate = [&] {
        now += 1.0;
        return stepViewer(viewer, renderer, step, loaded.tracts, size, now, false, background);
    };
    ViewerIteration first = iterate();   // syncs the meshes, then draws the first mesh's maps
    const int meshes = renderer.clipMeshes().count();
    ASSERT_GE(meshes, 2);
    EXPECT_TRUE(first.preparing);
    EXPECT_TRUE(first.rendered);
    EXPECT_EQ(renderer.clipMeshes().mapRenderCount(), 1u);
    for (int m = 2; m < meshes; ++m) {
        ViewerIteration it = iterate();
        EXPECT_TRUE(it.preparing && it.rendered);
        EXPECT_EQ(renderer.clipMeshes().mapRenderCount(), std::uint64_t(m));
    }
    EXPECT_EQ(renderer.clipMapsToDraw(viewerFrame(viewer, step, size)), 1);
    ViewerIteration preview = iterate();
    EXPECT_FALSE(preview.preparing);
    EXPECT_EQ(preview.decision.render, FrameKind::Preview);
    EXPECT_EQ(renderer.clipMeshes().mapRenderCount(), std::uint64_t(meshes));
    for (int i = 0; i < 1000 && !viewer.shownExact; ++i) ASSERT_FALSE(iterate().preparing);
    ASSERT_TRUE(viewer.shownExact);

    Renderer fresh(*context, loaded.volume, loaded.scene.transferFunction);
    configureRenderer(loaded, fresh);
    syncClipMeshes(step.state(), fresh.clipMeshes());
    fresh.render(viewerFrame(viewer, step, size));
    Image shown = renderer.readImage(), expected = fresh.readImage();
    ASSERT_EQ(shown.pixels.size(), expected.pixels.size());
    EXPECT_TRUE(std::equal(shown.pixels.begin(), shown.pixels.end(), expected.pixels.begin(),
                           [](const glm::vec4& a, const glm::vec4& b) { return a == b; }))
        << "maps drawn a mesh an iteration give another image than maps drawn at once";
}

}  // namespace
}  // namespace curette
