// Tubes expanded on the GPU (render/passes/gpu_tube_builder.h, shaders/tube_build.comp) against the CPU expansion of
// the same swept rings (expandTubeRings, the oracle): identical indices and colours, positions and normals
// within float rounding, over a few hundred curved streamlines, with and without caps, entries of different
// radius and side count appended, and batches forced small so most start at unaligned offsets; and the
// rendered frames of the two are the same picture.
#include "render/passes/gpu_tube_builder.h"

#include "base/error.h"
#include "render/renderer.h"
#include "tests/render/gl_test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace curette {
namespace {

using test::glContext;

// `count` smooth random curves (sums of sines) of 8-40 points, around the origin within about 20 mm.
Tractogram curves(std::size_t count, std::uint32_t seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::uniform_int_distribution<int> points(8, 40);
    Tractogram t;
    t.source = "curves";
    for (std::size_t s = 0; s < count; ++s) {
        glm::dvec3 start(10 * u(random), 10 * u(random), 10 * u(random)), a(u(random), u(random), u(random)),
            b(u(random), u(random), u(random)), c(u(random), u(random), u(random));
        int n = points(random);
        for (int i = 0; i < n; ++i) {
            double x = double(i) / (n - 1);
            t.points.emplace_back(glm::vec3(start + 20.0 * x * a + 3.0 * std::sin(3 * x + b.x) * b + 2.0 * std::cos(5 * x) * c));
        }
        t.offsets.push_back(static_cast<std::uint32_t>(t.points.size()));
    }
    return t;
}

struct Comparison {
    double positionMm = 0, direction = 0;
    bool sameIndices = false, sameColors = true;
};

Comparison compare(const TubeVertices& gpu, const TubeVertices& cpu) {
    Comparison c;
    EXPECT_EQ(gpu.positions.size(), cpu.positions.size());
    EXPECT_EQ(gpu.indices.size(), cpu.indices.size());
    if (gpu.positions.size() != cpu.positions.size()) return c;
    for (std::size_t i = 0; i < cpu.positions.size(); ++i) {
        c.positionMm = std::max(c.positionMm, double(glm::distance(gpu.positions[i], cpu.positions[i])));
        c.direction = std::max(c.direction, double(glm::distance(gpu.directions[i], cpu.directions[i])));
        c.sameColors = c.sameColors && gpu.colors[i] == cpu.colors[i];
    }
    c.sameIndices = gpu.indices == cpu.indices;
    return c;
}

TubeRings twoEntries() {
    TubeSettings thin;
    thin.radiusMm = 0.3;
    thin.sides = 5;
    thin.caps = false;
    TubeSettings thick;
    thick.radiusMm = 1.25;
    thick.sides = 12;
    thick.caps = true;
    thick.stepMm = 0.8;
    TubeRings rings = sweepTubeRings(curves(150, 3), thin);
    rings.append(sweepTubeRings(curves(150, 4), thick));
    return rings;
}

TEST(GpuTubes, ExpansionEqualsTheCpuExpansionOfTheSameRings) {
    glContext();
    TubeRings rings = twoEntries();
    ASSERT_EQ(rings.streamlines.size(), 300u);
    TubeVertices cpu = expandTubeRings(rings);
    for (std::size_t batchBytes : {defaultTubeBatchBytes, std::size_t(20000)}) {
        GpuTubeBuildStats stats;
        TubeSet gpu(buildTubeBuffersOnGpu(rings, &stats, batchBytes));
        if (batchBytes < defaultTubeBatchBytes) {
            EXPECT_GT(stats.batches, 50u) << "small batches were asked for";
        }
        Comparison c = compare(gpu.readBack(), cpu);
        EXPECT_TRUE(c.sameIndices) << "batch bytes " << batchBytes;
        EXPECT_TRUE(c.sameColors) << "batch bytes " << batchBytes;
        // Coordinates up to ~40 mm: a float's rounding there is 4e-6 mm; the shader adds a few roundings.
        EXPECT_LT(c.positionMm, 2e-5) << "batch bytes " << batchBytes;
        EXPECT_LT(c.direction, 1e-6) << "batch bytes " << batchBytes;
        // Every vertex of the GPU set lies in its box (the culling test relies on it).
        for (const glm::vec3& p : gpu.readBack().positions)
            for (int a = 0; a < 3; ++a) ASSERT_TRUE(p[a] >= gpu.boundsMin()[a] && p[a] <= gpu.boundsMax()[a]);
    }
}

TEST(GpuTubes, AStreamlineLargerThanABatchIsAClearError) {
    glContext();
    TubeRings rings = sweepTubeRings(curves(2, 5), TubeSettings{});
    try {
        buildTubeBuffersOnGpu(rings, nullptr, 256);
        FAIL() << "a 256-byte batch cannot hold a tube";
    } catch (const SystemError& e) {
        EXPECT_NE(std::string(e.what()).find("tube_rendering.build"), std::string::npos) << e.what();
    }
}

TEST(GpuTubes, TheRenderedFramesOfBothBuildsAgree) {
    VolumeData volume = test::makeVolume({24, 24, 24}, test::centredAffine({24, 24, 24}, glm::dvec3(2.0)), ScalarType::UInt8, test::blobField);
    TransferFunction tf = test::rampTransferFunction(40, 255, 0.05);
    Renderer renderer(glContext(), volume, tf);
    TubeRings rings = twoEntries();
    FrameDescription frame;
    frame.camera.fit(glm::dvec3(0), 30.0);
    frame.camera.azimuthDeg = 30;
    frame.camera.elevationDeg = 20;
    frame.size = {64, 64};
    for (ShadingMode mode : {ShadingMode::Phong, ShadingMode::Dos}) {
        frame.shading = mode;
        renderer.setTubes(expandTubeRings(rings), TubeShading{});
        renderer.render(frame);
        Image cpu = renderer.readImage();
        renderer.setTubeRings(rings, TubeShading{});
        renderer.render(frame);
        Image gpu = renderer.readImage();
        double worst = 0;
        std::size_t tubePixels = 0;
        std::vector<float> depth = renderer.gbuffer().readDepth();
        for (float d : depth) tubePixels += d > 0;
        for (std::size_t i = 0; i < cpu.pixels.size(); ++i)
            for (int ch = 0; ch < 4; ++ch) worst = std::max(worst, std::abs(double(cpu.pixels[i][ch]) - double(gpu.pixels[i][ch])));
        EXPECT_GT(tubePixels, 200u) << "the tubes must cover part of the image for the comparison to mean anything";
        // Vertices a few 1e-6 mm apart can move a rasterised edge by a pixel only where an edge passes within
        // that of a pixel centre: allow a level or two of 8-bit colour.
        EXPECT_LE(255.0 * worst, 2.0) << shadingModeName(mode);
    }
}

}  // namespace
}  // namespace curette
