#pragma once
// Volume import: NIfTI-1 and NIfTI-2 (.nii, .nii.gz, .hdr/.img; one 3-D volume of a 4-D/5-D file), NRRD
// (.nrrd attached, .nhdr detached; raw and gzip; both endians), MetaImage (.mha, .mhd) and raw files whose
// layout is given on the command line. Every reader keeps the index-to-world affine and
// throws InputError naming the file, the header field and the expected form on bad input.

#include "base/volume.h"

#include <filesystem>
#include <optional>
#include <string>

namespace curette::io {

// Layout of a headerless raw file (`--raw-dims` etc. on the command line, or the scene's volume.raw).
struct RawLayout {
    glm::ivec3 dims{0};
    ScalarType type = ScalarType::UInt8;
    bool bigEndian = false;
    glm::dvec3 spacing{1.0};
    glm::dvec3 origin{0.0};
    std::uint64_t headerBytes = 0;  // bytes to skip before the samples
    bool gzip = false;              // the whole file is gzip-compressed
};

enum class VolumeFormat { Auto, Nifti, Nrrd, Raw, MetaImage, Dicom };

struct VolumeReadOptions {
    VolumeFormat format = VolumeFormat::Auto;  // Auto: by extension, then by magic bytes; a directory is DICOM
    std::optional<RawLayout> raw;              // required for Raw
    int volumeIndex = 0;                       // 4-D/5-D files: which 3-D volume (0-based; `--volume N`, scene volume.index)
    std::string series;                        // DICOM: the series to open, by number or SeriesInstanceUID ("": the one
                                               // curette would pick, see io/dicom.h)
    bool showIdentifiers = false;              // DICOM: patient name and ids may be printed (`--show-identifiers`)
};

VolumeData readVolume(const std::filesystem::path& path, const VolumeReadOptions& options = {});

VolumeData readNifti(const std::filesystem::path& path, int volumeIndex);  // io/nifti.h (default 0 there)
VolumeData readNrrd(const std::filesystem::path& path);
VolumeData readRaw(const std::filesystem::path& path, const RawLayout& layout);

}  // namespace curette::io
