#pragma once
// How much of a voxel a clip region covers: step IV of CAO (Algorithm 2, lines 3-10) on the CPU. A voxel is
// probed at 9 samples (its centre and the eight corners of its own cell); only when those 9 disagree, at N
// more fixed offsets inside the same cell (line 9). The GPU twin is shaders/clip_coverage.glsl.
// This file is the one CPU definition of that sample count: the CPU reference of step IV
// (render/reference/lao_reference.cpp, clipVoxels) and the planning report's removal field (plan/) use it.

#include <glm/glm.hpp>

#include <functional>
#include <vector>

namespace curette::clip {

// How far from a voxel's centre its samples lie, per axis, in index units: the corners of the voxel's own
// cell (the paper's "corners of the voxel"), inset by 1/64 voxel. Own cell, so the count is the covered
// fraction of that voxel and not of the 2-voxel cube around it; inset, so a clip face lying exactly on a
// cell face (a carve that stops at a boundary) is credited to the voxel it covers and not to the one beyond.
// The GLSL twin is CELL_SAMPLE_HALF_WIDTH (shaders/clip_coverage.glsl).
inline constexpr double kCellSampleHalfWidth = 0.484375;

// The N extra anti-aliasing offsets of step IV (Algorithm 2, line 9) in voxel index units: Halton points
// (bases 2, 3, 5) in the sample cell [-kCellSampleHalfWidth, kCellSampleHalfWidth]^3, fixed so every run classifies the same. One definition for the GPU buffer and
// the CPU twins.
std::vector<glm::dvec3> antiAliasingOffsets(int count);

// The number of the 9 + N samples of the voxel centred at `centreIndex` (index space; N = offsets.size())
// that lie inside the clip region, as an index-space test. When the first 9 agree the N offsets are not
// probed and count as agreeing: the result is then 0 or 9 + N. So count / (9 + N) is always the voxel's
// covered (removed) fraction, and 1 - count / (9 + N) the visible fraction Algorithm 2 line 10 scales the
// opacity by (0 visible: clipped, category a).
int insideSampleCountInIndexSpace(const std::function<bool(glm::dvec3 index)>& insideAtIndex, glm::dvec3 centreIndex,
                                  const std::vector<glm::dvec3>& offsets);

// The same with a world-space inside test (world = indexToWorld * index, as the shader does).
int insideSampleCount(const std::function<bool(glm::dvec3 world)>& inside, const glm::dmat4& indexToWorld,
                      glm::dvec3 centreIndex, const std::vector<glm::dvec3>& offsets);

}  // namespace curette::clip
