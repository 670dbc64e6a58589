// Step V's recompute list in chunks of visited bricks (AmbientOcclusion: the list holds one chunk's voxels, not
// the volume's): with chunks forced small (CURETTE_RECOMPUTE_LIST_BRICKS), V_AO and the image equal those of the
// one-chunk list bit for bit, rendered whole and in slices, over mesh moves; and the list's memory shrinks.
#include "tests/render/moving_sphere_scene.h"

#include <gtest/gtest.h>

#include <cstdlib>

namespace curette {
namespace {

using test::MovingSphereScene;
using test::sameImage;

struct ForcedChunkBricks {
    explicit ForcedChunkBricks(int bricks) { setenv("CURETTE_RECOMPUTE_LIST_BRICKS", std::to_string(bricks).c_str(), 1); }
    ~ForcedChunkBricks() { unsetenv("CURETTE_RECOMPUTE_LIST_BRICKS"); }
};

std::size_t listBytes(const Renderer& r) {
    for (const GpuAllocation& a : r.gpuAllocations())
        if (a.resource == Resource::RecomputeList) return a.bytes;
    return 0;
}

TEST(RecomputeChunks, ChunkedListsGiveTheOneListsAmbientAndImageWholeAndInSlices) {
    // The AO volumes and the list are allocated at the first frame that needs them: the forced chunk size
    // applies to the renderers whose first lao/cao frame runs while it is set.
    MovingSphereScene one, chunked, sliced;
    one.renderer->render(one.frame);
    {
        ForcedChunkBricks force(40);   // 45 x 39 x 42 voxels: 12 x 10 x 11 = 1320 bricks, 33 chunks for step I
        chunked.renderer->render(chunked.frame);
        sliced.renderer->render(sliced.frame);   // step I whole
    }
    EXPECT_LT(listBytes(*chunked.renderer), listBytes(*one.renderer) / 10) << "the list holds one chunk";
    for (int pose = 0; pose < 5 && !HasFailure(); ++pose) {
        if (pose > 0) {
            for (MovingSphereScene* s : {&one, &chunked, &sliced}) s->moveTo(pose);
            one.renderer->render(one.frame);
            chunked.renderer->render(chunked.frame);
            int calls = 0;
            while (!sliced.renderer->advanceExact(sliced.frame, 0.0, 3)) ASSERT_LT(++calls, 100000);
            EXPECT_GT(calls, 10);
        }
        EXPECT_EQ(chunked.ambient(), one.ambient()) << "pose " << pose;
        EXPECT_EQ(sliced.ambient(), one.ambient()) << "pose " << pose;
        EXPECT_TRUE(sameImage(chunked.renderer->readImage(), one.renderer->readImage())) << "pose " << pose;
        EXPECT_TRUE(sameImage(sliced.renderer->readImage(), one.renderer->readImage())) << "pose " << pose;
        EXPECT_EQ(chunked.renderer->ambientOcclusion()->lastStats().recomputed, one.renderer->ambientOcclusion()->lastStats().recomputed);
    }
    // A first exact frame (every brick visited, after step I) in slices spans every chunk.
    MovingSphereScene fresh, freshSliced;
    fresh.renderer->render(fresh.frame);
    ForcedChunkBricks force(40);
    int calls = 0;
    while (!freshSliced.renderer->advanceExact(freshSliced.frame, 0.0, 50)) ASSERT_LT(++calls, 100000);
    EXPECT_LT(listBytes(*freshSliced.renderer), listBytes(*fresh.renderer) / 10);
    EXPECT_EQ(freshSliced.ambient(), fresh.ambient());
    EXPECT_TRUE(sameImage(freshSliced.renderer->readImage(), fresh.renderer->readImage()));
}

}  // namespace
}  // namespace curette
