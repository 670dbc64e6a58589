#pragma once
// Summary statistics of a volume's physical values, for `curette info`; voxels without data (NaN/Inf) are
// left out of all of them (VolumeData::noDataVoxels counts them).

#include "base/volume.h"

#include <array>
#include <vector>

namespace curette {

struct VolumeStatistics {
    double min = 0, max = 0, mean = 0, standardDeviation = 0;
    double nonZeroFraction = 0;                       // voxels != 0 (physical value)
    std::array<double, 5> percentiles{};              // 1, 25, 50, 75, 99 %: data values (nearest rank)
    std::vector<std::uint64_t> histogram;             // `bins` equal bins over [min, max]
};

VolumeStatistics computeStatistics(const VolumeData& volume, int bins = 16);

}  // namespace curette
