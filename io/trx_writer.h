#pragma once
// Streamlines as a TRX file (https://github.com/tee-ar-ex/trx-spec), the form io/trx.h reads: an uncompressed
// (stored) zip archive of
//     header.json          DIMENSIONS, VOXEL_TO_RASMM (the reference grid of tract_writing.h), NB_STREAMLINES,
//                          NB_VERTICES
//     offsets.uint64       NB_STREAMLINES + 1 entries, the first vertex of each streamline then NB_VERTICES
//                          (the spec's later form and trx-python's; io/trx.h reads both)
//     positions.3.float32  the points, world millimetres RAS (TRX positions need no transform), little-endian
// Stored, not deflated: the spec prefers it (a reader can map the arrays in place) and a million streamlines
// of float32 hardly compress. float32, not float16: a half has 11 significant bits, about 0.06 mm at 100 mm,
// which is not a round trip. Per-point scalars and per-streamline properties (dpv/, dps/) are not written:
// io/trx.h does not read them.
//
// The zip (PKWARE APPNOTE 4.3) is written without Zip64, so every member and the archive must stay below
// 4 GiB: about 357 million vertices. Beyond that the writer refuses with an InputError before writing.

#include "base/tractogram.h"

#include <filesystem>

namespace curette::io {

// Atomic and streamed (base/atomic_file.h). InputError(path, "points[n]", ...) for a coordinate that is not
// finite, InputError(path, "offsets", ...) when the offsets do not describe the points, and
// InputError(path, "positions.3.float32", ...) when the archive would need Zip64.
void writeTrx(const std::filesystem::path& path, const Tractogram& tracts);

}  // namespace curette::io
