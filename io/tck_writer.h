#pragma once
// Streamlines as MRtrix .tck (https://mrtrix.readthedocs.io, "Tracks file format"), the form io/tract_file.h
// reads: the text header
//     mrtrix tracks
//     count: N
//     datatype: Float32LE
//     file: . OFFSET
//     END
// (OFFSET = the header's own length in bytes), then each streamline's points as float32 little-endian x y z
// triplets in scanner-space (world RAS) millimetres, each streamline followed by a NaN triplet, and an Inf
// triplet ending the data (MRtrix writes the same: the NaN after the last streamline, then the Inf).
// .tck has no per-point scalars or per-streamline properties (MRtrix keeps them in .tsf files): they are not
// written. A streamline without points cannot be told apart from none in .tck, so empty streamlines are left
// out and `count` is the number written.

#include "base/tractogram.h"

#include <filesystem>

namespace curette::io {

// Atomic (base/atomic_file.h). InputError(path, "points[n]", ...) for a coordinate that is not finite, and
// InputError(path, "offsets", ...) when the offsets do not describe the points.
void writeTck(const std::filesystem::path& path, const Tractogram& tracts);

}  // namespace curette::io
