#pragma once
// Streamlines as TrackVis .trk version 2, the form io/tract_file.h reads back. The TrackVis format page
// (http://trackvis.org/docs/?subsect=fileformat) describes a 1000-byte little- or big-endian header followed
// by the tracks, each an int32 point count, the points (x, y, z and any per-point scalars, float32) and any
// per-track properties (float32). Its points live in "voxmm": voxel coordinates scaled by the voxel size, with
// the origin at the corner of voxel 0; vox_to_ras (version 2) and voxel_order place that grid in the world.
//
// curette writes little-endian, version 2, hdr_size 1000, n_count = the streamlines written (empty ones are
// left out, with their properties: nibabel drops them on reading, so n_count would disagree), voxel_order "RAS", and for the grid the one tract_writing.h derives from
// the points' bounds (1 mm voxels, axes along R, A, S, every point inside). vox_to_ras is that grid's
// voxel-centre affine, the matrix nibabel puts there, so each point is written as
//     voxmm = inverse(vox_to_ras . offset(-1/2) . scale(1 / voxel_size)) . world,
// the inverse of the reader's mapping (io/tract_file.h) with no reorientation (the voxel order is the
// affine's own). Per-point scalars and per-streamline properties are written when the Tractogram has them
// (at most 10 of each, names of at most 20 bytes, as the header holds them).

#include "base/tractogram.h"

#include <filesystem>

namespace curette::io {

// Atomic and streamed (base/atomic_file.h). InputError(path, "points[n]", ...) for a coordinate that is not
// finite, InputError(path, "offsets", ...) when the offsets do not describe the points, and InputError naming
// scalarNames/scalars/propertyNames/properties when those do not fit the header or the points.
void writeTrk(const std::filesystem::path& path, const Tractogram& tracts);

}  // namespace curette::io
