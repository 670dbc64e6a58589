#include "app/volume_statistics.h"

#include <algorithm>
#include <cmath>

namespace curette {

VolumeStatistics computeStatistics(const VolumeData& volume, int bins) {
    VolumeStatistics s;
    s.min = volume.minValue;
    s.max = volume.maxValue;
    s.histogram.assign(static_cast<std::size_t>(bins), 0);
    // Voxels without data (NaN/Inf in the file) are left out of every number (min and max already are).
    const std::size_t total = volume.voxelCount();
    const std::size_t n = total - static_cast<std::size_t>(volume.noDataVoxels);
    if (n == 0) return s;
    constexpr int fine = 4096;
    std::vector<std::uint64_t> fineHistogram(fine, 0);
    double span = s.max > s.min ? s.max - s.min : 1.0;
    double sum = 0, sumSquares = 0;
    std::uint64_t nonZero = 0;
    for (std::size_t i = 0; i < total; ++i) {
        if (volume.isNoData(i)) continue;
        double v = volume.valueScale * volume.normalized(i) + volume.valueOffset;
        sum += v;
        sumSquares += v * v;
        nonZero += v != 0.0;
        double unit = (v - s.min) / span;
        fineHistogram[static_cast<std::size_t>(std::clamp(static_cast<int>(unit * fine), 0, fine - 1))]++;
        s.histogram[static_cast<std::size_t>(std::clamp(static_cast<int>(unit * bins), 0, bins - 1))]++;
    }
    s.mean = sum / static_cast<double>(n);
    s.standardDeviation = std::sqrt(std::max(0.0, sumSquares / static_cast<double>(n) - s.mean * s.mean));
    s.nonZeroFraction = static_cast<double>(nonZero) / static_cast<double>(n);
    const double wanted[5] = {0.01, 0.25, 0.5, 0.75, 0.99};
    std::uint64_t cumulative = 0;
    std::size_t next = 0;
    for (int b = 0; b < fine && next < 5; ++b) {
        cumulative += fineHistogram[static_cast<std::size_t>(b)];
        while (next < 5 && static_cast<double>(cumulative) >= wanted[next] * static_cast<double>(n))
            s.percentiles[next++] = s.min + span * (b + 0.5) / fine;
    }
    return s;
}

}  // namespace curette
