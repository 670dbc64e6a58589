#pragma once
// Tractography import: TrackVis .trk (versions 1 and 2) and MRtrix .tck, into world millimetres RAS.

#include "base/tractogram.h"

#include <filesystem>
#include <span>

namespace curette::io {

// By extension: .trk, .tck, either gzip-compressed (.trk.gz, .tck.gz), or .trx (io/trx.h); a folder is
// read as a TRX folder.
Tractogram readTractogram(const std::filesystem::path& path);
// TrackVis (http://trackvis.org/docs/?subsect=fileformat): a 1000-byte header, then per track n_points,
// n_points x (x, y, z, scalars...) and the track's properties. Points are in "voxmm" (voxel coordinates times
// voxel size, origin at the corner of voxel 0); world = vox_to_ras . orient(voxmm / voxel_size - 0.5), the
// mapping nibabel uses. Version 1 (and version 2 with an all-zero vox_to_ras) has no affine: points are
// taken as millimetres, world = voxmm - voxel_size / 2.
Tractogram readTrkBytes(std::span<const std::uint8_t> bytes, const std::string& source);
// MRtrix (https://mrtrix.readthedocs.io, "Tracks file format"): a text header ending with END, then float32
// or float64 triplets in scanner-space millimetres; a NaN triplet ends a streamline, an Inf triplet the file.
// A header count that disagrees with the data is a warning (MATLAB writers leave it stale); the data is read.
Tractogram readTckBytes(std::span<const std::uint8_t> bytes, const std::string& source);

}  // namespace curette::io
