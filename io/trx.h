#pragma once
// TRX tractograms (https://github.com/tee-ar-ex/trx-spec): a zip archive (stored or deflated) or a folder of
// little-endian C-order arrays named `name[.cols].dtype`, with a JSON header. curette reads the streamlines:
// header.json (VOXEL_TO_RASMM, DIMENSIONS, NB_STREAMLINES, NB_VERTICES), positions.3.float16|float32|float64
// (already world millimetres RAS, so VOXEL_TO_RASMM is checked but not applied) and offsets.uint32|uint64,
// the first vertex of each streamline. The spec versions disagree on the length of offsets (bf1ae219:
// NB_STREAMLINES entries; 1e877afd and trx-python: one more, a final NB_VERTICES sentinel), so both are
// read. dpv/, dps/, groups/ and dpg/ (per-vertex, per-streamline and group data) are ignored.

#include "base/tractogram.h"

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

namespace curette::io {

// A .trx zip file, or a TRX folder (the same members as files).
Tractogram readTrx(const std::filesystem::path& path);
// The bytes of a .trx zip; `source` names it in errors.
Tractogram readTrxZipBytes(std::span<const std::uint8_t> bytes, const std::string& source);

}  // namespace curette::io
