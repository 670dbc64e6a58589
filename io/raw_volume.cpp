// Headerless raw volumes: the layout comes from the command line or the scene (RawLayout).
#include "io/gzip.h"
#include "io/volume_file.h"
#include "base/atomic_file.h"
#include "base/error.h"

#include <cmath>

namespace curette::io {

VolumeData readRaw(const std::filesystem::path& path, const RawLayout& layout) {
    std::string source = path.string();
    for (int a = 0; a < 3; ++a) {
        if (layout.dims[a] < 1)
            throw InputError(source, "raw dims", "three positive sizes", std::to_string(layout.dims[a]));
        if (!(layout.spacing[a] > 0.0) || !std::isfinite(layout.spacing[a]))
            throw InputError(source, "raw spacing", "three positive voxel sizes in mm", std::to_string(layout.spacing[a]));
    }
    std::uint64_t expected = static_cast<std::uint64_t>(layout.dims.x) * static_cast<std::uint64_t>(layout.dims.y) *
                             static_cast<std::uint64_t>(layout.dims.z) * scalarTypeSize(layout.type);
    std::vector<std::uint8_t> bytes = readFileBytes(path);
    if (layout.gzip || isGzip(bytes)) bytes = gunzip(bytes, source, layout.headerBytes + expected + 1);
    if (bytes.size() != layout.headerBytes + expected)
        throw InputError(source, "size", std::to_string(layout.headerBytes + expected) + " bytes (" + std::to_string(layout.headerBytes) +
                                             " header + " + std::to_string(layout.dims.x) + "x" + std::to_string(layout.dims.y) + "x" +
                                             std::to_string(layout.dims.z) + " " + scalarTypeName(layout.type) + ")",
                         std::to_string(bytes.size()) + " bytes");
    glm::dmat4 affine(1.0);
    for (int a = 0; a < 3; ++a) affine[a][a] = layout.spacing[a];
    affine[3] = glm::dvec4(layout.origin, 1.0);
    return buildVolume(source, layout.dims, layout.type, bytes.data() + layout.headerBytes, layout.bigEndian, 1.0, 0.0, affine);
}

}  // namespace curette::io
