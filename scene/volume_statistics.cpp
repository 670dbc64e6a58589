#include "scene/volume_statistics.h"

#include "base/value_histogram.h"
#include "render/model/volume_geometry.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace curette {

VolumeStatistics computeStatistics(const VolumeData& volume, int bins) {
    VolumeStatistics s;
    s.min = volume.minValue;
    s.max = volume.maxValue;
    ValueHistogram histogram = ValueHistogram::over(s.min, s.max, bins);
    // Voxels without data (NaN/Inf in the file) are left out of every number (min and max already are).
    const std::size_t total = volume.voxelCount();
    const std::size_t n = total - static_cast<std::size_t>(volume.noDataVoxels);
    if (n == 0) {
        s.histogram = std::move(histogram.counts);
        return s;
    }
    double sum = 0, sumSquares = 0;
    std::uint64_t nonZero = 0;
    for (std::size_t i = 0; i < total; ++i) {
        if (volume.isNoData(i)) continue;
        double v = volume.valueScale * volume.normalized(i) + volume.valueOffset;
        sum += v;
        sumSquares += v * v;
        nonZero += v != 0.0;
        histogram.add(v);
    }
    s.histogram = std::move(histogram.counts);
    s.mean = sum / static_cast<double>(n);
    s.standardDeviation = std::sqrt(std::max(0.0, sumSquares / static_cast<double>(n) - s.mean * s.mean));
    s.nonZeroFraction = static_cast<double>(nonZero) / static_cast<double>(n);
    // Percentiles are data values (nearest rank: the value at rank ceil(p n) - 1 in sorted order), not bin
    // centres, so an integer label map reports 0 where its voxels are 0.
    std::vector<double> values;
    values.reserve(n);
    for (std::size_t i = 0; i < total; ++i)
        if (!volume.isNoData(i)) values.push_back(volume.valueScale * volume.normalized(i) + volume.valueOffset);
    const double wanted[5] = {0.01, 0.25, 0.5, 0.75, 0.99};
    for (std::size_t k = 0; k < 5; ++k) {
        std::size_t rank = static_cast<std::size_t>(std::ceil(wanted[k] * static_cast<double>(n)));
        rank = std::clamp<std::size_t>(rank, 1, n) - 1;
        std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(rank), values.end());
        s.percentiles[k] = values[rank];
    }
    return s;
}

GreyWindow defaultGreyWindow(const VolumeStatistics& s) {
    if (s.percentiles[4] > s.percentiles[0]) return {s.percentiles[0], s.percentiles[4]};
    if (s.max > s.min) return {s.min, s.max};
    return {s.min - 0.5, s.min + 0.5};
}

double maxGradientMagnitude(const VolumeData& volume) {
    const glm::ivec3 dims = volume.dims;
    const glm::dmat3 toWorld = VolumeGeometry{dims, volume.indexToWorld}.gradientIndexToWorld() * volume.valueScale;
    double largest = 0;
    for (int k = 0; k < dims.z; ++k)
        for (int j = 0; j < dims.y; ++j)
            for (int i = 0; i < dims.x; ++i) {
                bool noData = volume.isNoData(volume.linearIndex(i, j, k));
                auto difference = [&](glm::ivec3 step) {
                    glm::ivec3 a = glm::clamp(glm::ivec3(i, j, k) + step, glm::ivec3(0), dims - 1);
                    glm::ivec3 b = glm::clamp(glm::ivec3(i, j, k) - step, glm::ivec3(0), dims - 1);
                    std::size_t ia = volume.linearIndex(a.x, a.y, a.z), ib = volume.linearIndex(b.x, b.y, b.z);
                    noData = noData || volume.isNoData(ia) || volume.isNoData(ib);
                    return volume.normalized(ia) - volume.normalized(ib);
                };
                glm::dvec3 d(difference({1, 0, 0}), difference({0, 1, 0}), difference({0, 0, 1}));
                if (!noData) largest = std::max(largest, glm::length(toWorld * (0.5 * d)));
            }
    return largest;
}

}  // namespace curette
