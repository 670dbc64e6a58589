// Meshes that need more than one depth interval from their own clipping camera (it looks along local +z,
// render/model/clipping_camera.h): the peeled second interval on the GPU, its count, the clipped region against the
// winding-number inside test, CAO == LAO on it, and a mesh with three intervals, whose third interval was
// left unclipped (a hole) before interval 2 was made to end at the farthest back face.
#include "mesh/primitives.h"
#include "plan/removal_field.h"
#include "render/passes/removal_probe.h"
#include "render/renderer.h"
#include "tests/render/gl_test_support.h"

#include <gtest/gtest.h>

#include <glm/gtc/quaternion.hpp>

#include <random>

namespace curette {
namespace {

using test::glContext;

// Slabs 14 x 14 mm across, stacked along local z: [z0, z1] each. One closed mesh of several shells.
clip::TriangleMesh stackedSlabs(const std::vector<glm::dvec2>& ranges) {
    clip::TriangleMesh out;
    out.source = "stacked slabs";
    for (glm::dvec2 r : ranges) {
        clip::TriangleMesh box = clip::makeBox(glm::dvec3(14, 14, r.y - r.x));
        auto first = static_cast<std::uint32_t>(out.positions.size());
        for (glm::vec3 p : box.positions) out.positions.push_back(p + glm::vec3(0, 0, float(0.5 * (r.x + r.y))));
        for (glm::uvec3 t : box.triangles) out.triangles.push_back(t + first);
    }
    return out;
}

struct IntervalScene {
    glm::ivec3 dims{40};
    VolumeData volume = test::makeVolume(dims, test::centredAffine(dims), ScalarType::UInt8, [](glm::dvec3 p) { return test::blobField(p); });
    Renderer renderer{glContext(), volume, test::rampTransferFunction(40, 255, 0.4)};
    std::shared_ptr<const clip::TriangleMesh> geometry;
    clip::RigidPose pose;
    IntervalScene(clip::TriangleMesh mesh, clip::RigidPose p) : geometry(std::make_shared<const clip::TriangleMesh>(std::move(mesh))), pose(p) {
        renderer.clipMeshes().add(geometry, glm::dvec3(1.0), pose, "intervals");
        renderer.clipMeshes().update();
    }
    // Whether the GPU clip test says each local point (in the mesh's frame) is inside.
    std::vector<bool> inside(const std::vector<glm::dvec3>& local) {
        std::vector<glm::dvec3> world;
        for (glm::dvec3 l : local) world.emplace_back(pose.matrix() * glm::dvec4(l, 1.0));
        RemovalProbe probe(renderer.geometry(), 8);
        std::vector<std::uint8_t> flags = probe.insideFlags(renderer.clipMeshes(), world);
        return {flags.begin(), flags.end()};
    }
};

const clip::RigidPose kTurned{glm::dvec3(1.3, -0.7, 0.4), glm::angleAxis(glm::radians(35.0), glm::normalize(glm::dvec3(1, -2, 1)))};

TEST(ClipIntervals, TwoShellsAlongTheCameraAreTwoIntervals) {
    IntervalScene scene(stackedSlabs({{-8, -3}, {2, 7}}), kTurned);
    EXPECT_EQ(scene.renderer.clipMeshes().intervals(0), 2);
    EXPECT_FALSE(scene.renderer.clipMeshes().deeperThanTwoIntervals(0));
    std::vector<bool> in = scene.inside({{0, 0, -5.5}, {0, 0, -0.5}, {0, 0, 4.5}, {0, 0, 9}, {3, -4, 5}, {3, -4, 0}});
    EXPECT_EQ(in, (std::vector<bool>{true, false, true, false, true, false})) << "slab 1, gap, slab 2, behind";
}

TEST(ClipIntervals, TheClippedRegionOfAConcaveMeshIsItsShapeAwayFromTheSurface) {
    // A torus turned in its own vertices, so its camera looks across the ring: two intervals where the view
    // crosses both arms.
    clip::TriangleMesh torus = clip::makeTorus(9, 3.5, 64, 24);
    glm::dmat3 turn = glm::mat3_cast(glm::angleAxis(glm::radians(90.0), glm::dvec3(1, 0, 0)));
    for (glm::vec3& p : torus.positions) p = glm::vec3(turn * glm::dvec3(p));
    IntervalScene scene(torus, kTurned);
    EXPECT_EQ(scene.renderer.clipMeshes().intervals(0), 2);
    plan::InsideTest exact = plan::insideAnyMesh({plan::PosedMesh{scene.geometry, clip::RigidPose{}, glm::dvec3(1.0)}});
    std::mt19937 random(3);
    std::uniform_real_distribution<double> u(-14, 14);
    std::vector<glm::dvec3> points;
    std::vector<bool> expected;
    for (int n = 0; n < 6000; ++n) {
        glm::dvec3 p(u(random), u(random), u(random));
        // Away from the surface by more than a map pixel diagonal (the maps' nearest-pixel lookup).
        bool e = exact(p), far = true;
        for (glm::dvec3 d : {glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 1)})
            far = far && exact(p + 0.8 * d) == e && exact(p - 0.8 * d) == e;
        if (!far) continue;
        points.push_back(p);
        expected.push_back(e);
    }
    std::vector<bool> got = scene.inside(points);
    int in = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        ASSERT_EQ(got[i], expected[i]) << "local point " << points[i].x << ", " << points[i].y << ", " << points[i].z;
        in += expected[i];
    }
    EXPECT_GT(in, 200);
    EXPECT_GT(points.size(), 3000u);
}

TEST(ClipIntervals, CaoEqualsFreshLaoOnATwoIntervalMesh) {
    clip::TriangleMesh shells = stackedSlabs({{-8, -3}, {2, 7}});
    auto geometry = std::make_shared<const clip::TriangleMesh>(shells);
    glm::ivec3 dims(36);
    VolumeData volume = test::makeVolume(dims, test::centredAffine(dims), ScalarType::UInt8, [](glm::dvec3 p) { return test::blobField(p); });
    TransferFunction tf = test::rampTransferFunction(40, 255, 0.4);
    LaoSettings lao;
    lao.samples = 6;
    FrameDescription frame;
    frame.camera.fit(glm::dvec3(0.0), 20.0);
    frame.size = {24, 24};
    auto ambientOf = [&](ShadingMode mode, const std::vector<clip::RigidPose>& poses) {
        Renderer renderer(glContext(), volume, tf);
        renderer.setLaoSettings(lao);
        renderer.clipMeshes().add(geometry, glm::dvec3(1.0), poses.front(), "shells");
        std::vector<std::uint16_t> ambient;
        for (const clip::RigidPose& p : poses) {
            renderer.clipMeshes().setPose(0, p);
            frame.shading = mode;
            renderer.render(frame);
        }
        EXPECT_EQ(renderer.clipMeshes().intervals(0), 2);
        return renderer.ambientOcclusion()->readAmbient();
    };
    std::vector<clip::RigidPose> poses{kTurned, {glm::dvec3(-2, 3, 1), glm::angleAxis(glm::radians(-50.0), glm::dvec3(0, 1, 0))}};
    // CAO follows the meshes through both poses; LAO recomputes the last one from scratch in a new renderer.
    EXPECT_EQ(ambientOf(ShadingMode::Cao, poses), ambientOf(ShadingMode::Lao, {poses.back()}));
}

TEST(ClipIntervals, AThirdIntervalIsClippedLikeTheHullInsteadOfLeftAHole) {
    IntervalScene scene(stackedSlabs({{-10, -7}, {-3, 0}, {4, 7}}), kTurned);
    EXPECT_EQ(scene.renderer.clipMeshes().intervals(0), 2);
    EXPECT_TRUE(scene.renderer.clipMeshes().deeperThanTwoIntervals(0));
    std::vector<bool> in = scene.inside({{0, 0, -8.5}, {0, 0, -5}, {0, 0, -1.5}, {0, 0, 2}, {0, 0, 5.5}, {0, 0, 9}, {-4, 5, 5.5}});
    // slab 1, the gap after it (kept), slab 2, the gap after it (clipped: the hull), slab 3, behind, slab 3.
    EXPECT_EQ(in, (std::vector<bool>{true, false, true, true, true, false, true}));
}

}  // namespace
}  // namespace curette
