#pragma once
// NRRD (http://teem.sourceforge.net/nrrd/format.html): attached .nrrd and detached .nhdr headers; raw, gzip
// and ascii encodings; either endianness; `space directions`/`space origin` kept as the index-to-world
// affine (LPS and LAS spaces converted to RAS), `spacings` as the fallback.

#include "base/volume.h"

#include <filesystem>
#include <span>

namespace curette::io {

VolumeData readNrrd(const std::filesystem::path& path);
// An attached NRRD from memory (`baseDirectory` resolves a detached data file): the fuzzing entry point.
VolumeData readNrrdBytes(std::span<const std::uint8_t> bytes, const std::string& source,
                         const std::filesystem::path& baseDirectory);

}  // namespace curette::io
