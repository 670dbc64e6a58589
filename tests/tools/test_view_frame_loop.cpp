// The viewer's frame-loop decisions (viewer/view_frame_loop.h) on a fake clock and a fake renderer: previews
// while something moves, the exact frame once nothing has moved for the settle time, step I in slices with a
// preview meanwhile, the preview resolution steered by its cost, and exact quality never previewing motion.
#include "viewer/view_frame_loop.h"

#include <gtest/gtest.h>

#include <limits>

#include <cmath>

#include <optional>

namespace curette {
namespace {

// What the fake renderer shows: the last frame it was asked for (a kind and a size), until the scene moves.
struct FakeScreen {
    std::optional<std::pair<FrameKind, glm::ivec2>> shown;
    void moved() { shown.reset(); }
    void show(const FrameDecision& d) {
        if (d.render != FrameKind::None) shown = std::make_pair(d.render, d.size);
    }
    // The exact frame at the window's size, or a preview at any size.
    void describe(FrameLoopInputs& in, glm::ivec2 exactSize) const {
        in.exactShown = shown && shown->first == FrameKind::Exact && shown->second == exactSize;
        in.previewShown = shown && shown->first == FrameKind::Preview;
    }
};

constexpr glm::ivec2 kWindow{1000, 800};

struct LoopRun {
    ViewFrameLoop loop;
    FakeScreen screen;
    double now = 0;
    explicit LoopRun(FrameLoopSettings s = {}) : loop(s) {}
    // msAtHalf: what a frame costs at half the window's resolution; a frame's cost grows with its pixels.
    std::uint64_t precomputeInputs = 7;   // step I's inputs (Renderer::precomputeInputsVersion)
    FrameDecision frame(bool moved, bool precomputePending = false, double msAtHalf = 50,
                        double movedAt = std::numeric_limits<double>::quiet_NaN()) {
        if (moved) screen.moved();
        FrameLoopInputs in;
        in.now = now;
        in.moved = moved;
        in.movedAt = movedAt;
        in.precomputePending = precomputePending;
        in.precomputeInputs = precomputeInputs;
        in.exactSize = kWindow;
        screen.describe(in, kWindow);
        FrameDecision d = loop.decide(in);
        screen.show(d);
        double scale = d.size.x / (0.5 * kWindow.x);
        if (d.render != FrameKind::None) loop.rendered(d, msAtHalf * scale * scale);
        now += 0.0625;   // 16 frames a second (a binary fraction: the clock's sums are exact)
        return d;
    }
};

TEST(ViewFrameLoop, PreviewsWhileMovingAndRendersTheExactFrameOnceTheMotionHasSettled) {
    FrameLoopSettings s;
    s.settleSeconds = 0.25;
    s.previewTargetMs = 50;   // the frames below cost 50 ms at scale 0.5: the preview scale stays there
    s.minPreviewScale = s.maxPreviewScale = 0.5;
    LoopRun run(s);
    FrameDecision first = run.frame(false);
    EXPECT_EQ(first.render, FrameKind::Exact) << "a still scene starts exact";
    EXPECT_EQ(first.size, kWindow);
    EXPECT_EQ(run.frame(false).render, FrameKind::None) << "nothing changed: nothing to render";
    for (int i = 0; i < 5; ++i) {
        FrameDecision d = run.frame(true);
        EXPECT_EQ(d.render, FrameKind::Preview) << "moving frame " << i;
        EXPECT_TRUE(d.inMotion);
        EXPECT_EQ(d.size, glm::ivec2(500, 400)) << "at the preview scale (0.5)";
        EXPECT_EQ(d.rayStepScale, 2.0) << "and twice the ray step";
    }
    double lastMotion = run.now - 0.0625;
    EXPECT_DOUBLE_EQ(run.loop.lastMotion(), lastMotion);
    // Still frames: the preview stays on screen until settleSeconds have passed since the last motion.
    int exactAt = -1;
    for (int i = 0; i < 10 && exactAt < 0; ++i) {
        double t = run.now;
        FrameDecision d = run.frame(false);
        if (t - lastMotion < s.settleSeconds) {
            EXPECT_EQ(d.render, FrameKind::None) << "still within the settle time at " << t - lastMotion << " s";
            EXPECT_TRUE(d.inMotion);
        } else {
            EXPECT_EQ(d.render, FrameKind::Exact) << (t - lastMotion) << " s after the last motion";
            EXPECT_EQ(d.size, kWindow);
            EXPECT_EQ(d.rayStepScale, 1.0);
            EXPECT_EQ(d.exactBudgetMs, s.exactBudgetMs) << "adaptive quality computes the exact frame in slices";
            EXPECT_GT(d.exactBudgetMs, 0.0);
            EXPECT_FALSE(d.inMotion);
            exactAt = i;
        }
    }
    EXPECT_EQ(exactAt, 3) << "0.0625, 0.125, 0.1875 s wait; at 0.25 s the exact frame";
    EXPECT_EQ(run.frame(false).render, FrameKind::None);
}

// The last motion's preview steers the resolution like every other, so the next preview would have another size.
// Once the motion stops, the preview on screen already shows the frame: drawing it again at the new size would
// show the same picture a frame later and hold the exact frame back by that frame.
TEST(ViewFrameLoop, AfterTheMotionThePreviewOnScreenIsNotDrawnAgainAtTheSteeredSize) {
    FrameLoopSettings s;
    s.settleSeconds = 0.25;
    s.previewTargetMs = 50;
    s.minPreviewScale = 0.125;
    s.maxPreviewScale = 0.5;
    LoopRun run(s);
    run.frame(false);   // the exact frame
    glm::ivec2 lastPreview{0};
    for (int i = 0; i < 5; ++i) {
        FrameDecision d = run.frame(true, false, 400);   // 400 ms at half resolution: the steering shrinks it
        ASSERT_EQ(d.render, FrameKind::Preview);
        lastPreview = d.size;
    }
    ASSERT_NE(run.loop.previewSize(kWindow), lastPreview) << "the steering has moved the size since the last preview";
    double lastMotion = run.loop.lastMotion();
    int exactAt = -1;
    for (int i = 0; i < 10 && exactAt < 0; ++i) {
        double t = run.now;
        FrameDecision d = run.frame(false, false, 400);
        if (t - lastMotion < s.settleSeconds) {
            EXPECT_EQ(d.render, FrameKind::None) << "the frame's preview is on screen at " << t - lastMotion << " s";
            EXPECT_TRUE(d.inMotion);
        } else {
            EXPECT_EQ(d.render, FrameKind::Exact);
            exactAt = i;
        }
    }
    EXPECT_EQ(exactAt, 3);
    // A motion draws a preview at the steered size again.
    glm::ivec2 steered = run.loop.previewSize(kWindow);
    FrameDecision moved = run.frame(true, false, 400);
    EXPECT_EQ(moved.render, FrameKind::Preview);
    EXPECT_EQ(moved.size, steered);
}

// A played session's motion reaches the loop after the frame it was rendering: the settle time counts from the
// motion's own time (FrameLoopInputs::movedAt), so the exact frame waits no longer for the loop's lateness; a
// motion given no time counts from the frame, as before; and a late time never moves the last motion back.
TEST(ViewFrameLoop, TheSettleTimeCountsFromWhenTheMotionHappened) {
    FrameLoopSettings s;
    s.settleSeconds = 0.25;
    s.minPreviewScale = s.maxPreviewScale = 0.5;
    for (bool timed : {true, false}) {
        SCOPED_TRACE(timed ? "with the motion's time" : "without");
        LoopRun run(s);
        run.frame(false);
        // Each motion happened 0.125 s (two frames of 1/16 s) before the frame that applies it.
        double happened = 0;
        for (int i = 0; i < 5; ++i) {
            happened = run.now - 0.125;
            ASSERT_EQ(run.frame(true, false, 50, timed ? happened : std::numeric_limits<double>::quiet_NaN()).render, FrameKind::Preview);
        }
        EXPECT_EQ(run.loop.lastMotion(), timed ? happened : run.now - 0.0625);
        int stillFrames = 0;
        while (run.frame(false).render != FrameKind::Exact) ASSERT_LT(++stillFrames, 10);
        // 0.25 s settle at 1/16 s a frame: from the motion's time two frames after the one that applied it, from that
        // frame's own time four.
        EXPECT_EQ(stillFrames, timed ? 1 : 3);
    }
    LoopRun run(s);
    run.frame(true);
    double first = run.loop.lastMotion();
    run.frame(true, false, 50, first - 1.0);
    EXPECT_EQ(run.loop.lastMotion(), first) << "an earlier motion applied later leaves the last motion where it was";
}

TEST(ViewFrameLoop, ExactQualityNeverPreviewsMotion) {
    FrameLoopSettings s;
    s.quality = ViewQuality::Exact;
    LoopRun run(s);
    for (int i = 0; i < 4; ++i) {
        FrameDecision d = run.frame(true);
        EXPECT_EQ(d.render, FrameKind::Exact);
        EXPECT_EQ(d.size, kWindow);
        EXPECT_EQ(d.exactBudgetMs, 0.0) << "exact quality renders the exact frame whole";
    }
    EXPECT_EQ(run.frame(false).render, FrameKind::None);
}

TEST(ViewFrameLoop, StepIRunsInSlicesWithAPreviewUntilItIsDone) {
    FrameLoopSettings s;
    s.precomputeBudgetMs = 40;
    for (ViewQuality quality : {ViewQuality::Adaptive, ViewQuality::Exact}) {
        s.quality = quality;
        LoopRun run(s);
        FrameDecision d = run.frame(false, true);
        EXPECT_EQ(d.precomputeBudgetMs, 40) << viewQualityName(quality);
        EXPECT_EQ(d.render, FrameKind::Preview) << "no exact frame before step I is done";
        EXPECT_EQ(d.size, run.loop.previewSize(kWindow)) << "at the preview resolution (a full frame would stall)";
        d = run.frame(false, true);
        EXPECT_EQ(d.precomputeBudgetMs, 40) << "the next slice";
        EXPECT_EQ(d.render, FrameKind::None) << "the same preview is still on screen";
        d = run.frame(true, true);
        EXPECT_EQ(d.render, FrameKind::Preview) << "moving during step I: a new preview";
        EXPECT_EQ(d.precomputeBudgetMs, 40);
        for (int i = 0; i < 5; ++i) run.frame(false, true);
        d = run.frame(false, false);
        EXPECT_EQ(d.precomputeBudgetMs, 0);
        EXPECT_EQ(d.render, FrameKind::Exact) << "step I done and still: the exact frame";
    }
}

// A TF drag in lao or cao changes step I's inputs every frame, and each change starts step I over: its slices
// wait until the edits have settled, and the drag gets previews alone.
TEST(ViewFrameLoop, StepIWaitsWhileItsInputsAreBeingEdited) {
    FrameLoopSettings s;
    s.precomputeBudgetMs = 40;
    LoopRun run(s);
    FrameDecision d = run.frame(false, true);
    EXPECT_EQ(d.precomputeBudgetMs, 40) << "the first frame's inputs are not an edit: step I starts at once";
    for (int i = 0; i < 8; ++i) {   // half a second of dragging: an edit every frame
        ++run.precomputeInputs;
        d = run.frame(true, true);
        EXPECT_EQ(d.precomputeBudgetMs, 0) << "frame " << i << " of the drag: no slice of a step I the next edit restarts";
        EXPECT_EQ(d.render, FrameKind::Preview) << "frame " << i;
        EXPECT_TRUE(d.inMotion);
    }
    // The drag stops: step I waits out the settle time (frames of 1/16 s: the first frame at or past it runs).
    int waited = 0;
    while ((d = run.frame(false, true)).precomputeBudgetMs == 0) ASSERT_LT(++waited, 10) << "step I never resumed";
    EXPECT_EQ(waited, static_cast<int>(std::ceil(s.settleSeconds / 0.0625)) - 1) << "it resumes once the inputs have been still for the settle time";
    EXPECT_EQ(d.precomputeBudgetMs, 40);
    // A camera motion alone (inputs unchanged) does not hold step I back.
    d = run.frame(true, true);
    EXPECT_EQ(d.precomputeBudgetMs, 40);
}

TEST(ViewFrameLoop, ThePreviewResolutionFollowsItsCostWithinItsBounds) {
    FrameLoopSettings s;
    s.previewTargetMs = 50;
    s.minPreviewScale = 0.2;
    s.maxPreviewScale = 0.5;
    LoopRun run(s);
    EXPECT_DOUBLE_EQ(run.loop.previewScale(), 0.2) << "the loop starts at the lower bound";
    for (int i = 0; i < 30; ++i) run.frame(true, false, 1);
    EXPECT_DOUBLE_EQ(run.loop.previewScale(), 0.5) << "cheap previews: the upper bound";
    // Previews cost 200 ms at scale 0.5 (4x the target): the scale that meets it is 0.25; the loop goes half the
    // way there (geometrically) each frame.
    double before = run.loop.previewScale();
    run.frame(true, false, 200);
    EXPECT_NEAR(run.loop.previewScale(), before * std::sqrt(0.5), 1e-12) << "half the step (in log scale) to 0.25";
    for (int i = 0; i < 30; ++i) run.frame(true, false, 200);
    EXPECT_NEAR(run.loop.previewScale(), 0.25, 1e-3) << "where 200 ms at 0.5 meets 50 ms";
    for (int i = 0; i < 30; ++i) run.frame(true, false, 2000);
    EXPECT_DOUBLE_EQ(run.loop.previewScale(), 0.2) << "the lower bound";
    for (int i = 0; i < 30; ++i) run.frame(true, false, 1);
    EXPECT_DOUBLE_EQ(run.loop.previewScale(), 0.5) << "the upper bound";
    // Exact frames and still previews (during step I) do not steer it.
    run.now += 1;
    run.screen.moved();   // what is on screen is no longer the frame (say, the TF changed and step I reruns)
    FrameDecision still = run.frame(false, true, 5000);
    ASSERT_EQ(still.render, FrameKind::Preview);
    ASSERT_FALSE(still.inMotion);
    EXPECT_DOUBLE_EQ(run.loop.previewScale(), 0.5);
    run.now += 1;
    FrameDecision exact = run.frame(false, false, 5000);
    ASSERT_EQ(exact.render, FrameKind::Exact);
    EXPECT_DOUBLE_EQ(run.loop.previewScale(), 0.5);
}

// An exact frame in slices writes the exact image slice by slice. When that image is what is on screen, or there
// is none yet (a scene's first frame), adaptive quality draws a preview first so the slices are never shown half
// done; exact quality renders whole and needs none; with a preview on screen the slices start at once.
TEST(ViewFrameLoop, APreviewComesFirstWhenTheExactFrameWouldBeDrawnOverTheScreen) {
    for (ViewQuality quality : {ViewQuality::Adaptive, ViewQuality::Exact}) {
        SCOPED_TRACE(viewQualityName(quality));
        FrameLoopSettings s;
        s.quality = quality;
        ViewFrameLoop loop(s);
        FrameLoopInputs in;
        in.now = 10;
        in.exactSize = kWindow;
        in.exactImageOnScreen = true;   // nothing on screen yet, or the last exact image
        FrameDecision d = loop.decide(in);
        EXPECT_EQ(d.render, quality == ViewQuality::Adaptive ? FrameKind::Preview : FrameKind::Exact);
        EXPECT_FALSE(d.inMotion);
        in.now = 11;
        in.exactImageOnScreen = false;   // the preview is on screen now
        d = loop.decide(in);
        EXPECT_EQ(d.render, FrameKind::Exact);
        EXPECT_EQ(d.exactBudgetMs > 0, quality == ViewQuality::Adaptive);
        // The exact frame is what is on screen: nothing to draw.
        in.now = 12;
        in.exactImageOnScreen = true;
        in.exactShown = true;
        EXPECT_EQ(loop.decide(in).render, FrameKind::None);
    }
}

TEST(ViewFrameLoop, QualityNamesAndDefaults) {
    EXPECT_EQ(parseViewQuality("exact"), ViewQuality::Exact);
    EXPECT_EQ(parseViewQuality("adaptive"), ViewQuality::Adaptive);
    EXPECT_EQ(parseViewQuality("fast"), std::nullopt);
    EXPECT_EQ(defaultViewQuality(true), ViewQuality::Adaptive) << "a software renderer";
    EXPECT_EQ(defaultViewQuality(false), ViewQuality::Exact) << "a hardware GPU";
}

}  // namespace
}  // namespace curette
