#pragma once
// The drilled removal (plan/removal_volume.h) as a file: beside a saved scene (its "removal" key) and beside a
// session whose recording started after drilling (its header's "removal"). One NIfTI-1 volume on the scan grid
// (io/nifti_uint64.h: datatype 1280, DT_UINT64), 4-D: dim[4] = 8 words per voxel, x fastest, the word slowest:
// bit i + 8 j of word k is the sub-cell (i, j, k) of the voxel, centred at index + ((i, j, k) + 0.5) / 8 - 0.5
// (plan::VoxelMask). It reads back bit for bit (equal RemovalVolume::digest); the voxel's drilled fraction is
// the set bits / 512.
//
// Files written before the sub-cells were 8 per axis (3-D, one word per voxel: bit i + 4 j + 16 k the sub-cell
// (i, j, k) of 4 per axis) still load: each old sub-cell becomes the 2 x 2 x 2 new ones it is made of (the
// same region, the same fractions). A session header's digest of such a file is the old one (of the words).

#include "plan/removal_volume.h"
#include "session/loaded_scene.h"
#include "session/session.h"

#include <filesystem>
#include <memory>
#include <string>

namespace curette {

// "<stem>.removal.nii.gz" beside `owner` (a scene or session file): "plan.json" -> "plan.removal.nii.gz".
std::filesystem::path removalFileBeside(const std::filesystem::path& owner);

// Atomic; throws SystemError when it cannot be written.
void writeRemovalFile(const std::filesystem::path& path, const plan::RemovalVolume& removal);

// The removal a file holds, for a scan of `dims` and `indexToWorld`. Throws InputError naming the file and the
// field (dim, srow, datatype, ...) and the expected form when it is missing or not on that grid; `referrer`
// and `key` (the scene or session file and its key) are named when the file does not exist.
// `fileDigest`, when given, receives the digest of the removal as the file has it: RemovalVolume::digest,
// or for a file of 4 x 4 x 4 bits the digest version 6 wrote then (of each drilled voxel's index and word).
std::shared_ptr<plan::RemovalVolume> readRemovalFile(const std::filesystem::path& path, glm::ivec3 dims, const glm::dmat4& indexToWorld,
                                                     const std::string& referrer, const std::string& key, std::string* fileDigest = nullptr);

// The removal a session starts from: from version 6 its header's (the file beside the session file, its digest
// checked; none: nothing drilled), before that the scene's.
std::shared_ptr<const plan::RemovalVolume> sessionStartRemoval(const Session& session, const LoadedScene& loaded);

}  // namespace curette
