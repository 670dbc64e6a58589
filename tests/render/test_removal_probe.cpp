// The GPU side of the removal report (render/passes/removal_probe.h) against its CPU oracle (plan/removal_field.h):
// the same sample pattern as step IV, the clip maps against the winding-number inside test.
#include "mesh/coverage.h"
#include "mesh/primitives.h"
#include "plan/removal_field.h"
#include "render/passes/removal_probe.h"
#include "render/renderer.h"
#include "tests/render/gl_test_support.h"

#include <gtest/gtest.h>

#include <glm/gtc/quaternion.hpp>

#include <cmath>
#include <random>

namespace curette {
namespace {

using test::glContext;

struct ProbeCase {
    const char* name;
    clip::TriangleMesh mesh;
    clip::RigidPose pose;
};

std::vector<ProbeCase> cases() {
    clip::RigidPose sphere{glm::dvec3(2.3, -1.7, 0.6), {}};
    clip::RigidPose box{glm::dvec3(-1.0, 2.0, 1.5), glm::angleAxis(glm::radians(30.0), glm::normalize(glm::dvec3(1, 2, 3)))};
    return {{"sphere", clip::makeSphere(9.0, 4), sphere}, {"rotated box", clip::makeBox(glm::dvec3(14, 10, 8)), box}};
}

TEST(RemovalProbe, TheGpuFieldMatchesItsCpuOracle) {
    for (const ProbeCase& c : cases()) {
        for (glm::dvec3 spacing : {glm::dvec3(1.0), glm::dvec3(0.8, 1.1, 1.4)}) {
            glm::ivec3 dims(36);
            VolumeData volume = test::makeVolume(dims, test::centredAffine(dims, spacing), ScalarType::UInt8, [](glm::dvec3) { return 100.0; });
            Renderer renderer(glContext(), volume, test::rampTransferFunction(0, 255, 0.5));
            auto geometry = std::make_shared<const clip::TriangleMesh>(c.mesh);
            renderer.clipMeshes().add(geometry, glm::dvec3(1.0), c.pose, c.name);
            RemovalProbe probe(renderer.geometry(), 32);
            plan::RemovalField gpu = probe.removalField(renderer.clipMeshes());
            gpu.validate();
            plan::InsideTest inside = plan::insideAnyMesh({plan::PosedMesh{geometry, c.pose, glm::dvec3(1.0)}});
            plan::RemovalField cpu = plan::removalFieldCpu(dims, volume.indexToWorld, gpu.origin, gpu.size, inside, clip::antiAliasingOffsets(32));
            ASSERT_EQ(cpu.insideSamples.size(), gpu.insideSamples.size());
            // The GPU answers from depth maps of 0.4-0.5 mm pixels (nearest pixel): samples within a pixel
            // diagonal of the surface may fall on either side, so counts may differ by a few samples there.
            double sumGpu = 0, sumCpu = 0;
            std::size_t differing = 0, removed = 0;  // voxels whose counts differ; voxels the CPU sees touched
            for (std::size_t i = 0; i < gpu.insideSamples.size(); ++i) {
                sumGpu += gpu.insideSamples[i];
                sumCpu += cpu.insideSamples[i];
                differing += gpu.insideSamples[i] != cpu.insideSamples[i];
                removed += cpu.insideSamples[i] > 0;
                ASSERT_LE(std::abs(int(gpu.insideSamples[i]) - int(cpu.insideSamples[i])), 8) << c.name << " voxel " << i;
            }
            ASSERT_GT(removed, 1000u);
            // Nearest-pixel lookups move the surface by up to half a map pixel, so the removed volumes may
            // differ by up to area * pixel / 2: a box whose faces happen to fall between pixel centres shows
            // a few per cent at this size; a sphere's offsets average out.
            double pixelMm = renderer.clipMeshes().camera(0).pixelMm();
            double bound = c.mesh.surfaceArea() * pixelMm / 2 / std::abs(c.mesh.signedVolume());
            EXPECT_NEAR(sumGpu / sumCpu, 1.0, bound) << c.name << ": removed volume GPU vs CPU";
            std::printf("[ removal ] %s spacing %.1f,%.1f,%.1f: %zu of %zu voxels differ, volume ratio %.5f\n", c.name, spacing.x,
                        spacing.y, spacing.z, differing, removed, sumGpu / sumCpu);
        }
    }
}

TEST(RemovalProbe, InsideFlagsMatchTheWindingNumberAwayFromTheSurface) {
    glm::ivec3 dims(32);
    VolumeData volume = test::makeVolume(dims, test::centredAffine(dims), ScalarType::UInt8, [](glm::dvec3) { return 100.0; });
    Renderer renderer(glContext(), volume, test::rampTransferFunction(0, 255, 0.5));
    std::vector<ProbeCase> list = cases();
    std::vector<plan::PosedMesh> posed;
    for (const ProbeCase& c : list) {
        auto geometry = std::make_shared<const clip::TriangleMesh>(c.mesh);
        renderer.clipMeshes().add(geometry, glm::dvec3(1.0), c.pose, c.name);
        posed.push_back({geometry, c.pose, glm::dvec3(1.0)});
    }
    std::mt19937 random(7);
    std::uniform_real_distribution<double> u(-15, 15);
    std::vector<glm::dvec3> points(20000);
    for (glm::dvec3& p : points) p = glm::dvec3(u(random), u(random), u(random));
    RemovalProbe probe(renderer.geometry(), 32);
    std::vector<std::uint8_t> flags = probe.insideFlags(renderer.clipMeshes(), points);
    plan::InsideTest inside = plan::insideAnyMesh(posed);
    int agree = 0, in = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        bool expected = inside(points[i]);
        // Near the surface the maps' nearest pixel may decide either way: the same rule renders the carve.
        bool nearSurface = false;
        for (glm::dvec3 d : {glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 1)})
            nearSurface = nearSurface || inside(points[i] + 0.75 * d) != expected || inside(points[i] - 0.75 * d) != expected;
        if (nearSurface) continue;
        ASSERT_EQ(flags[i] != 0, expected) << "point " << i;
        ++agree;
        in += expected;
    }
    EXPECT_GT(agree, 15000);
    EXPECT_GT(in, 1000);
}

}  // namespace
}  // namespace curette
