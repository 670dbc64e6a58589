#include "render/model/phong_shading_placement.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace curette {

const char* phongShadingName(PhongShading placement) {
    return placement == PhongShading::InLoop ? "in the loop" : "between rounds";
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
