#include "render/model/phong_shading_placement.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace curette {

const char* phongShadingName(PhongShading placement) {
    return placement == PhongShading::InLoop ? "in the loop" : "between rounds";
}

double ValueHistogram::binCentre(std::size_t bin) const {
    return lo + (hi - lo) * (static_cast<double>(bin) + 0.5) / static_cast<double>(counts.size());
}

ValueHistogram ValueHistogram::of(const VolumeData& volume, int bins, std::size_t maxVoxels) {
    ValueHistogram h;
    h.lo = volume.minValue;
    h.hi = volume.maxValue;
    h.counts.assign(static_cast<std::size_t>(std::max(bins, 1)), 0);
    const std::size_t n = volume.voxelCount();
    const std::size_t stride = std::max<std::size_t>(1, (n + maxVoxels - 1) / std::max<std::size_t>(maxVoxels, 1));
    const double width = h.hi - h.lo;
    for (std::size_t i = 0; i < n; i += stride) {
        if (volume.isNoData(i)) continue;
        double value = volume.valueScale * volume.normalized(i) + volume.valueOffset;
        double unit = width > 0 ? (value - h.lo) / width : 0.0;
        auto bin = static_cast<std::size_t>(std::clamp(unit * static_cast<double>(h.counts.size()), 0.0,
                                                       static_cast<double>(h.counts.size() - 1)));
        ++h.counts[bin];
    }
    return h;
}

double medianVisibleExtinctionPerMm(const ValueHistogram& histogram, const TransferFunction& tf) {
    std::vector<std::pair<double, std::uint64_t>> visible;   // extinction per mm, voxels
    std::uint64_t total = 0;
    for (std::size_t bin = 0; bin < histogram.counts.size(); ++bin) {
        double opacity = tf.evaluateOpacity(histogram.binCentre(bin));
        if (opacity <= 0.0 || histogram.counts[bin] == 0) continue;
        double extinction = opacity >= 1.0 ? std::numeric_limits<double>::infinity() : -std::log1p(-opacity) / tf.unitLengthMm;
        visible.emplace_back(extinction, histogram.counts[bin]);
        total += histogram.counts[bin];
    }
    if (total == 0) return 0.0;
    std::sort(visible.begin(), visible.end());
    std::uint64_t seen = 0;
    for (const auto& [extinction, count] : visible)
        if ((seen += count) * 2 >= total) return extinction;
    return visible.back().first;
}

PhongShading phongShadingPlacement(double medianExtinctionPerMm, double earlyTerminationAlpha, double meanExtentMm) {
    if (!(medianExtinctionPerMm > 0.0)) return PhongShading::BetweenRounds;   // nothing visible: no round ever stops
    double terminationMm = -std::log1p(-std::min(earlyTerminationAlpha, 1.0 - 1e-9)) / medianExtinctionPerMm;
    return terminationMm < 0.5 * meanExtentMm ? PhongShading::BetweenRounds : PhongShading::InLoop;
}

}  // namespace curette
