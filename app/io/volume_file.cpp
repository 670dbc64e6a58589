// Which reader a volume file needs: by extension, then by its first bytes.
#include "app/io/volume_file.h"

#include "app/io/gzip.h"
#include "app/io/nifti.h"
#include "app/io/nrrd.h"
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
    return VolumeFormat::Auto;
}

}  // namespace

VolumeData readVolume(const std::filesystem::path& path, const VolumeReadOptions& options) {
    std::string name = path.string();
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw InputError(name, "", "an existing volume file", "no such file");
    VolumeFormat format = options.format;
    if (format == VolumeFormat::Auto) {
        if (endsWith(name, ".nii") || endsWith(name, ".nii.gz") || endsWith(name, ".hdr") || endsWith(name, ".hdr.gz"))
            format = VolumeFormat::Nifti;
        else if (endsWith(name, ".nrrd") || endsWith(name, ".nhdr"))
            format = VolumeFormat::Nrrd;
        else if (options.raw)
            format = VolumeFormat::Raw;
        else
            format = sniff(path);
    }
    switch (format) {
        case VolumeFormat::Nifti: return readNifti(path);
        case VolumeFormat::Nrrd: return readNrrd(path);
        case VolumeFormat::Raw:
            if (!options.raw)
                throw InputError(name, "format", "a raw layout (--raw-dims and --raw-type, or the scene's volume.raw)", "none");
            return readRaw(path, *options.raw);
        case VolumeFormat::Auto: break;
    }
    throw InputError(name, "format",
                     "NIfTI-1 (.nii, .nii.gz, .hdr/.img), NRRD (.nrrd, .nhdr) or raw with --raw-dims/--raw-type",
                     "a file curette does not recognise");
}

}  // namespace curette::io
