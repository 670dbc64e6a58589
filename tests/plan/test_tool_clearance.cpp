// Tool clearance (plan/tool_clearance.h): the live gap from a held mesh to the protected structures is never
// larger than the true gap, and larger than it by at most its stated uncertainty; inside a structure it is 0.
#include "plan/tool_clearance.h"

#include "mesh/primitives.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace curette::plan {
namespace {

// A slab of protected cells, voxels x in [25, 30] over the whole y, z range, on an anisotropic grid.
struct SlabScene {
    glm::ivec3 dims{40, 36, 30};
    glm::dvec3 spacing{0.8, 1.2, 2.0};
    glm::dmat4 indexToWorld{1.0};
    std::vector<std::uint8_t> cells;
    double faceX() const { return (25 - 0.5) * spacing.x + indexToWorld[3].x; }   // the slab's first face, world x

    SlabScene() {
        indexToWorld = glm::dmat4(glm::dvec4(spacing.x, 0, 0, 0), glm::dvec4(0, spacing.y, 0, 0), glm::dvec4(0, 0, spacing.z, 0),
                                  glm::dvec4(-3, 5, -7, 1));
        cells.assign(static_cast<std::size_t>(dims.x) * dims.y * dims.z, 0);
        for (int k = 0; k < dims.z; ++k)
            for (int j = 0; j < dims.y; ++j)
                for (int i = 25; i <= 30; ++i) cells[(static_cast<std::size_t>(k) * dims.y + j) * dims.x + i] = 1;
    }
};

TEST(ToolClearance, NeverLargerThanTheTrueGapAndWithinItsUncertainty) {
    SlabScene s;
    ToolClearance clearance(s.dims, s.indexToWorld, s.cells);
    auto sphere = std::make_shared<const clip::TriangleMesh>(clip::makeSphere(4.0, 3));
    std::mt19937 random(7);
    std::uniform_real_distribution<double> x(-2.0, 14.0), unit(-1.0, 1.0), scale(0.5, 1.5);
    for (int trial = 0; trial < 40; ++trial) {
        PosedMesh tool{sphere, {}, glm::dvec3(scale(random), scale(random), scale(random))};
        tool.pose.position = {x(random), 5 + 20 + 5 * unit(random), -7 + 30 + 5 * unit(random)};
        tool.pose.orientation = glm::normalize(glm::dquat(unit(random), unit(random), unit(random), unit(random)));
        // The slab spans the tool in y and z, so the gap is from the tool's largest x (a vertex) to the face.
        const glm::dmat4 toWorld = tool.pose.matrix() * glm::dmat4(glm::dvec4(tool.scale.x, 0, 0, 0), glm::dvec4(0, tool.scale.y, 0, 0),
                                                                   glm::dvec4(0, 0, tool.scale.z, 0), glm::dvec4(0, 0, 0, 1));
        double maxX = -1e9;
        for (const glm::vec3& p : sphere->positions) maxX = std::max(maxX, (toWorld * glm::dvec4(glm::dvec3(p), 1.0)).x);
        const double gap = std::max(0.0, s.faceX() - maxX);
        std::optional<Clearance> c = clearance.of(tool);
        ASSERT_TRUE(c);
        EXPECT_LE(c->mm, gap + 1e-9) << "trial " << trial << ": a clearance larger than the gap understates the risk";
        EXPECT_GE(c->mm + c->uncertaintyMm, gap - 1e-9) << "trial " << trial;
        // A cell diagonal (the corner bound at a cell centre reaches half of it each way) and the sample spacing.
        EXPECT_LE(c->uncertaintyMm, glm::length(s.spacing) + 2 * kClearanceSampleMm) << "trial " << trial;
    }
}

// The gap from a posed tool to an axis-aligned box of world points, by brute force: the tool's triangles
// sampled every `stepMm` (an oracle independent of the clearance's sampling), each sample clamped to the box.
double bruteForceGap(const PosedMesh& tool, glm::dvec3 lo, glm::dvec3 hi, double stepMm) {
    const glm::dmat4 toWorld = tool.pose.matrix() * glm::dmat4(glm::dvec4(tool.scale.x, 0, 0, 0), glm::dvec4(0, tool.scale.y, 0, 0),
                                                               glm::dvec4(0, 0, tool.scale.z, 0), glm::dvec4(0, 0, 0, 1));
    double best = 1e30;
    for (const glm::uvec3& t : tool.geometry->triangles) {
        glm::dvec3 a(toWorld * glm::dvec4(glm::dvec3(tool.geometry->positions[t.x]), 1.0));
        glm::dvec3 b(toWorld * glm::dvec4(glm::dvec3(tool.geometry->positions[t.y]), 1.0));
        glm::dvec3 c(toWorld * glm::dvec4(glm::dvec3(tool.geometry->positions[t.z]), 1.0));
        int n = std::max(1, static_cast<int>(std::ceil(std::max(glm::length(b - a), glm::length(c - a)) / stepMm)));
        for (int i = 0; i <= n; ++i)
            for (int j = 0; i + j <= n; ++j) {
                glm::dvec3 p = a + (b - a) * (double(i) / n) + (c - a) * (double(j) / n);
                best = std::min(best, glm::length(p - glm::clamp(p, lo, hi)));
            }
    }
    return best;
}

// A small structure (2 x 2 x 2 cells) has convex corners, where a distance interpolated between lattice corners
// exceeds the true one, and a tool's nearest point often lies inside one of its triangles.
TEST(ToolClearance, NearTheCornersOfASmallStructure) {
    SlabScene s;
    std::fill(s.cells.begin(), s.cells.end(), 0);
    const glm::ivec3 first(18, 17, 14);
    for (int k = 0; k < 2; ++k)
        for (int j = 0; j < 2; ++j)
            for (int i = 0; i < 2; ++i) s.cells[(static_cast<std::size_t>(first.z + k) * s.dims.y + first.y + j) * s.dims.x + first.x + i] = 1;
    const glm::dvec3 lo(s.indexToWorld * glm::dvec4(glm::dvec3(first) - 0.5, 1.0)), hi(s.indexToWorld * glm::dvec4(glm::dvec3(first) + 1.5, 1.0));
    ToolClearance clearance(s.dims, s.indexToWorld, s.cells);
    auto box = std::make_shared<const clip::TriangleMesh>(clip::makeBox({6, 5, 4}));
    std::mt19937 random(11);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    int close = 0;
    for (int trial = 0; trial < 60; ++trial) {
        PosedMesh tool{box, {}, glm::dvec3(1.0)};
        tool.pose.orientation = glm::normalize(glm::dquat(unit(random), unit(random), unit(random), unit(random)));
        glm::dvec3 direction = glm::normalize(glm::dvec3(unit(random), unit(random), unit(random)));
        tool.pose.position = 0.5 * (lo + hi) + direction * (4.0 + 2.0 * (unit(random) + 1.0));
        const double gap = bruteForceGap(tool, lo, hi, 0.01);
        std::optional<Clearance> c = clearance.of(tool);
        ASSERT_TRUE(c);
        EXPECT_LE(c->mm, gap + 0.01) << "trial " << trial << ": a clearance larger than the gap understates the risk";
        EXPECT_GE(c->mm + c->uncertaintyMm, gap - 0.01) << "trial " << trial;
        close += gap < 2.0;
    }
    EXPECT_GT(close, 10) << "enough tools come close for the corners to matter";
}

TEST(ToolClearance, ATouchingToolHasNoClearance) {
    SlabScene s;
    ToolClearance clearance(s.dims, s.indexToWorld, s.cells);
    auto sphere = std::make_shared<const clip::TriangleMesh>(clip::makeSphere(4.0, 3));
    PosedMesh tool{sphere, {}, glm::dvec3(1.0)};
    tool.pose.position = {s.faceX() - 3.0, 25, 23};   // 1 mm into the slab
    std::optional<Clearance> c = clearance.of(tool);
    ASSERT_TRUE(c);
    EXPECT_EQ(c->mm, 0.0);
    EXPECT_LT(c->nearestOnTool.x, s.faceX() + 1.5);
}

TEST(ToolClearance, NothingProtectedGivesNoFigure) {
    SlabScene s;
    std::fill(s.cells.begin(), s.cells.end(), 0);
    ToolClearance clearance(s.dims, s.indexToWorld, s.cells);
    EXPECT_TRUE(clearance.empty());
    EXPECT_FALSE(clearance.of({std::make_shared<const clip::TriangleMesh>(clip::makeSphere(4.0, 2)), {}, glm::dvec3(1.0)}));
}

}  // namespace
}  // namespace curette::plan
