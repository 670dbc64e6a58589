// VolumeLayout (render/model/volume_layout.h): which voxels every texel of a folded volume holds. GL-free.
#include "render/model/volume_layout.h"

#include "base/error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

namespace curette {
namespace {

TEST(VolumeLayout, AVolumeThatFitsIsStoredAsItIs) {
    VolumeLayout l = VolumeLayout::forLimit({24, 20, 64}, 64, "v.nii");
    EXPECT_FALSE(l.folded());
    EXPECT_EQ(l.texels, glm::ivec3(24, 20, 64));
    EXPECT_EQ(l.texel({3, 4, 63}), glm::ivec3(3, 4, 63));
    EXPECT_FALSE(l.hasTwin({3, 4, 32}));
}

TEST(VolumeLayout, TheLongAxisFoldsAlongTheShortestOtherAxis) {
    VolumeLayout l = VolumeLayout::forLimit({24, 20, 70}, 64, "v.nii");
    ASSERT_TRUE(l.folded());
    EXPECT_EQ(l.foldAxis, 2);
    EXPECT_EQ(l.acrossAxis, 1);
    EXPECT_EQ(l.pieces, 2);
    EXPECT_EQ(l.stride, 35);
    EXPECT_EQ(l.texels, glm::ivec3(24, 41, 36));   // 2 x 20 + 1 zero texel across; 35 + 1 long
    // The llvmpipe limit: 512 x 512 x 2100 folds into 2 pieces of 1051 slices.
    VolumeLayout ct = VolumeLayout::forLimit({512, 512, 2100}, 2048, "ct.nii");
    EXPECT_EQ(ct.pieces, 2);
    EXPECT_EQ(ct.texels, glm::ivec3(1025, 512, 1051));   // x and y tie: across x
    for (int axis = 0; axis < 3; ++axis) EXPECT_LE(ct.texels[axis], 2048);
}

TEST(VolumeLayout, EveryVoxelHasItsOwnTexelAndTheCutVoxelsTwo) {
    for (glm::ivec3 dims : {glm::ivec3(5, 3, 40), glm::ivec3(17, 2, 2), glm::ivec3(3, 47, 6), glm::ivec3(2, 2, 60)}) {
        VolumeLayout l = VolumeLayout::forLimit(dims, 16, "v.nii");
        ASSERT_TRUE(l.folded());
        for (int axis = 0; axis < 3; ++axis) EXPECT_LE(l.texels[axis], 16);
        std::vector<int> owner(l.texelCount(), -1);
        auto at = [&](glm::ivec3 t) {
            for (int axis = 0; axis < 3; ++axis) {
                EXPECT_GE(t[axis], 0);
                EXPECT_LT(t[axis], l.texels[axis]);
            }
            return (std::size_t(t.z) * std::size_t(l.texels.y) + std::size_t(t.y)) * std::size_t(l.texels.x) + std::size_t(t.x);
        };
        int id = 0, twins = 0;
        for (int z = 0; z < dims.z; ++z)
            for (int y = 0; y < dims.y; ++y)
                for (int x = 0; x < dims.x; ++x, ++id) {
                    glm::ivec3 v(x, y, z);
                    EXPECT_EQ(owner[at(l.texel(v))], -1);
                    owner[at(l.texel(v))] = id;
                    if (l.hasTwin(v)) {
                        EXPECT_EQ(owner[at(l.twinTexel(v))], -1);
                        owner[at(l.twinTexel(v))] = id;
                        // the twin is the previous piece's last texel along the fold axis
                        EXPECT_EQ(l.twinTexel(v)[l.foldAxis], l.stride);
                        ++twins;
                    }
                }
        int cuts = l.pieces - 1;
        EXPECT_EQ(twins, cuts * dims[(l.foldAxis + 1) % 3] * dims[(l.foldAxis + 2) % 3]);
        // Within a piece, voxels next to each other along every axis are texels next to each other: trilinear
        // filtering between two voxel centres of one piece never reads another piece.
        for (int p = 0; p < l.pieces; ++p)
            for (int i = l.pieceFirst(p); i < l.pieceLast(p); ++i) {
                glm::ivec3 v(0);
                v[l.foldAxis] = i;
                glm::ivec3 w = v;
                w[l.foldAxis] = i + 1;
                EXPECT_EQ(l.texelIn(w, p) - l.texelIn(v, p), glm::ivec3(l.foldAxis == 0, l.foldAxis == 1, l.foldAxis == 2));
            }
    }
}

TEST(VolumeLayout, FoldAndUnfoldRoundTrip) {
    VolumeLayout l = VolumeLayout::forLimit({4, 7, 40}, 16, "v.nii");
    ASSERT_TRUE(l.folded());
    std::vector<int> voxels(l.voxelCount());
    std::iota(voxels.begin(), voxels.end(), 1);
    std::vector<int> texels = l.fold(voxels, 0);
    EXPECT_EQ(texels.size(), l.texelCount());
    EXPECT_EQ(l.unfold(texels), voxels);
    // The texels no voxel owns hold the fill: the gaps between pieces and the last piece's tail.
    std::size_t stored = l.voxelCount() + std::size_t(l.pieces - 1) * 4 * 7;
    EXPECT_EQ(std::size_t(std::count(texels.begin(), texels.end(), 0)), l.texelCount() - stored);
}

TEST(VolumeLayout, AVolumeThatCannotFoldIsAnInputError) {
    EXPECT_THROW(VolumeLayout::forLimit({40, 40, 4}, 16, "v.nii"), InputError);     // two axes over
    EXPECT_THROW(VolumeLayout::forLimit({12, 12, 200}, 16, "v.nii"), InputError);   // no room across
    EXPECT_THROW(VolumeLayout::forLimit({0, 4, 4}, 16, "v.nii"), InputError);
    try {
        VolumeLayout::forLimit({12, 12, 200}, 16, "v.nii");
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("v.nii"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("GL_MAX_3D_TEXTURE_SIZE 16"), std::string::npos);
    }
}

}  // namespace
}  // namespace curette
