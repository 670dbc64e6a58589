// The bricks steps IV and V visit (render/mesh_voxel_box.h) against a brute-force check of every voxel, on
// an oblique anisotropic grid with turned meshes, where the axis-aligned box around the map boxes is several
// times larger; and the brick set's bookkeeping.
#include "mesh/primitives.h"
#include "gl/bindings.h"
#include "render/mesh_voxel_box.h"
#include "render/renderer.h"
#include "tests/render/gl_test_support.h"

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

namespace curette {
namespace {

using test::glContext;

// A uniform volume on an oblique, anisotropic grid: its cells lie turned against every map and box.
VolumeData obliqueVolume(glm::ivec3 dims) {
    glm::dmat4 turn = glm::mat4_cast(glm::angleAxis(glm::radians(25.0), glm::normalize(glm::dvec3(2.0, -1.0, 3.0))));
    glm::dmat4 affine = turn * test::centredAffine(dims, glm::dvec3(0.8, 1.0, 1.3));
    return test::makeVolume(dims, affine, ScalarType::UInt8, [](glm::dvec3) { return 100.0; });
}

// Within `spread` mm of the origin along every axis, turned about a random axis.
clip::RigidPose randomTurnedPose(std::mt19937& random, double spread) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    glm::dvec3 axis = glm::normalize(glm::dvec3(u(random), u(random), u(random)) + glm::dvec3(1e-9));
    glm::dvec3 position = spread * glm::dvec3(u(random), u(random), u(random));
    return {position, glm::angleAxis(3.14159 * u(random), axis)};
}

void drawMaps(clip::ClipMeshSet& set, double dilationMm) {
    set.setDilationRadiusMm(dilationMm);
    set.setDilatedMapsNeeded(true);
    set.update();
}

// An oblique grid's renderer, a thin rod and a small ball: placed by rounds, the rod alone, then with the ball,
// at random poses, with the maps drawn.
struct RodAndBallGrid {
    glm::ivec3 dims{48, 44, 40};
    VolumeData volume = obliqueVolume(dims);
    Renderer renderer{glContext(), volume, test::rampTransferFunction(0, 255, 0.5)};
    std::shared_ptr<const clip::TriangleMesh> rod = std::make_shared<const clip::TriangleMesh>(clip::makeCylinder(2.5, 30.0, 24));
    std::shared_ptr<const clip::TriangleMesh> ball = std::make_shared<const clip::TriangleMesh>(clip::makeSphere(5.0, 2));

    void place(int round, std::mt19937& random, double dilationMm) {
        clip::ClipMeshSet& set = renderer.clipMeshes();
        set.clear();
        for (int m = 0; m < 1 + round % 2; ++m)
            set.add(m == 0 ? rod : ball, glm::dvec3(1.0), randomTurnedPose(random, 16.0), m == 0 ? "rod" : "ball");
        drawMaps(set, dilationMm);
    }
};

// Distance from world point p to mesh i's dilated box (clip::ClipMeshSet::dilatedBoxLocal) in the mesh's
// (rigid) frame, in double.
double distanceToDilatedBox(const clip::ClipMeshSet& set, int i, glm::dvec3 p) {
    glm::dvec3 lo, hi;
    set.dilatedBoxLocal(i, lo, hi);
    glm::dvec3 q(set.pose(i).inverseMatrix() * glm::dvec4(p, 1.0));
    return glm::length(glm::max(glm::max(lo - q, q - hi), glm::dvec3(0.0)));
}

// The clip probe (clip_probe.comp) at `points`: bit 0 inside a mesh, bit 1 inside a dilated shape.
std::vector<std::uint32_t> probe(const clip::ClipMeshSet& set, const std::vector<glm::vec4>& points) {
    gl::Buffer in = gl::createBuffer(), out = gl::createBuffer();
    glNamedBufferStorage(in.name(), static_cast<GLsizeiptr>(points.size() * sizeof(glm::vec4)), points.data(), 0);
    glNamedBufferStorage(out.name(), static_cast<GLsizeiptr>(points.size() * 4), nullptr, GL_DYNAMIC_STORAGE_BIT);
    static gl::Program program = gl::Program::compute("clip_probe.comp");
    set.apply(program);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding::ssboProbePoints, in.name());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding::ssboProbeResults, out.name());
    program.set("pointCount", static_cast<unsigned>(points.size()));
    program.dispatchCovering(glm::uvec3(static_cast<unsigned>(points.size()), 1, 1));
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<std::uint32_t> results(points.size());
    glGetNamedBufferSubData(out.name(), 0, static_cast<GLsizeiptr>(results.size() * 4), results.data());
    return results;
}

// Distance from world point p to mesh i's reach ball (clip::ClipMeshSet::reachBallLocal).
double distanceToReachBall(const clip::ClipMeshSet& set, int i, glm::dvec3 p) {
    clip::ClipMeshSet::Ball ball = set.reachBallLocal(i);
    glm::dvec3 centre(set.pose(i).matrix() * glm::dvec4(ball.centre, 1.0));
    return std::max(glm::length(p - centre) - ball.radius, 0.0);
}

// Conservative: every voxel whose V_o or LAO a mesh can change lies in a visited brick, by the GPU's own maps:
// one of its nine clip samples (clip_coverage.glsl) inside a mesh, or its centre within R (the dilation radius)
// of a voxel centre the maps call inside. Tight: every visited brick holds a voxel centre within a cell
// diagonal of a dilated box, and near that mesh's reach ball. On an oblique, anisotropic grid with turned
// meshes, the bricks hold far fewer voxels than the axis-aligned box, and fewer than the dilated boxes'.
TEST(VisitBricks, HoldEveryVoxelTheMapsCanTouchAndLittleElse) {
    RodAndBallGrid scene;
    const glm::ivec3 dims = scene.dims;
    const VolumeGeometry& g = scene.renderer.geometry();
    clip::ClipMeshSet& set = scene.renderer.clipMeshes();
    const double reachMm = 4.0;
    // The brick's circumradius: half the diagonal of its voxel centres' parallelepiped.
    const double brickCircumradius = 0.5 * (kVisitBrickSize - 1) * g.cellDiagonalMm();
    std::mt19937 random(7);
    std::uint64_t visitedVoxels = 0, boxVoxels = 0, dilatedBoxVoxels = 0, touched = 0, reached = 0;
    for (int round = 0; round < 10; ++round) {
        scene.place(round, random, reachMm);
        BrickSet bricks = bricksAroundMeshes(g, set);
        visitedVoxels += bricks.visitedVoxels();
        boxVoxels += voxelBoxAroundMeshes(g, set).voxelCount();
        std::vector<glm::vec4> points;
        std::vector<glm::ivec3> voxels;
        std::vector<double> brickNearest(bricks.brickCount(), 1e300), brickNearestBall(bricks.brickCount(), 1e300);
        for (int k = 0; k < dims.z; ++k)
            for (int j = 0; j < dims.y; ++j)
                for (int i = 0; i < dims.x; ++i) {
                    glm::dvec3 p(g.indexToWorld * glm::dvec4(i, j, k, 1.0));
                    double nearest = 1e300, nearestBall = 1e300;
                    for (int m = 0; m < set.count(); ++m) {
                        double box = distanceToDilatedBox(set, m, p);
                        nearest = std::min(nearest, box);
                        if (box <= g.cellDiagonalMm()) nearestBall = std::min(nearestBall, distanceToReachBall(set, m, p));
                    }
                    dilatedBoxVoxels += nearest == 0.0;
                    glm::ivec3 b = glm::ivec3(i, j, k) / kVisitBrickSize;
                    std::size_t brick = std::size_t(b.x) + std::size_t(bricks.grid.x) * (std::size_t(b.y) + std::size_t(bricks.grid.y) * std::size_t(b.z));
                    brickNearest[brick] = std::min(brickNearest[brick], nearest);
                    brickNearestBall[brick] = std::min(brickNearestBall[brick], nearestBall);
                    // The voxel centre and its eight corner samples, as step IV takes them.
                    for (int c = 0; c < 9; ++c) {
                        glm::dvec3 offset = c == 0 ? glm::dvec3(0.0) : glm::dvec3((c - 1) & 1 ? 1 : -1, (c - 1) & 2 ? 1 : -1, (c - 1) & 4 ? 1 : -1);
                        points.emplace_back(glm::vec3(g.indexToWorld * glm::dvec4(glm::dvec3(i, j, k) + offset, 1.0)), 0.0f);
                        voxels.push_back({i, j, k});
                    }
                }
        std::vector<std::uint32_t> results = probe(set, points);
        std::uint64_t touchedOutside = 0, reachedOutside = 0;
        std::vector<glm::ivec3> inside;
        for (std::size_t p = 0; p < points.size(); ++p) {
            if (!(results[p] & 1u)) continue;
            ++touched;
            touchedOutside += !bricks.visits(voxels[p]);
            if (p % 9 == 0) inside.push_back(voxels[p]);
        }
        // Every voxel centre within R of a centre the maps call inside.
        glm::dvec3 spacing(glm::length(glm::dvec3(g.indexToWorld[0])), glm::length(glm::dvec3(g.indexToWorld[1])),
                           glm::length(glm::dvec3(g.indexToWorld[2])));
        glm::ivec3 around(glm::ceil(reachMm / spacing));
        std::vector<std::uint8_t> withinReach(std::size_t(dims.x) * std::size_t(dims.y) * std::size_t(dims.z), 0);
        for (glm::ivec3 v : inside) {
            glm::dvec3 from(g.indexToWorld * glm::dvec4(glm::dvec3(v), 1.0));
            glm::ivec3 lo = glm::max(v - around, glm::ivec3(0)), hi = glm::min(v + around, dims - 1);
            for (int k = lo.z; k <= hi.z; ++k)
                for (int j = lo.y; j <= hi.y; ++j)
                    for (int i = lo.x; i <= hi.x; ++i) {
                        std::size_t n = std::size_t(i) + std::size_t(dims.x) * (std::size_t(j) + std::size_t(dims.y) * std::size_t(k));
                        if (withinReach[n] || glm::length(glm::dvec3(g.indexToWorld * glm::dvec4(i, j, k, 1.0)) - from) > reachMm) continue;
                        withinReach[n] = 1;
                        ++reached;
                        reachedOutside += !bricks.visits({i, j, k});
                    }
        }
        ASSERT_EQ(touchedOutside, 0u) << "round " << round << ": the maps touch voxels whose bricks are not visited";
        ASSERT_EQ(reachedOutside, 0u) << "round " << round << ": voxels within R of a clipped point whose bricks are not visited";
        for (std::size_t b = 0; b < bricks.brickCount(); ++b)
            if (bricks.visited[b]) {
                ASSERT_LE(brickNearest[b], g.cellDiagonalMm()) << "round " << round << ": brick " << b << " is visited but no voxel centre in it is near a dilated box";
                ASSERT_LE(brickNearestBall[b], brickCircumradius + g.cellDiagonalMm())
                    << "round " << round << ": brick " << b << " is visited but no voxel centre in it is near its mesh's reach ball";
            }
    }
    std::printf("[ visit bricks ] turned meshes: %llu voxel touches and %llu voxels within reach checked; bricks hold %.1f%% of the voxels of the "
                "axis-aligned boxes, %.1f%% of those of the dilated boxes\n",
                static_cast<unsigned long long>(touched), static_cast<unsigned long long>(reached), 100.0 * double(visitedVoxels) / double(boxVoxels),
                100.0 * double(visitedVoxels) / double(dilatedBoxVoxels));
    EXPECT_GT(touched, 10000u);
    EXPECT_GT(reached, 10000u);
    EXPECT_LT(visitedVoxels, boxVoxels / 2) << "turned meshes: the oriented boxes' bricks must hold well under the axis-aligned box";
}

// Distance from world point p to mesh i's depth box (clip::ClipMeshSet::depthBoxLocal), and how far p lies
// outside its depth ball, in double: step IV tests a voxel's samples against mesh i only where both are within
// the sample reach of the centre (clip_test.glsl nearDepthBox).
bool nearDepthBoxAndBall(const clip::ClipMeshSet& set, int i, glm::dvec3 p, double reach) {
    glm::dvec3 lo, hi;
    set.depthBoxLocal(i, lo, hi);
    glm::dvec3 q(set.pose(i).inverseMatrix() * glm::dvec4(p, 1.0));
    clip::ClipMeshSet::Ball ball = set.depthBallLocal(i);
    return glm::length(glm::max(glm::max(lo - q, q - hi), glm::dvec3(0.0))) <= reach && glm::length(q - ball.centre) <= ball.radius + reach;
}

// Step IV compiles the clip-sample test out of the bricks beyond every mesh's sample reach
// (bricksWithinSampleReach). Conservative: every voxel whose centre nearDepthBox admits for some mesh, and every
// voxel one of whose nine clip samples the GPU's maps call inside, lies in a brick within reach. Tight: those
// bricks are a small part of the visited ones. Off with the depth-box tests (every voxel near a mesh is tested).
TEST(VisitBricks, SampleReachBricksHoldEveryVoxelWhoseSamplesAreTested) {
    RodAndBallGrid scene;
    const glm::ivec3 dims = scene.dims;
    const VolumeGeometry& g = scene.renderer.geometry();
    clip::ClipMeshSet& set = scene.renderer.clipMeshes();
    const double reach = clipSampleReachMm(g);
    std::mt19937 random(11);
    std::uint64_t nearVoxels = 0, insideVoxels = 0, withinBricks = 0, aroundBricks = 0;
    for (int round = 0; round < 8; ++round) {
        scene.place(round, random, 4.0);
        BrickSet within = bricksWithinSampleReach(g, set);
        withinBricks += within.visitedCount();
        aroundBricks += bricksAroundMeshes(g, set).visitedCount();
        std::vector<glm::vec4> points;
        std::vector<glm::ivec3> voxels;
        for (int k = 0; k < dims.z; ++k)
            for (int j = 0; j < dims.y; ++j)
                for (int i = 0; i < dims.x; ++i) {
                    glm::dvec3 p(g.indexToWorld * glm::dvec4(i, j, k, 1.0));
                    bool near = false;
                    for (int m = 0; m < set.count(); ++m) near = near || nearDepthBoxAndBall(set, m, p, reach);
                    nearVoxels += near;
                    if (near) EXPECT_TRUE(within.visits({i, j, k})) << "voxel " << i << " " << j << " " << k << " round " << round;
                    for (int c = 0; c < 9; ++c) {
                        glm::dvec3 offset = c == 0 ? glm::dvec3(0.0)
                                                   : clip::kCellSampleHalfWidth *
                                                         glm::dvec3((c - 1) & 1 ? 1 : -1, (c - 1) & 2 ? 1 : -1, (c - 1) & 4 ? 1 : -1);
                        points.emplace_back(glm::vec3(g.indexToWorld * glm::dvec4(glm::dvec3(i, j, k) + offset, 1.0)), 0.0f);
                        voxels.push_back({i, j, k});
                    }
                }
        std::vector<std::uint32_t> results = probe(set, points);
        for (std::size_t p = 0; p < points.size(); ++p) {
            if (!(results[p] & 1u)) continue;
            ++insideVoxels;
            EXPECT_TRUE(within.visits(voxels[p])) << "a clip sample inside, round " << round;
        }
        set.setDepthBoxTests(false);
        EXPECT_EQ(bricksWithinSampleReach(g, set).visitedCount(), within.brickCount());
        set.setDepthBoxTests(true);
    }
    std::printf("voxels near a depth box %llu, clip samples inside %llu; bricks within sample reach %llu of %llu visited\n",
                static_cast<unsigned long long>(nearVoxels), static_cast<unsigned long long>(insideVoxels),
                static_cast<unsigned long long>(withinBricks), static_cast<unsigned long long>(aroundBricks));
    EXPECT_GT(insideVoxels, 1000u);
    EXPECT_LT(withinBricks * 4, aroundBricks * 3);
}

// Step IV takes the count of the bricks deep inside a mesh as 9 + N without a test (bricksDeepInsideMeshes).
// Sound: every clip sample of every voxel in them, the nine and the N anti-aliasing ones, is inside by the GPU's
// maps. Useful: most bricks whose voxels' samples are all inside are found. Turned meshes on an oblique,
// anisotropic grid, a torus among them (two intervals); none with the depth-box tests off.
TEST(VisitBricks, DeepBricksHaveEveryClipSampleInside) {
    glContext();
    glm::ivec3 dims(56, 52, 48);
    VolumeData volume = obliqueVolume(dims);
    Renderer renderer(glContext(), volume, test::rampTransferFunction(0, 255, 0.5));
    const VolumeGeometry& g = renderer.geometry();
    clip::ClipMeshSet& set = renderer.clipMeshes();
    auto ball = std::make_shared<const clip::TriangleMesh>(clip::makeSphere(14.0, 3));
    auto rod = std::make_shared<const clip::TriangleMesh>(clip::makeCylinder(9.0, 40.0, 32));
    auto ring = std::make_shared<const clip::TriangleMesh>(clip::makeTorus(14.0, 7.0, 48, 24));
    const std::vector<glm::dvec3> offsets = clip::antiAliasingOffsets(16);
    std::mt19937 random(5);
    std::uint64_t deepBricks = 0, allInsideBricks = 0, deepSamples = 0;
    for (int round = 0; round < 6; ++round) {
        set.clear();
        set.add(round % 3 == 0 ? ball : round % 3 == 1 ? rod : ring, glm::dvec3(1.0), randomTurnedPose(random, 8.0), "mesh");
        drawMaps(set, 4.0);
        BrickSet deep = bricksDeepInsideMeshes(g, set);
        deepBricks += deep.visitedCount();
        // Every voxel's 9 + N samples, brick by brick.
        std::vector<glm::vec4> points;
        std::vector<std::uint32_t> brickOf;
        for (int k = 0; k < dims.z; ++k)
            for (int j = 0; j < dims.y; ++j)
                for (int i = 0; i < dims.x; ++i) {
                    glm::ivec3 b = glm::ivec3(i, j, k) / kVisitBrickSize;
                    std::uint32_t brick = std::uint32_t(b.x + deep.grid.x * (b.y + deep.grid.y * b.z));
                    for (int c = 0; c < 9 + int(offsets.size()); ++c) {
                        glm::dvec3 offset = c == 0 ? glm::dvec3(0.0)
                                            : c < 9 ? clip::kCellSampleHalfWidth * glm::dvec3((c - 1) & 1 ? 1 : -1, (c - 1) & 2 ? 1 : -1, (c - 1) & 4 ? 1 : -1)
                                                    : offsets[std::size_t(c - 9)];
                        points.emplace_back(glm::vec3(g.indexToWorld * glm::dvec4(glm::dvec3(i, j, k) + offset, 1.0)), 0.0f);
                        brickOf.push_back(brick);
                    }
                }
        std::vector<std::uint32_t> results = probe(set, points);
        std::vector<std::uint8_t> someOutside(deep.brickCount(), 0);
        for (std::size_t p = 0; p < points.size(); ++p) {
            if (!(results[p] & 1u)) someOutside[brickOf[p]] = 1;
            if (deep.visited[brickOf[p]]) {
                ++deepSamples;
                EXPECT_TRUE(results[p] & 1u) << "a sample outside in a deep brick, round " << round;
            }
        }
        for (std::size_t b = 0; b < someOutside.size(); ++b) allInsideBricks += !someOutside[b];
        set.setDepthBoxTests(false);
        EXPECT_EQ(bricksDeepInsideMeshes(g, set).visitedCount(), 0u);
        set.setDepthBoxTests(true);
    }
    std::printf("deep bricks %llu of %llu with every sample inside (%llu samples checked)\n", static_cast<unsigned long long>(deepBricks),
                static_cast<unsigned long long>(allInsideBricks), static_cast<unsigned long long>(deepSamples));
    EXPECT_GT(deepBricks * 2, allInsideBricks);
}

TEST(VisitBricks, BrickSetCountsPartialBricksAndUnites) {
    BrickSet a = BrickSet::none({9, 4, 5}), b = BrickSet::none({9, 4, 5});
    EXPECT_EQ(a.grid, glm::ivec3(3, 1, 2));
    a.visited[2] = 1;       // x 8..8, y 0..3, z 0..3: 1 * 4 * 4
    b.visited[5] = 1;       // x 8..8, z 4..4: 1 * 4 * 1
    EXPECT_EQ(a.visitedVoxels(), 16u);
    a.unite(b);
    EXPECT_EQ(a.visitedCount(), 2u);
    EXPECT_EQ(a.visitedVoxels(), 20u);
    EXPECT_EQ(a.visitedIndices(), (std::vector<std::uint32_t>{2, 5}));
    EXPECT_TRUE(a.visits({8, 3, 4}));
    EXPECT_FALSE(a.visits({7, 3, 4}));
    EXPECT_EQ(BrickSet::all({9, 4, 5}).visitedVoxels(), 9u * 4u * 5u);
}

}  // namespace
}  // namespace curette
