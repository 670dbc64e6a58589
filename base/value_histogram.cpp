#include "base/value_histogram.h"

#include <algorithm>

namespace curette {

ValueHistogram ValueHistogram::over(double lo, double hi, int bins) {
    ValueHistogram h;
    h.lo = lo;
    h.hi = hi;
    h.counts.assign(static_cast<std::size_t>(std::max(bins, 1)), 0);
    return h;
}

ValueHistogram ValueHistogram::of(const VolumeData& volume, int bins, std::size_t maxVoxels) {
    ValueHistogram h = over(volume.minValue, volume.maxValue, bins);
    const std::size_t n = volume.voxelCount();
    const std::size_t stride = std::max<std::size_t>(1, (n + maxVoxels - 1) / std::max<std::size_t>(maxVoxels, 1));
    for (std::size_t i = 0; i < n; i += stride)
        if (!volume.isNoData(i)) h.add(volume.valueScale * volume.normalized(i) + volume.valueOffset);
    return h;
}

void ValueHistogram::add(double value) {
    const int bins = static_cast<int>(counts.size());
    const double span = hi > lo ? hi - lo : 1.0;
    ++counts[static_cast<std::size_t>(std::clamp(static_cast<int>((value - lo) / span * bins), 0, bins - 1))];
}

double ValueHistogram::binCentre(std::size_t bin) const {
    return lo + (hi - lo) * (static_cast<double>(bin) + 0.5) / static_cast<double>(counts.size());
}

}  // namespace curette
