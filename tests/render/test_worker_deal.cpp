// The order of a dispatch's work groups on llvmpipe (render/model/worker_deal.h): the deal is a permutation, and
// llvmpipe's split of the dealt list (one contiguous run of floor(n / T) groups per thread, the rest one at a
// time, lp_cs_tpool.c) gives every thread an even share of a list whose cost sits in one part of it, which the
// list in its own order does not. The grid holds fewer groups than rows past the jobs.
#include "render/model/worker_deal.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <numeric>

namespace curette {
namespace {

// The work each of `threads` threads does when llvmpipe splits a dispatch of these costs, in list order.
std::vector<double> threadWork(const std::vector<double>& costs, int threads) {
    std::size_t t = static_cast<std::size_t>(threads), run = costs.size() / t;
    std::vector<double> work(t, 0.0);
    for (std::size_t i = 0; i < costs.size(); ++i) work[i < run * t ? i / run : (i - run * t) % t] += costs[i];
    return work;
}

// How much more than the mean the busiest thread does.
double excessOverMean(const std::vector<double>& work) {
    double total = std::accumulate(work.begin(), work.end(), 0.0);
    return *std::max_element(work.begin(), work.end()) - total / double(work.size());
}

TEST(WorkerDeal, IsAPermutationThatGivesEachRunEveryTthItem) {
    for (int threads : {1, 2, 3, 4, 8})
        for (std::uint32_t n : {0u, 1u, 2u, 7u, 64u, 1001u}) {
            std::vector<std::uint32_t> items(n);
            std::iota(items.begin(), items.end(), 100u);
            std::vector<std::uint32_t> dealt = dealtToWorkerThreads(items, threads);
            std::vector<std::uint32_t> sorted = dealt;
            std::sort(sorted.begin(), sorted.end());
            ASSERT_EQ(sorted, items) << threads << " threads, " << n << " items";
            std::size_t run = n / std::size_t(threads);
            for (std::size_t r = 0; r < std::size_t(threads); ++r)
                for (std::size_t j = 0; j < run; ++j) EXPECT_EQ(dealt[r * run + j], items[j * threads + r]);
        }
}

// Lists whose cost sits together, as a step I slice whose first half is air (cheap with the seen-brick rule)
// or step IV's bricks around a mesh at one end of the visited box: dealt, no thread does more than one group's
// cost (1 here) above the mean.
TEST(WorkerDeal, BalancesListsWhoseCostSitsTogether) {
    std::vector<std::function<double(std::size_t, std::size_t)>> shapes = {
        [](std::size_t i, std::size_t n) { return i < n / 2 ? 0.05 : 1.0; },                        // air, then tissue
        [](std::size_t i, std::size_t n) { return i < n / 3 ? 1.0 : 0.1; },                         // a mesh at one end
        [](std::size_t i, std::size_t n) { return 10 * i >= 5 * n && 10 * i < 7 * n ? 1.0 : 0.0; },  // past the middle
        [](std::size_t i, std::size_t n) { return double(i) / double(n); }};                        // a ramp
    for (int threads : {2, 3, 4})
        for (std::size_t n : {1000u, 10007u, 116380u})
            for (std::size_t s = 0; s < shapes.size(); ++s) {
                std::vector<std::uint32_t> order(n);
                std::iota(order.begin(), order.end(), 0u);
                std::vector<std::uint32_t> dealt = dealtToWorkerThreads(order, threads);
                std::vector<double> costs(n), dealtCosts(n);
                for (std::size_t i = 0; i < n; ++i) costs[i] = shapes[s](i, n);
                for (std::size_t i = 0; i < n; ++i) dealtCosts[i] = costs[dealt[i]];
                EXPECT_LE(excessOverMean(threadWork(dealtCosts, threads)), 1.0)
                    << "shape " << s << ", " << threads << " threads, " << n << " items";
                // In its own order the list leaves a thread far busier than the mean (the deal is what balances).
                EXPECT_GT(excessOverMean(threadWork(costs, threads)), 0.05 * double(n) / threads)
                    << "shape " << s << ", " << threads << " threads, " << n << " items";
            }
}

TEST(WorkerDeal, TheGridLeavesFewerGroupsThanRowsPastTheJobs) {
    EXPECT_EQ(workGroupGrid(0).y, 0u);
    for (std::uint64_t groups : {1ull, 5ull, 32767ull, 32768ull, 32769ull, 65537ull, 116380ull, 3000001ull}) {
        glm::uvec2 grid = workGroupGrid(groups);
        std::uint64_t slots = std::uint64_t(grid.x) * grid.y;
        EXPECT_LE(grid.x, kMaxWorkGroupsX) << groups;
        EXPECT_GE(slots, groups) << groups;
        EXPECT_LT(slots - groups, std::max<std::uint64_t>(grid.y, 1)) << groups;
    }
}

}  // namespace
}  // namespace curette
