#pragma once
// Summary statistics of a volume's physical values, for `curette info`; voxels without data (NaN/Inf) are
// left out of all of them (VolumeData::noDataVoxels counts them).

#include "base/volume.h"
#include "render/model/slice_view.h"

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

// The slice views' grey window (render/model/slice_view.h), one rule for the viewer and `render --slices`:
// the 1st to the 99th percentile of the data values; min to max when those agree; value +-0.5 for a
// constant volume.
GreyWindow defaultGreyWindow(const VolumeStatistics& statistics);

// The largest gradient magnitude (physical value per mm) over the voxels, by the ray caster's own central
// differences (render/reference/raycast_reference.cpp at a voxel centre: the neighbours along i, j and k,
// clamped at the edges, through VolumeGeometry::gradientIndexToWorld): the range of the TF editor's
// gradient-opacity curve. Voxels without data, and differences that reach one, are left out; 0 for a
// constant volume.
double maxGradientMagnitude(const VolumeData& volume);

}  // namespace curette
