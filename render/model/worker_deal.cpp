#include "render/model/worker_deal.h"

#include <algorithm>
#include <thread>

namespace curette {

int llvmpipeWorkerThreads() { return static_cast<int>(std::max(2u, std::thread::hardware_concurrency())); }

std::vector<std::uint32_t> dealtToWorkerThreads(const std::vector<std::uint32_t>& items, int threads) {
    std::size_t t = static_cast<std::size_t>(std::max(threads, 1));
    std::size_t run = items.size() / t;
    std::vector<std::uint32_t> dealt(items);
    for (std::size_t r = 0; r < t; ++r)
        for (std::size_t j = 0; j < run; ++j) dealt[r * run + j] = items[j * t + r];
    return dealt;
}

glm::uvec2 workGroupGrid(std::uint64_t groups) {
    if (groups == 0) return glm::uvec2(1, 0);
    std::uint64_t rows = (groups + kMaxWorkGroupsX - 1) / kMaxWorkGroupsX;
    std::uint64_t width = (groups + rows - 1) / rows;
    return glm::uvec2(static_cast<unsigned>(width), static_cast<unsigned>((groups + width - 1) / width));
}

}  // namespace curette
