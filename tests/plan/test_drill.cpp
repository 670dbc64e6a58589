// Drilling on the CPU: the swept volume of a moving burr against analytic shapes (a sphere's straight stroke
// is a capsule), strokes split into frames against one stroke (no ridges), a rotating burr against a densely
// sampled union, erase, and undo/redo restoring the sub-voxel masks exactly.
#include "mesh/primitives.h"
#include "mesh/triangle_mesh.h"
#include "plan/undo_history.h"
#include "plan/drill_sweep.h"
#include "plan/removal_volume.h"
#include "plan_test_support.h"

#include <gtest/gtest.h>

#include <glm/gtc/quaternion.hpp>

#include <random>

namespace curette::plan {
namespace {

using namespace testing;

clip::SolidShape sphere(double r) { return clip::SolidShape{clip::SolidShape::Kind::Sphere, r}; }

// Drills `tool` from pose a to pose b into `removal`.
std::size_t drill(RemovalVolume& removal, const DrillTool& tool, const clip::RigidPose& a, const clip::RigidPose& b,
                  bool erase = false, BrickMaskMap* before = nullptr) {
    return applySweep(removal, DrillSweep(tool, a, b), erase, before);
}

clip::RigidPose at(glm::dvec3 p, glm::dquat q = glm::dquat(1, 0, 0, 0)) { return clip::RigidPose{p, q}; }

TEST(SolidShape, SignedDistanceAgreesWithThePrimitiveMeshes) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-9.0, 9.0);
    const std::vector<clip::TriangleMesh> meshes = {clip::makeSphere(5.0, 5), clip::makeBox({8, 6, 10}),
                                                    clip::makeCylinder(4.0, 12.0, 256), clip::makeCapsule(3.0, 8.0, 256)};
    for (const clip::TriangleMesh& mesh : meshes) {
        ASSERT_TRUE(mesh.solid) << mesh.source;
        int checked = 0;
        for (int i = 0; i < 400; ++i) {
            glm::dvec3 p(u(rng), u(rng), u(rng));
            double d = mesh.solid->signedDistance(p);
            if (std::abs(d) < 0.05) continue;   // the mesh is a polygonal approximation of the solid
            EXPECT_EQ(d < 0, clip::containsPoint(mesh, p)) << mesh.source << " at " << p.x << "," << p.y << "," << p.z;
            ++checked;
        }
        EXPECT_GT(checked, 300);
    }
    EXPECT_FALSE(clip::makeCone(3, 5).solid);
    EXPECT_FALSE(clip::makeTorus(5, 2).solid);
}

// A straight stroke of a sphere in one frame removes its capsule: pi r^2 L + 4/3 pi r^3, within 1 %; also a
// 2 mm burr (radius 1 mm) on a 1 mm grid, off the voxel centres and along (0.8, 0.5, 0.3), where the sub-cell
// lattice beats with the stroke (4 sub-cells per axis gave +1.1 % there).
TEST(Drill, AStraightStrokeOfASphereIsItsCapsule) {
    struct Case {
        glm::dvec3 spacing;
        double r;
        glm::dvec3 a, direction;
    };
    const Case cases[] = {{glm::dvec3(1.0), 2.0, {-12.3, -4.1, 2.2}, {0.8, 0.3, 0.5}},
                          {glm::dvec3(0.7, 0.8, 1.5), 2.0, {-12.3, -4.1, 2.2}, {0.8, 0.3, 0.5}},
                          {glm::dvec3(1.0), 1.0, {-12.7, -9.9, -5.3}, {0.8, 0.5, 0.3}},
                          {glm::dvec3(1.0), 1.0, {9.644, -12.866, 8.177}, {-0.322, 0.812, -0.487}}};
    for (const Case& c : cases) {
        glm::ivec3 dims = dimsFor(c.spacing, 24.0);
        RemovalVolume removal(dims, gridAffine(c.spacing, dims));
        const double length = 30.0;
        glm::dvec3 b = c.a + length * glm::normalize(c.direction);
        drill(removal, {sphere(c.r)}, at(c.a), at(b));
        double analytic = kPi * c.r * c.r * length + 4.0 / 3.0 * kPi * c.r * c.r * c.r;
        RecordProperty("capsule_ratio", std::to_string(removal.drilledVolumeMm3() / analytic));
        EXPECT_NEAR(removal.drilledVolumeMm3() / analytic, 1.0, 0.01)
            << "radius " << c.r << ", spacing " << c.spacing.x << "," << c.spacing.y << "," << c.spacing.z;
    }
}

// The sweep's distance bound only settles what testing every sub-cell would: the same bits, for a rotating,
// non-uniformly scaled box and cylinder on a sheared grid, drilled and erased.
TEST(Drill, SettlingVoxelsByTheBoundGivesTheBitsOfEverySubCell) {
    glm::ivec3 dims(28, 26, 24);
    glm::dmat4 affine(1.0);
    affine[0] = glm::dvec4(0.9, 0.1, 0.0, 0.0);
    affine[1] = glm::dvec4(-0.05, 0.8, 0.1, 0.0);
    affine[2] = glm::dvec4(0.0, 0.15, 1.1, 0.0);
    affine[3] = glm::dvec4(-12.0, -10.0, -13.0, 1.0);
    RemovalVolume fast(dims, affine), slow(dims, affine);
    const DrillTool tools[] = {{clip::SolidShape{clip::SolidShape::Kind::Box, 0, 0, {3.0, 2.0, 5.0}}, {1.3, 0.7, 1.0}},
                               {clip::SolidShape{clip::SolidShape::Kind::Cylinder, 1.5, 6.0}, {1.0, 1.0, 0.6}},
                               {sphere(1.7), glm::dvec3(1.0)}};
    glm::dquat q0 = glm::angleAxis(glm::radians(20.0), glm::normalize(glm::dvec3(1, 2, 3)));
    glm::dquat q1 = glm::angleAxis(glm::radians(75.0), glm::normalize(glm::dvec3(-1, 0.5, 2)));
    std::size_t settled = 0;
    for (int i = 0; i < 3; ++i) {
        DrillSweep sweep(tools[i], at({-4.0 + 3 * i, -2.1, 0.7}, q0), at({3.3, 1.9 - i, -1.2}, q1));
        bool erase = i == 2;
        std::size_t a = applySweep(fast, sweep, erase);
        std::size_t b = slow.apply([&](glm::dvec3 w) { return sweep.contains(w); }, slow.voxelBoxAround(sweep.boundsMin(), sweep.boundsMax()),
                                   erase);
        EXPECT_EQ(a, b);
        EXPECT_EQ(fast.digest(), slow.digest()) << "after sweep " << i;
        settled += a;
    }
    EXPECT_GT(settled, 500u);
    EXPECT_FALSE(fast.empty());
}

// A voxel's byte never says less than its bits: one drilled sub-cell is byte 1, a full voxel 255.
TEST(Drill, TheDrilledByteRoundsUp) {
    EXPECT_EQ(drilledByteFromBits(0), 0);
    EXPECT_EQ(drilledByteFromBits(1), 1);
    EXPECT_EQ(drilledByteFromBits(kRemovalCellsPerVoxel), 255);
    for (int bits = 0; bits <= kRemovalCellsPerVoxel; ++bits) {
        EXPECT_GE(drilledByteFromBits(bits) / 255.0, double(bits) / kRemovalCellsPerVoxel);
        EXPECT_LT(drilledByteFromBits(bits) / 255.0, double(bits) / kRemovalCellsPerVoxel + 1.0 / 255.0);
    }
}

// Frames are not samples: the stroke split into 7 frames removes what it removes in one (the union of the
// pieces of a straight sweep is the whole sweep), while the burr's poses alone at the frame times would not.
TEST(Drill, AStrokeSplitIntoFramesLeavesNoRidges) {
    glm::ivec3 dims = dimsFor(glm::dvec3(1.0), 20.0);
    glm::dmat4 affine = gridAffine(glm::dvec3(1.0), dims);
    RemovalVolume whole(dims, affine), framed(dims, affine), sampled(dims, affine);
    DrillTool tool{sphere(2.0)};
    glm::dvec3 a(-14, 1.3, -0.4), b(14, -2.1, 3.7);
    drill(whole, tool, at(a), at(b));
    for (int f = 0; f < 7; ++f) {
        clip::RigidPose p0 = at(glm::mix(a, b, f / 7.0)), p1 = at(glm::mix(a, b, (f + 1) / 7.0));
        drill(framed, tool, p0, p1);
        drill(sampled, tool, p1, p1);   // only where the burr is at the frame
    }
    EXPECT_NEAR(framed.drilledVolumeMm3(), whole.drilledVolumeMm3(), 1e-3 * whole.drilledVolumeMm3());
    EXPECT_LT(sampled.drilledVolumeMm3(), 0.9 * whole.drilledVolumeMm3()) << "poses at frame times leave gaps";
}

// A cylinder turning 60 degrees about an axis through its centre: the sweep against the union of 301 poses
// along the turn; the sub-steps keep every point within the rotation tolerance, so the volumes agree to the
// shell that tolerance leaves (surface area times 0.125 mm, here under 1 %).
TEST(Drill, ARotatingBurrSweepsItsTurn) {
    glm::ivec3 dims = dimsFor(glm::dvec3(0.5), 8.0);
    glm::dmat4 affine = gridAffine(glm::dvec3(0.5), dims);
    RemovalVolume swept(dims, affine), dense(dims, affine);
    DrillTool tool{clip::SolidShape{clip::SolidShape::Kind::Cylinder, 1.5, 8.0}};
    glm::dquat q0(1, 0, 0, 0), q1 = glm::angleAxis(glm::radians(60.0), glm::dvec3(1, 0, 0));
    glm::dvec3 p0(0.3, -0.2, 0.1), p1(1.9, 0.4, -0.6);
    drill(swept, tool, at(p0, q0), at(p1, q1));
    EXPECT_GT(DrillSweep(tool, at(p0, q0), at(p1, q1)).substeps(), 10);
    for (int i = 0; i <= 300; ++i) {
        double s = i / 300.0;
        clip::RigidPose p = at(glm::mix(p0, p1, s), glm::slerp(q0, q1, s));
        drill(dense, tool, p, p);
    }
    RecordProperty("rotating_ratio", std::to_string(swept.drilledVolumeMm3() / dense.drilledVolumeMm3()));
    EXPECT_NEAR(swept.drilledVolumeMm3() / dense.drilledVolumeMm3(), 1.0, 0.01);
}

TEST(Drill, EraseRestoresWhatTheStrokeRemoved) {
    glm::ivec3 dims = dimsFor(glm::dvec3(1.0), 12.0);
    RemovalVolume removal(dims, gridAffine(glm::dvec3(1.0), dims));
    drill(removal, {sphere(2.0)}, at({-5, 0, 0}), at({5, 0, 0}));
    double full = removal.drilledVolumeMm3();
    drill(removal, {sphere(3.0)}, at({0, 0, 0}), at({0, 0, 0}), true);
    EXPECT_LT(removal.drilledVolumeMm3(), full - 50.0);
    drill(removal, {sphere(3.0)}, at({-8, 0, 0}), at({8, 0, 0}), true);
    EXPECT_TRUE(removal.empty());
    EXPECT_EQ(removal.drilledVolumeMm3(), 0.0);
}

// Undo and redo give back the exact sub-voxel masks, a new stroke drops the redo steps, and the budget
// forgets the oldest steps, never the removal.
TEST(UndoHistory, UndoAndRedoRestoreTheMasksExactly) {
    glm::ivec3 dims = dimsFor(glm::dvec3(1.0), 16.0);
    glm::dmat4 affine = gridAffine(glm::dvec3(1.0), dims);
    RemovalVolume removal(dims, affine);
    UndoHistory history;
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-10.0, 10.0);
    std::vector<std::vector<VoxelMask>> states;
    auto snapshot = [&] {
        std::vector<VoxelMask> s;
        for (int z = 0; z < dims.z; ++z)
            for (int y = 0; y < dims.y; ++y)
                for (int x = 0; x < dims.x; ++x) s.push_back(removal.mask({x, y, z}));
        return s;
    };
    states.push_back(snapshot());
    for (int stroke = 0; stroke < 4; ++stroke) {
        history.beginStroke();
        glm::dvec3 p(u(rng), u(rng), u(rng));
        for (int frame = 0; frame < 3; ++frame) {
            glm::dvec3 q = p + glm::dvec3(u(rng), u(rng), u(rng)) * 0.3;
            drill(removal, {sphere(1.5 + stroke * 0.5)}, at(p), at(q), stroke == 3, history.before());
            p = q;
        }
        history.endStroke(removal);
        EXPECT_GT(history.lastStrokeBytes(), 0u);
        states.push_back(snapshot());
    }
    ASSERT_EQ(history.undoSteps(), 4u);
    for (int i = 3; i >= 0; --i) {
        ASSERT_TRUE(history.undo(removal));
        EXPECT_EQ(snapshot(), states[static_cast<std::size_t>(i)]) << "after undoing stroke " << i;
    }
    EXPECT_FALSE(history.undo(removal));
    EXPECT_TRUE(removal.empty());
    ASSERT_TRUE(history.redo(removal));
    ASSERT_TRUE(history.redo(removal));
    EXPECT_EQ(snapshot(), states[2]);
    history.beginStroke();
    drill(removal, {sphere(2.0)}, at({0, 0, 0}), at({1, 0, 0}), false, history.before());
    history.endStroke(removal);
    EXPECT_EQ(history.redoSteps(), 0u) << "a new stroke drops what could be redone";

    UndoHistory small(1);   // a budget below one step: only the newest is kept
    RemovalVolume other(dims, affine);
    for (int i = 0; i < 3; ++i) {
        small.beginStroke();
        drill(other, {sphere(2.0)}, at({-8.0 + 6 * i, 0, 0}), at({-7.0 + 6 * i, 0, 0}), false, small.before());
        small.endStroke(other);
    }
    EXPECT_EQ(small.undoSteps(), 1u);
    double kept = other.drilledVolumeMm3();
    ASSERT_TRUE(small.undo(other));
    EXPECT_GT(other.drilledVolumeMm3(), 0.5 * kept) << "forgotten steps stay drilled";
}

}  // namespace
}  // namespace curette::plan

namespace curette::plan {
namespace {

using namespace testing;

// The report's field with the drilled removal folded in: the box grows to the drilled bricks, a voxel only
// drilled counts its drilled fraction, one only cut by meshes keeps its count, and where both reach the count
// is 1 - (1 - meshes)(1 - drilled), rounded up (never less removed than step IV's V_o says).
TEST(DrillReport, TheFieldCountsTheDrilledRemovalWithTheMeshes) {
    glm::ivec3 dims = dimsFor(glm::dvec3(1.0), 16.0);
    glm::dmat4 affine = gridAffine(glm::dvec3(1.0), dims);
    RemovalVolume removal(dims, affine);
    DrillSweep sweep({clip::SolidShape{clip::SolidShape::Kind::Sphere, 3.0}}, clip::RigidPose{glm::dvec3(-8, 0, 0), {}},
                     clip::RigidPose{glm::dvec3(-2, 0, 0), {}});
    applySweep(removal, sweep, false);
    RemovalField meshes;
    meshes.gridDims = dims;
    meshes.indexToWorld = affine;
    meshes.samplesPerVoxel = 9 + 256;
    meshes.origin = glm::ivec3(14);
    meshes.size = glm::ivec3(6);
    meshes.insideSamples.assign(meshes.box().voxelCount(), 0);
    for (std::size_t i = 0; i < meshes.insideSamples.size(); ++i) meshes.insideSamples[i] = static_cast<std::uint16_t>((i * 37) % 266);
    RemovalField both = withDrilledRemoval(meshes, removal);
    both.validate();
    VoxelBox drilledBox = removal.drilledBox();
    EXPECT_TRUE(both.box().contains(drilledBox.origin) && both.box().contains(drilledBox.origin + drilledBox.size - 1));
    EXPECT_TRUE(both.box().contains(meshes.origin) && both.box().contains(meshes.origin + meshes.size - 1));
    int checkedBoth = 0;
    for (int z = both.origin.z; z < both.origin.z + both.size.z; ++z)
        for (int y = both.origin.y; y < both.origin.y + both.size.y; ++y)
            for (int x = both.origin.x; x < both.origin.x + both.size.x; ++x) {
                glm::ivec3 v(x, y, z);
                double m = meshes.removedFraction(v), d = removal.drilledFraction(v);
                double expected = 1.0 - (1.0 - m) * (1.0 - d);
                double got = both.removedFraction(v);
                ASSERT_GE(got, expected - 1e-12) << "never less than the combination";
                ASSERT_LT(got, expected + 1.0 / both.samplesPerVoxel) << "rounded up by less than one sample";
                checkedBoth += m > 0 && d > 0 && d < 1;
            }
    EXPECT_GT(checkedBoth, 0) << "some voxels must be reached by both";
    RemovalField none = withDrilledRemoval(meshes, RemovalVolume(dims, affine));
    EXPECT_EQ(none.insideSamples, meshes.insideSamples);
}

}  // namespace
}  // namespace curette::plan
