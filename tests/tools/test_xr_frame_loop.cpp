// The headset's frame-loop decisions (viewer/xr_frame_loop.h) on a fake clock: the head counts as moved only
// beyond its stillness bounds (a drift counts once it adds up), previews while something moves, then the exact
// frame in slices started once and kept through jitter, abandoned by a motion; held eyes when nothing is new;
// exact quality renders both eyes whole every frame.
#include "viewer/xr_frame_loop.h"

#include <gtest/gtest.h>

#include <glm/gtc/quaternion.hpp>

namespace curette {
namespace {

TrackedView headAt(double xMm, double turnDeg = 0.0) {
    TrackedView v;
    v.positionM = {xMm / 1000.0, 1.6, 0.0};
    v.orientation = glm::angleAxis(glm::radians(turnDeg), glm::dvec3(0, 1, 0));
    return v;
}

TEST(HeadMotion, JitterIsStillAndADriftCountsOnceItAddsUp) {
    HeadMotion m(HeadStillness{5.0, 1.0});
    EXPECT_FALSE(m.moved(headAt(0)));       // where measuring starts
    EXPECT_FALSE(m.moved(headAt(3)));
    EXPECT_FALSE(m.moved(headAt(-4)));
    EXPECT_FALSE(m.moved(headAt(0, 0.9)));
    EXPECT_TRUE(m.moved(headAt(0, 1.5)));    // turned past 1 degree
    EXPECT_FALSE(m.moved(headAt(4, 1.5)));   // measured from the last motion now
    EXPECT_TRUE(m.moved(headAt(6, 1.5)));    // 6 mm from it
    // A drift of 1 mm a frame counts every sixth frame, not every frame and not never.
    int counted = 0;
    for (int i = 1; i <= 30; ++i) counted += m.moved(headAt(6 + i, 1.5));
    EXPECT_EQ(counted, 5);
}

struct FakeHeadset {
    XrFrameLoop loop;
    double now = 0;
    explicit FakeHeadset(FrameLoopSettings s) : loop(s, HeadStillness{5.0, 1.0}) {}
    // One frame: its decision executed as tools/xr_loop.cpp does (a preview submitted; an exact frame done
    // after `slices` ExactSlice frames).
    int slicesDone = 0;
    int slices = 3;
    XrFrameDecision frame(bool sceneMoved, TrackedView head = headAt(0)) {
        XrFrameInputs in;
        in.now = now;
        in.sceneMoved = sceneMoved;
        in.head = head;
        in.recommendedSize = {100, 90};
        XrFrameDecision d = loop.decide(in);
        if (d.step == XrStep::Preview) loop.previewSubmitted(d, 10.0);
        if (d.step == XrStep::ExactSlice) {
            if (d.startExact) slicesDone = 0;
            if (++slicesDone == slices) loop.exactSubmitted();
        }
        now += 0.015625;   // 64 Hz: the clock's sums are exact in binary
        return d;
    }
};

FrameLoopSettings adaptive() {
    FrameLoopSettings s;
    s.quality = ViewQuality::Adaptive;
    s.settleSeconds = 0.0625;   // 4 frames
    s.minPreviewScale = s.maxPreviewScale = 0.5;   // unsteered: a preview of a state is drawn once
    return s;
}

TEST(XrFrameLoop, PreviewsWhileMovingThenTheExactFrameInSlicesThroughJitterThenHeldEyes) {
    FakeHeadset run(adaptive());
    EXPECT_EQ(run.frame(false).step, XrStep::Preview);   // nothing held yet: a preview first
    for (int i = 0; i < 3; ++i) {
        XrFrameDecision d = run.frame(true);
        EXPECT_EQ(d.step, XrStep::Preview) << i;
        EXPECT_TRUE(d.moved);
        EXPECT_LT(d.frame.size.x, 100);
    }
    // Within the settle time: the preview of this state is held.
    for (int i = 0; i < 3; ++i) EXPECT_EQ(run.frame(false).step, XrStep::Hold) << i;
    // Still: the exact frame, started once, its slices going on while the head jitters under the bounds.
    XrFrameDecision first = run.frame(false, headAt(2));
    EXPECT_EQ(first.step, XrStep::ExactSlice);
    EXPECT_TRUE(first.startExact);
    EXPECT_GT(first.frame.exactBudgetMs, 0);
    XrFrameDecision second = run.frame(false, headAt(-2, 0.5));
    EXPECT_EQ(second.step, XrStep::ExactSlice);
    EXPECT_FALSE(second.startExact);
    EXPECT_FALSE(second.moved);
    EXPECT_EQ(run.frame(false, headAt(1)).step, XrStep::ExactSlice);   // the third slice: submitted
    for (int i = 0; i < 5; ++i) EXPECT_EQ(run.frame(false, headAt(i % 2 ? 2 : -2)).step, XrStep::Hold) << i;
}

TEST(XrFrameLoop, AMotionAbandonsTheExactFrameAndTheNextStartsOver) {
    FakeHeadset run(adaptive());
    run.slices = 100;   // never done within this test
    run.frame(true);
    for (int i = 0; i < 4; ++i) run.frame(false);
    XrFrameDecision d = run.frame(false);
    ASSERT_EQ(d.step, XrStep::ExactSlice);
    EXPECT_FALSE(d.startExact);   // started the frame before
    EXPECT_EQ(run.frame(false, headAt(20)).step, XrStep::Preview);   // the head moved 2 cm: a motion
    XrFrameDecision again;
    for (int i = 0; i < 8 && again.step != XrStep::ExactSlice; ++i) again = run.frame(false, headAt(20));
    EXPECT_EQ(again.step, XrStep::ExactSlice);
    EXPECT_TRUE(again.startExact) << "the abandoned exact frame was continued";
}

TEST(XrFrameLoop, ExactQualityRendersBothEyesWholeEveryFrame) {
    FrameLoopSettings s = adaptive();
    s.quality = ViewQuality::Exact;
    FakeHeadset run(s);
    for (int i = 0; i < 6; ++i) EXPECT_EQ(run.frame(i % 2 == 0, headAt(10.0 * i)).step, XrStep::ExactWhole) << i;
}

}  // namespace
}  // namespace curette
