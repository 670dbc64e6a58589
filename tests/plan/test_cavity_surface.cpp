// The cavity surface: closed and outward on random fields (several seeds, mirrored affines too) and on a
// sphere, whose enclosed volume is within 3 % of 4/3 pi r^3 at r = 10 voxels (measured -1.9 %: the 0.5 level of
// the removed fraction, a coverage of two-voxel boxes, lies slightly inside a convex surface).
#include "mesh/coverage.h"
#include "plan/cavity_surface.h"
#include "plan_test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace curette::plan {
namespace {

using namespace testing;

TEST(CavitySurface, ClosedOnRandomFields) {
    for (unsigned seed = 1; seed <= 20; ++seed) {
        std::mt19937 random(seed);
        VoxelBox box{{int(random() % 5), int(random() % 5), int(random() % 5)},
                     {int(random() % 7) + 1, int(random() % 7) + 1, int(random() % 7) + 1}};
        std::uniform_real_distribution<double> uniform(0.0, 1.0);
        std::vector<double> values(box.voxelCount());
        // Values on a coarse set of levels so many hit the iso value exactly (the degenerate case).
        for (double& v : values) v = seed % 2 ? uniform(random) : std::floor(uniform(random) * 4.0) / 2.0;
        glm::dmat4 affine = gridAffine({0.7, 1.1, 1.3}, box.origin + box.size);
        if (seed % 3 == 0) affine[0] = -affine[0];  // a mirroring affine (det < 0): still outward
        clip::TriangleMesh mesh = isoSurfaceTetrahedra(box, values, affine, 0.5);
        bool anyInside = std::any_of(values.begin(), values.end(), [](double v) { return v >= 0.5; });
        if (!anyInside) {
            EXPECT_TRUE(mesh.triangles.empty());
            continue;
        }
        EXPECT_NO_THROW(clip::validateClosed(mesh)) << "seed " << seed;
        EXPECT_GT(mesh.signedVolume(), 0.0) << "seed " << seed << " faces outward";
    }
}

TEST(CavitySurface, OfASphereFieldEnclosesTheSphere) {
    const double r = 10.0;
    glm::ivec3 dims(27, 27, 27);
    glm::dmat4 affine = gridAffine(glm::dvec3(1.0), dims);
    RemovalField field = removalFieldCpu(dims, affine, glm::ivec3(0), dims, sphere({0.3, -0.2, 0.1}, r), clip::antiAliasingOffsets(32));
    clip::TriangleMesh mesh = cavitySurface(field, {});
    ASSERT_NO_THROW(clip::validateClosed(mesh));
    const double exact = 4.0 / 3.0 * kPi * r * r * r;
    EXPECT_NEAR(mesh.signedVolume(), exact, 0.03 * exact);
    RecordProperty("sphere_volume_relative_error", std::to_string(mesh.signedVolume() / exact - 1.0));
    // No tissue: no surface. Tissue in half the box: a closed surface around the half ball.
    std::vector<std::uint8_t> none(field.box().voxelCount(), 0), half(field.box().voxelCount(), 0);
    EXPECT_TRUE(cavitySurface(field, none).triangles.empty());
    for (std::size_t i = 0; i < half.size(); ++i) half[i] = int(i % std::size_t(dims.x)) < dims.x / 2 ? 1 : 0;
    clip::TriangleMesh halfMesh = cavitySurface(field, half);
    EXPECT_NO_THROW(clip::validateClosed(halfMesh));
    // The tissue ends between the voxel centres at x = -1 and x = 0 (f drops from ~1 to 0): the iso surface cuts
    // at x = -0.5, 0.8 mm short of the sphere's centre, leaving half the ball less a slab of pi (r^2 h - h^3 / 3).
    const double h = 0.8, expectedHalf = exact / 2 - kPi * (r * r * h - h * h * h / 3);
    EXPECT_NEAR(halfMesh.signedVolume(), expectedHalf, 0.045 * expectedHalf);  // measured -3.2 %
}

}  // namespace
}  // namespace curette::plan
