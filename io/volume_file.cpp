// Which reader a volume file needs: by extension, then by its first bytes.
#include "io/volume_file.h"

#include "io/dicom.h"
#include "io/gzip.h"
#include "io/metaimage.h"
#include "io/nifti.h"
#include "io/nrrd.h"
#include "base/error.h"

#include <cstring>
#include <fstream>

namespace curette::io {

namespace {

bool endsWith(const std::string& s, const std::string& suffix) {
    if (s.size() < suffix.size()) return false;
    for (std::size_t i = 0; i < suffix.size(); ++i)
        if (std::tolower(static_cast<unsigned char>(s[s.size() - suffix.size() + i])) != suffix[i]) return false;
    return true;
}

VolumeFormat sniff(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    char head[352] = {};
    in.read(head, sizeof head);
    std::streamsize n = in.gcount();
    if (n >= 4 && std::memcmp(head, "NRRD", 4) == 0) return VolumeFormat::Nrrd;
    if (n >= 2 && static_cast<unsigned char>(head[0]) == 0x1f && static_cast<unsigned char>(head[1]) == 0x8b) return VolumeFormat::Nifti;
    if (n >= 348 && (std::memcmp(head + 344, "n+1", 4) == 0 || std::memcmp(head + 344, "ni1", 4) == 0)) return VolumeFormat::Nifti;
    // NIfTI-2 (nifti2.h): the magic follows the 4-byte sizeof_hdr.
    if (n >= 8 && (std::memcmp(head + 4, "n+2", 4) == 0 || std::memcmp(head + 4, "ni2", 4) == 0)) return VolumeFormat::Nifti;
    // MetaImage headers are text; NDims or ObjectType usually comes first (MetaIO metaObject.cxx).
    if (n >= 5 && (std::memcmp(head, "NDims", 5) == 0 || (n >= 10 && std::memcmp(head, "ObjectType", 10) == 0))) return VolumeFormat::MetaImage;
    if (n >= 132 && std::memcmp(head + 128, "DICM", 4) == 0) return VolumeFormat::Dicom;  // PS3.10 7.1 preamble + prefix
    return VolumeFormat::Auto;
}

}  // namespace

namespace {

VolumeData readAs(VolumeFormat format, const std::filesystem::path& path, const VolumeReadOptions& options) {
    switch (format) {
        case VolumeFormat::Nifti: return readNifti(path, options.volumeIndex);
        case VolumeFormat::Nrrd: return readNrrd(path);
        case VolumeFormat::Raw:
            if (!options.raw)
                throw InputError(path.string(), "format", "a raw layout (--raw-dims and --raw-type, or the scene's volume.raw)", "none");
            return readRaw(path, *options.raw);
        case VolumeFormat::Dicom: return readDicomSeries(path, options);
        case VolumeFormat::MetaImage: return readMetaImage(path, options.volumeIndex);
        case VolumeFormat::Auto: break;
    }
    throw InputError(path.string(), "format",
                     "NIfTI-1/-2 (.nii, .nii.gz, .hdr/.img), NRRD (.nrrd, .nhdr), MetaImage (.mha, .mhd), DICOM (a folder, .dcm) or raw with --raw-dims/--raw-type",
                     "a file curette does not recognise");
}

}  // namespace

VolumeData readVolume(const std::filesystem::path& path, const VolumeReadOptions& options) {
    std::string name = path.string();
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw InputError(name, "", "an existing volume file", "no such file");
    VolumeFormat format = options.format;
    if (format == VolumeFormat::Auto) {
        if (std::filesystem::is_directory(path, ec) || endsWith(name, ".dcm"))
            format = VolumeFormat::Dicom;
        else if (endsWith(name, ".nii") || endsWith(name, ".nii.gz") || endsWith(name, ".hdr") || endsWith(name, ".hdr.gz"))
            format = VolumeFormat::Nifti;
        else if (endsWith(name, ".nrrd") || endsWith(name, ".nhdr"))
            format = VolumeFormat::Nrrd;
        else if (endsWith(name, ".mha") || endsWith(name, ".mhd"))
            format = VolumeFormat::MetaImage;
        else if (options.raw)
            format = VolumeFormat::Raw;
        else
            format = sniff(path);
    }
    VolumeData volume = readAs(format, path, options);
    if (volume.files.empty()) volume.files = {path};   // a reader of one file leaves it to here
    return volume;
}

}  // namespace curette::io
