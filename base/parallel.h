#pragma once
// Independent work split across the machine's threads: body(first, end) over contiguous ranges of [0, count),
// one per hardware thread (at most 8), the calling thread taking the first. For items that do not depend on
// each other, so the result does not depend on the split.

#include <algorithm>
#include <cstddef>
#include <thread>
#include <vector>

namespace curette {

template <typename Body>
void splitAcrossThreads(std::size_t count, const Body& body) {
    const std::size_t threads = std::clamp<std::size_t>(std::thread::hardware_concurrency(), 1, 8);
    const std::size_t per = (count + threads - 1) / threads;
    std::vector<std::thread> workers;
    for (std::size_t t = 1; t < threads && t * per < count; ++t) workers.emplace_back([&, t] { body(t * per, std::min(count, (t + 1) * per)); });
    body(0, std::min(count, per));
    for (std::thread& w : workers) w.join();
}

}  // namespace curette
