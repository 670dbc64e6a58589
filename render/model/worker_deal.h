#pragma once
// The order of a dispatch's work groups on llvmpipe (docs/subsystems.md, "Empty space, tile
// order and clip spans"). Its compute thread pool (lp_cs_tpool.c, Mesa 22.3) hands each of its T worker
// threads one contiguous run of floor(n / T) of a dispatch's n work groups, in gl_WorkGroupID order (x fastest),
// and the n mod T left over one at a time. A list whose costly entries sit together (the bricks around a clip
// mesh, or the slab of a step I slice that holds the head while the rest is air) then keeps one thread busy
// while the other waits. Dealt out round-robin, every run takes every T-th entry of the list, so each thread
// gets an even share of every part of it. Which group computes which voxel changes, not what it computes.
// On a GPU the order is immaterial.
#include <glm/vec2.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace curette {

// The worker threads llvmpipe starts: one per CPU core (LP_NUM_THREADS aside), at least 2.
int llvmpipeWorkerThreads();

// `items` reordered so that a run of floor(n / threads) consecutive entries starting at r * floor(n / threads)
// holds items r, r + threads, r + 2 * threads, ...; the n mod threads last items keep their places.
std::vector<std::uint32_t> dealtToWorkerThreads(const std::vector<std::uint32_t>& items, int threads);

// The widest row of work groups a dispatch here uses (GL guarantees 65535 per dimension).
inline constexpr std::uint32_t kMaxWorkGroupsX = 32768;

// A 2-D grid of work groups for `groups` jobs numbered y * width + x (at most kMaxWorkGroupsX along x): as few
// rows as that allows, each as narrow as it can be, so fewer groups than rows lie past the jobs and llvmpipe's
// runs split the jobs themselves evenly. shaders/lao_compact.comp sizes its indirect dispatch the same way.
// (1, 0) for no jobs.
glm::uvec2 workGroupGrid(std::uint64_t groups);

}  // namespace curette
