#pragma once
// Counts of a volume's physical values in equal bins over [lo, hi] (a constant volume: everything in bin 0):
// the one binning rule of `curette info`'s histogram (scene/volume_statistics.h) and of the ray caster's phong
// placement (render/model/phong_shading_placement.h).

#include "base/volume.h"

#include <cstdint>
#include <vector>

namespace curette {

struct ValueHistogram {
    double lo = 0, hi = 0;
    std::vector<std::uint64_t> counts;

    static ValueHistogram over(double lo, double hi, int bins);
    // Every voxel of a volume of up to `maxVoxels` voxels and an even stride through a larger one, over
    // [minValue, maxValue]; voxels without data are left out.
    static ValueHistogram of(const VolumeData& volume, int bins, std::size_t maxVoxels);
    void add(double value);
    double binCentre(std::size_t bin) const;
};

}  // namespace curette
