// Where phong shades its visible samples in the ray cast (render/model/phong_shading_placement.h): the policy's
// arithmetic on known histograms, and the same image bit for bit from both places, with and without cut faces.
#include "mesh/primitives.h"
#include "render/model/phong_shading_placement.h"
#include "render/renderer.h"
#include "tests/render/gl_test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numeric>

namespace curette {
namespace {

using test::glContext;

// Opacity 0 up to 50, `plateau` from 100 up.
TransferFunction plateauTransferFunction(double plateau, double unitLengthMm = 1.0) {
    TransferFunction tf;
    tf.color = {{0, {0.2, 0.3, 0.6}}, {120, {0.9, 0.5, 0.3}}, {255, {1, 1, 0.9}}};
    tf.opacity = {{0, 0}, {50, 0}, {100, plateau}, {255, plateau}};
    tf.unitLengthMm = unitLengthMm;
    tf.material = {0.25, 0.7, 0.4, 24.0};
    return tf;
}

TEST(PhongShadingPlacement, TheMedianExtinctionIsTheVisibleVoxelsOwn) {
    // A quarter of the voxels 0 (transparent), three quarters 200 (on the plateau).
    glm::ivec3 dims(16, 16, 8);
    VolumeData volume = test::makeVolume(dims, test::centredAffine(dims), ScalarType::UInt8,
                                         [](glm::dvec3 p) { return p.x < -4 ? 0.0 : 200.0; });
    ValueHistogram all = ValueHistogram::of(volume, 256, volume.voxelCount());
    EXPECT_EQ(volume.voxelCount(), std::accumulate(all.counts.begin(), all.counts.end(), std::uint64_t{0}));
    EXPECT_EQ(volume.voxelCount() / 4, all.counts.front());
    EXPECT_EQ(volume.voxelCount() * 3 / 4, all.counts.back());
    // A stride through a larger volume: every 8th voxel.
    ValueHistogram strided = ValueHistogram::of(volume, 256, volume.voxelCount() / 8);
    EXPECT_EQ(volume.voxelCount() / 8, std::accumulate(strided.counts.begin(), strided.counts.end(), std::uint64_t{0}));

    EXPECT_NEAR(-std::log(0.7), medianVisibleExtinctionPerMm(all, plateauTransferFunction(0.3)), 1e-12);
    // Opacity per 2 mm: half the extinction per mm.
    EXPECT_NEAR(-std::log(0.7) / 2, medianVisibleExtinctionPerMm(all, plateauTransferFunction(0.3, 2.0)), 1e-12);
    EXPECT_EQ(0.0, medianVisibleExtinctionPerMm(all, plateauTransferFunction(0.0)));
}

TEST(PhongShadingPlacement, RoundsWhereARayEndsShortlyIntoTissueTheLoopWhereItCrossesTheVolume) {
    // A ray reaches 0.99 after -ln(0.01) / extinction mm: 19.5 mm at the head TF's median 0.236 per mm, 271 mm
    // at the glass TF's 0.017, against half of Colin27's 193 mm mean extent.
    EXPECT_EQ(PhongShading::BetweenRounds, phongShadingPlacement(0.236, 0.99, 193.0));
    EXPECT_EQ(PhongShading::InLoop, phongShadingPlacement(0.017, 0.99, 193.0));
    // At the boundary: -ln(0.01) / 0.1 = 46.05 mm, against halves of 92 and 93 mm.
    EXPECT_EQ(PhongShading::InLoop, phongShadingPlacement(0.1, 0.99, 92.0));
    EXPECT_EQ(PhongShading::BetweenRounds, phongShadingPlacement(0.1, 0.99, 93.0));
    // Nothing visible: no round ever stops.
    EXPECT_EQ(PhongShading::BetweenRounds, phongShadingPlacement(0.0, 0.99, 193.0));
}

FrameDescription phongFrame(bool cutFaces) {
    FrameDescription f = test::frameLookingAt(glm::dvec3(1, -2, 0), 110, 65, 35, {80, 72}, ShadingMode::Phong);
    f.raycast.jitterSeed = 5;
    f.raycast.cutFace.enabled = cutFaces;
    return f;
}

// Both places take the same samples in the same order: the image is the same bit for bit, for a glass-like and
// an opaque TF, without clip meshes and with a sphere carving the blobs with cut faces.
TEST(PhongShadingPlacement, BothPlacesGiveTheSameImage) {
    glContext();
    glm::ivec3 dims(48, 40, 36);
    VolumeData volume = test::makeVolume(dims, test::centredAffine(dims, {0.9, 1.1, 1.3}), ScalarType::UInt8, test::blobField);
    struct Case { const char* name; double plateau; PhongShading expected; };
    for (const Case& c : {Case{"glass", 0.02, PhongShading::InLoop}, Case{"opaque", 0.6, PhongShading::BetweenRounds}}) {
        for (bool carved : {false, true}) {
            SCOPED_TRACE(std::string(c.name) + (carved ? ", carved with cut faces" : ""));
            Renderer renderer(glContext(), volume, plateauTransferFunction(c.plateau));
            if (carved) {
                renderer.clipMeshes().add(std::make_shared<const clip::TriangleMesh>(clip::makeSphere(9.0)), glm::dvec3(1.0),
                                          clip::RigidPose{glm::dvec3(4, 6, 5), glm::dquat(1, 0, 0, 0)}, "sphere");
                renderer.clipMeshes().update();
            }
            FrameDescription frame = phongFrame(carved);
            EXPECT_EQ(c.expected, renderer.phongShading(frame));
            renderer.setPhongShading(PhongShading::InLoop);
            renderer.render(frame);
            Image inLoop = renderer.readImage();
            renderer.setPhongShading(PhongShading::BetweenRounds);
            renderer.render(frame);
            Image betweenRounds = renderer.readImage();
            double coverage = 0;
            for (const glm::vec4& p : inLoop.pixels) coverage += p.a > 0.05f ? 1.0 : 0.0;
            EXPECT_GT(coverage / static_cast<double>(inLoop.pixels.size()), 0.2) << "the blobs fill the view";
            EXPECT_EQ(0, std::memcmp(inLoop.pixels.data(), betweenRounds.pixels.data(), inLoop.pixels.size() * sizeof(glm::vec4)));
        }
    }
}

}  // namespace
}  // namespace curette
