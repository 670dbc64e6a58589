#include "io/nifti.h"

#include "io/gzip.h"
#include "base/atomic_file.h"
#include "base/error.h"
#include "base/log.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>

namespace curette::io {

namespace {

// NIfTI-1 (nifti1.h) and NIfTI-2 (nifti2.h, NIFTI-Imaging/nifti_clib) carry the same fields at different offsets and widths;
// each layout is read into HeaderFields and everything after that (dims, datatype, scaling, the affine, the
// data offset) is one code path.
constexpr std::size_t kHeaderSize1 = 348;          // sizeof_hdr of NIfTI-1
constexpr std::size_t kHeaderSize2 = 540;          // sizeof_hdr of NIfTI-2
constexpr std::size_t kLargestHeader = kHeaderSize2 + 4;
constexpr std::size_t kSingleFileMinOffset1 = 352; // header + 4-byte extension flag
constexpr std::size_t kSingleFileMinOffset2 = 544;

// Field reader over the header bytes, swapping bytes when the file's endianness differs.
class Header {
public:
    Header(std::span<const std::uint8_t> bytes, bool swap) : bytes_(bytes), swap_(swap) {}
    template <typename T>
    T get(std::size_t offset) const {
        std::uint8_t raw[sizeof(T)];
        std::memcpy(raw, bytes_.data() + offset, sizeof(T));
        if (swap_)
            for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
        T value;
        std::memcpy(&value, raw, sizeof(T));
        return value;
    }
    std::int64_t i16(std::size_t o) const { return get<std::int16_t>(o); }
    std::int64_t i32(std::size_t o) const { return get<std::int32_t>(o); }
    std::int64_t i64(std::size_t o) const { return get<std::int64_t>(o); }
    double f32(std::size_t o) const { return get<float>(o); }
    double f64(std::size_t o) const { return get<double>(o); }

private:
    std::span<const std::uint8_t> bytes_;
    bool swap_;
};

// The header fields curette uses, widened to NIfTI-2's types (NIfTI-1's int16 and float32 convert exactly).
struct HeaderFields {
    int version = 1;
    bool swap = false;
    bool pair = false;  // "ni1"/"ni2": data in the .img file
    std::int64_t dim[8] = {};
    std::int64_t intentCode = 0, datatype = 0, bitpix = 0;
    double pixdim[8] = {};
    double voxOffset = 0;
    double sclSlope = 0, sclInter = 0;
    int xyztUnits = 0;
    std::int64_t qformCode = 0, sformCode = 0;
    double quatern[3] = {}, qoffset[3] = {};
    double srow[12] = {};  // srow_x, srow_y, srow_z
};

std::int32_t bswap32(std::int32_t v) { return static_cast<std::int32_t>(__builtin_bswap32(static_cast<std::uint32_t>(v))); }

HeaderFields readFields(std::span<const std::uint8_t> bytes, const std::string& source) {
    if (bytes.size() < 4)
        throw InputError(source, "header", "a NIfTI-1 (348-byte) or NIfTI-2 (540-byte) header", std::to_string(bytes.size()) + " bytes");
    std::int32_t size;
    std::memcpy(&size, bytes.data(), 4);
    HeaderFields f;
    // Endianness from sizeof_hdr, for both versions (nifti2.h NIFTI2_NEEDS_SWAP; nifti1.h tests dim[0] instead,
    // which agrees on every valid file).
    if (size == 348 || bswap32(size) == 348) f.version = 1, f.swap = size != 348;
    else if (size == 540 || bswap32(size) == 540) f.version = 2, f.swap = size != 540;
    else throw InputError(source, "sizeof_hdr", "348 (NIfTI-1) or 540 (NIfTI-2)", std::to_string(size));
    std::size_t headerSize = f.version == 1 ? kHeaderSize1 : kHeaderSize2;
    if (bytes.size() < headerSize)
        throw InputError(source, "header", "a NIfTI-" + std::to_string(f.version) + " header of " + std::to_string(headerSize) + " bytes",
                         std::to_string(bytes.size()) + " bytes");
    Header h(bytes, f.swap);
    if (f.version == 1) {
        // nifti1.h: magic at 344, "n+1\0" single file, "ni1\0" header/image pair.
        const std::uint8_t* magic = bytes.data() + 344;
        if (std::memcmp(magic, "n+1\0", 4) == 0) f.pair = false;
        else if (std::memcmp(magic, "ni1\0", 4) == 0) f.pair = true;
        else
            throw InputError(source, "magic", "\"n+1\" (single file) or \"ni1\" (.hdr/.img pair)",
                             std::all_of(magic, magic + 4, [](std::uint8_t c) { return c == 0; })
                                 ? "none: an ANALYZE 7.5 header, whose orientation is undefined (convert it to NIfTI)"
                                 : "other bytes");
        for (std::size_t i = 0; i < 8; ++i) f.dim[i] = h.i16(40 + 2 * i);
        f.intentCode = h.i16(68);
        f.datatype = h.i16(70), f.bitpix = h.i16(72);
        for (std::size_t i = 0; i < 8; ++i) f.pixdim[i] = h.f32(76 + 4 * i);
        f.voxOffset = h.f32(108);
        f.sclSlope = h.f32(112), f.sclInter = h.f32(116);
        f.xyztUnits = bytes[123];
        f.qformCode = h.i16(252), f.sformCode = h.i16(254);
        for (std::size_t i = 0; i < 3; ++i) f.quatern[i] = h.f32(256 + 4 * i), f.qoffset[i] = h.f32(268 + 4 * i);
        for (std::size_t i = 0; i < 12; ++i) f.srow[i] = h.f32(280 + 4 * i);
    } else {
        // nifti2.h: magic at 4, "n+2\0" or "ni2\0" followed by "\r\n\032\n", which catches a file damaged by a
        // text-mode transfer (line-ending translation).
        const std::uint8_t* magic = bytes.data() + 4;
        if (std::memcmp(magic, "n+2\0\r\n\032\n", 8) == 0) f.pair = false;
        else if (std::memcmp(magic, "ni2\0\r\n\032\n", 8) == 0) f.pair = true;
        else throw InputError(source, "magic", "\"n+2\\0\\r\\n\\032\\n\" (single file) or \"ni2\\0\\r\\n\\032\\n\" (.hdr/.img pair)", "other bytes");
        f.datatype = h.i16(12), f.bitpix = h.i16(14);
        for (std::size_t i = 0; i < 8; ++i) f.dim[i] = h.i64(16 + 8 * i);
        for (std::size_t i = 0; i < 8; ++i) f.pixdim[i] = h.f64(104 + 8 * i);
        // vox_offset is int64 in NIfTI-2 (offset 168); as a double it is exact up to 2^53, far past the 1e15 limit.
        f.voxOffset = static_cast<double>(h.i64(168));
        f.sclSlope = h.f64(176), f.sclInter = h.f64(184);
        f.qformCode = h.i32(344), f.sformCode = h.i32(348);
        for (std::size_t i = 0; i < 3; ++i) f.quatern[i] = h.f64(352 + 8 * i), f.qoffset[i] = h.f64(376 + 8 * i);
        for (std::size_t i = 0; i < 12; ++i) f.srow[i] = h.f64(400 + 8 * i);
        f.xyztUnits = static_cast<int>(h.i32(500) & 0xff);
        f.intentCode = h.i32(504);
    }
    return f;
}

struct ParsedHeader {
    int version = 1;
    glm::ivec3 dims{0};
    ScalarType type = ScalarType::UInt8;
    double slope = 1.0, intercept = 0.0;
    glm::dmat4 affine{1.0};
    std::uint64_t dataOffset = 0;   // of the first volume
    std::uint64_t volumeBytes = 0;  // of one 3-D volume
    int volumeCount = 1;            // dim[4] * dim[5]
    bool bigEndian = false;
    bool pair = false;  // "ni1"/"ni2": data in the .img file

    // Bytes from the start of the data file up to the end of volume `index`.
    std::uint64_t bytesThrough(int index) const { return dataOffset + static_cast<std::uint64_t>(index + 1) * volumeBytes; }
};

// Everything after the layout: one definition for both versions.
ParsedHeader interpret(const HeaderFields& f, const std::string& source) {
    ParsedHeader p;
    p.version = f.version;
    p.pair = f.pair;
    p.bigEndian = (std::endian::native == std::endian::little) == f.swap;

    // CIFTI-2 (NIfTI-2 with intent codes 3000-3099, e.g. 3001 ConnDense) stores matrices over surface vertices
    // and parcels in dims 5-7, not a volume.
    if (f.intentCode >= 3000 && f.intentCode <= 3099)
        throw InputError(source, "intent_code", "a volume (intent codes 3000-3099 are CIFTI-2 matrices over surfaces and parcels, not volumes)",
                         std::to_string(f.intentCode));

    // dim[0] is the number of dimensions; dims 1-3 are space, 4 time, 5 (e.g. vector components) a further
    // index: curette reads one 3-D volume of up to dim[4] * dim[5]. dim[i] for i > dim[0] is ignored (nifti1.h).
    std::int64_t rank = f.dim[0];
    if (rank < 1 || rank > 7) throw InputError(source, "dim[0]", "a number of dimensions in 1..7", std::to_string(rank));
    // 2^24 voxels per axis: far above any GL_MAX_3D_TEXTURE_SIZE, and int-sized.
    constexpr std::int64_t kMaxAxis = std::int64_t(1) << 24;
    for (int i = 1; i <= 3; ++i) {
        std::int64_t d = i <= rank ? f.dim[i] : 1;
        if (d < 1 || d > kMaxAxis)
            throw InputError(source, "dim[" + std::to_string(i) + "]", "a size in 1.." + std::to_string(kMaxAxis), std::to_string(d));
        p.dims[i - 1] = static_cast<int>(d);
    }
    std::int64_t count = 1;
    for (int i = 4; i <= 5 && i <= rank; ++i) {
        std::int64_t d = f.dim[i];
        if (d < 1 || d > (std::int64_t(1) << 30))
            throw InputError(source, "dim[" + std::to_string(i) + "]", "a count of volumes in 1..2^30", std::to_string(d));
        count *= d;
    }
    if (count > (std::int64_t(1) << 30))
        throw InputError(source, "dim[4]*dim[5]", "at most 2^30 volumes", std::to_string(count));
    p.volumeCount = static_cast<int>(count);
    for (int i = 6; i <= rank; ++i)
        if (f.dim[i] != 1)
            throw InputError(source, "dim[" + std::to_string(i) + "]", "1 (curette reads the 3-D volumes of files with up to 5 dimensions)",
                             std::to_string(f.dim[i]));

    int expectedBits = 0;
    switch (f.datatype) {
        case 2: p.type = ScalarType::UInt8, expectedBits = 8; break;
        case 4: p.type = ScalarType::Int16, expectedBits = 16; break;
        case 8: p.type = ScalarType::Int32, expectedBits = 32; break;
        case 16: p.type = ScalarType::Float32, expectedBits = 32; break;
        case 64: p.type = ScalarType::Float64, expectedBits = 64; break;
        case 512: p.type = ScalarType::UInt16, expectedBits = 16; break;
        default:
            throw InputError(source, "datatype", "one of 2 (uint8), 4 (int16), 512 (uint16), 8 (int32), 16 (float32), 64 (float64)",
                             std::to_string(f.datatype));
    }
    if (f.bitpix != expectedBits)
        throw InputError(source, "bitpix", std::to_string(expectedBits) + " for datatype " + std::to_string(f.datatype),
                         std::to_string(f.bitpix));

    // scl_slope 0 (or not finite) means "no scaling" (nifti1.h); the MNI templates store NaN.
    if (f.sclSlope != 0.0 && std::isfinite(f.sclSlope)) {
        p.slope = f.sclSlope;
        p.intercept = std::isfinite(f.sclInter) ? f.sclInter : 0.0;
    }

    // Spatial units (xyzt_units bits 0-2): metres and micrometres convert to millimetres; unknown is mm.
    int units = f.xyztUnits & 0x07;
    double toMm = units == 1 ? 1000.0 : units == 3 ? 1e-3 : 1.0;
    glm::dvec3 pixdim(f.pixdim[1], f.pixdim[2], f.pixdim[3]);
    for (int a = 0; a < 3; ++a) {
        if (!std::isfinite(pixdim[a])) throw InputError(source, "pixdim[" + std::to_string(a + 1) + "]", "a finite voxel size");
        if (pixdim[a] <= 0.0) pixdim[a] = 1.0;  // unset sizes: treat as 1 (nifti1.h method 1 assumes > 0)
    }
    if (f.sformCode > 0) {
        // METHOD 3: the general affine, rows srow_x, srow_y, srow_z.
        glm::dmat4 m(1.0);
        for (int row = 0; row < 3; ++row)
            for (int col = 0; col < 4; ++col) {
                double v = f.srow[4 * row + col];
                if (!std::isfinite(v)) throw InputError(source, "srow", "finite sform coefficients");
                m[col][row] = v;
            }
        p.affine = m;
    } else if (f.qformCode > 0) {
        for (int i = 0; i < 3; ++i)
            if (!std::isfinite(f.quatern[i]) || !std::isfinite(f.qoffset[i]))
                throw InputError(source, "quatern/qoffset", "finite qform parameters");
        p.affine = niftiQformAffine(f.quatern[0], f.quatern[1], f.quatern[2], f.pixdim[0], pixdim,
                                    {f.qoffset[0], f.qoffset[1], f.qoffset[2]});
    } else {
        // METHOD 1 (ANALYZE 7.5 compatibility): scaling only.
        p.affine = glm::dmat4(1.0);
        for (int a = 0; a < 3; ++a) p.affine[a][a] = pixdim[a];
    }
    for (int col = 0; col < 4; ++col)
        for (int row = 0; row < 3; ++row) p.affine[col][row] *= toMm;
    if (std::abs(glm::determinant(glm::dmat3(p.affine))) < 1e-12)
        throw InputError(source, f.sformCode > 0 ? "srow" : "pixdim", "an invertible index-to-world transform", "a singular one");

    double offset = f.voxOffset;
    if (!std::isfinite(offset) || offset < 0 || offset > 1e15)
        throw InputError(source, "vox_offset", "a byte offset in [0, 1e15]", std::to_string(offset));
    p.dataOffset = static_cast<std::uint64_t>(offset);
    std::uint64_t minOffset = f.version == 1 ? kSingleFileMinOffset1 : kSingleFileMinOffset2;
    if (!p.pair && p.dataOffset < minOffset) {
        // The MNI templates of mricron-data store 0; the data still starts after header and extension flag.
        log::warn(source + ": vox_offset " + std::to_string(p.dataOffset) + " is below " + std::to_string(minOffset) +
                  " for a single-file NIfTI-" + std::to_string(f.version) + "; using " + std::to_string(minOffset));
        p.dataOffset = minOffset;
    }
    // Three axes of up to 2^24 could overflow 64 bits; bound the voxel count by 2^50 first.
    std::uint64_t voxels = static_cast<std::uint64_t>(p.dims.x) * static_cast<std::uint64_t>(p.dims.y);
    if (voxels > (std::uint64_t(1) << 50) / static_cast<std::uint64_t>(p.dims.z))
        throw InputError(source, "dim[1..3]", "a volume of at most 2^50 voxels",
                         std::to_string(p.dims.x) + "x" + std::to_string(p.dims.y) + "x" + std::to_string(p.dims.z));
    voxels *= static_cast<std::uint64_t>(p.dims.z);
    p.volumeBytes = voxels * scalarTypeSize(p.type);
    // bytesThrough(any index) must not overflow: all volumes together within 2^62 bytes.
    if (static_cast<std::uint64_t>(p.volumeCount) > ((std::uint64_t(1) << 62) - p.dataOffset) / p.volumeBytes)
        throw InputError(source, "dim", "at most 2^62 bytes of voxels in all volumes", std::to_string(p.volumeCount) + " volumes of " +
                                                                                           std::to_string(p.volumeBytes) + " bytes");
    return p;
}

ParsedHeader parseHeader(std::span<const std::uint8_t> bytes, const std::string& source) {
    return interpret(readFields(bytes, source), source);
}

// The 0-based volume of a 4-D/5-D file, checked against its count (`--volume N`, scene volume.index).
void checkVolumeIndex(const ParsedHeader& p, int index, const std::string& source) {
    if (index < 0 || index >= p.volumeCount)
        throw InputError(source, "--volume / volume.index",
                         "a volume index in 0.." + std::to_string(p.volumeCount - 1) + " (the file holds " +
                             std::to_string(p.volumeCount) + (p.volumeCount == 1 ? " volume)" : " volumes)"),
                         std::to_string(index));
}

// `data` starts at the data offset (vox_offset); volume `index` follows `index` whole volumes.
VolumeData build(const ParsedHeader& p, std::span<const std::uint8_t> data, int index, const std::string& source,
                 const std::string& dataSource) {
    std::uint64_t start = static_cast<std::uint64_t>(index) * p.volumeBytes;
    if (data.size() < start + p.volumeBytes)
        throw InputError(dataSource, "data",
                         std::to_string(p.volumeBytes) + " bytes of voxels (" + std::to_string(p.dims.x) + "x" +
                             std::to_string(p.dims.y) + "x" + std::to_string(p.dims.z) + " " + scalarTypeName(p.type) + ")" +
                             (p.volumeCount > 1 ? " for volume " + std::to_string(index) + " of " + std::to_string(p.volumeCount) : ""),
                         std::to_string(data.size() > start ? data.size() - start : 0) + " bytes");
    VolumeData volume = buildVolume(source, p.dims, p.type, data.data() + start, p.bigEndian, p.slope, p.intercept, p.affine);
    volume.volumeCount = p.volumeCount;
    volume.volumeIndex = index;
    return volume;
}

bool endsWith(const std::string& s, const std::string& suffix) {
    return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

glm::dmat4 niftiQformAffine(double b, double c, double d, double qfac, glm::dvec3 pixdim, glm::dvec3 offset) {
    // nifti1.h METHOD 2: a = sqrt(1 - b^2 - c^2 - d^2) (0 and renormalise when rounding pushes it negative).
    double a2 = 1.0 - (b * b + c * c + d * d);
    double a = 0.0;
    if (a2 > 1e-7) {
        a = std::sqrt(a2);
    } else {
        double n = std::sqrt(b * b + c * c + d * d);
        if (n > 0) b /= n, c /= n, d /= n;
    }
    glm::dmat3 r;
    r[0] = glm::dvec3(a * a + b * b - c * c - d * d, 2 * (b * c + a * d), 2 * (b * d - a * c));
    r[1] = glm::dvec3(2 * (b * c - a * d), a * a + c * c - b * b - d * d, 2 * (c * d + a * b));
    r[2] = glm::dvec3(2 * (b * d + a * c), 2 * (c * d - a * b), a * a + d * d - c * c - b * b);
    // pixdim[0] should be +1 or -1; nifti1_io reads any negative value as -1 and anything else (zero too) as +1.
    qfac = qfac < 0.0 ? -1.0 : 1.0;
    glm::dmat4 m(1.0);
    m[0] = glm::dvec4(r[0] * pixdim.x, 0.0);
    m[1] = glm::dvec4(r[1] * pixdim.y, 0.0);
    m[2] = glm::dvec4(r[2] * (pixdim.z * qfac), 0.0);
    m[3] = glm::dvec4(offset, 1.0);
    return m;
}

VolumeData readNiftiBytes(std::span<const std::uint8_t> bytes, const std::string& source, int volumeIndex) {
    ParsedHeader p = parseHeader(bytes, source);
    if (p.pair)
        throw InputError(source, "magic", p.version == 1 ? "\"n+1\" for a single-file NIfTI" : "\"n+2\" for a single-file NIfTI",
                         p.version == 1 ? "\"ni1\" (a .hdr/.img pair)" : "\"ni2\" (a .hdr/.img pair)");
    checkVolumeIndex(p, volumeIndex, source);
    if (p.dataOffset > bytes.size())
        throw InputError(source, "vox_offset", "an offset inside the file (" + std::to_string(bytes.size()) + " bytes)",
                         std::to_string(p.dataOffset));
    return build(p, bytes.subspan(p.dataOffset), volumeIndex, source, source);
}

VolumeData readNifti(const std::filesystem::path& path, int volumeIndex) {
    std::string source = path.string();
    std::vector<std::uint8_t> file = readFileBytes(path);
    if (isGzip(file)) {
        // Read the header first, so the inflation is sized by what the header promises, and stops after the
        // volume asked for (a 4-D series need not be inflated whole to show its first volume).
        std::vector<std::uint8_t> head = gunzip(file, source, 1u << 20, kLargestHeader);
        ParsedHeader p = parseHeader(head, source);
        checkVolumeIndex(p, volumeIndex, source);
        std::uint64_t total = p.pair ? kLargestHeader : p.bytesThrough(volumeIndex);
        file = gunzip(file, source, total + (1u << 16), total);
    }
    ParsedHeader p = parseHeader(file, source);
    if (!p.pair) return readNiftiBytes(file, source, volumeIndex);
    checkVolumeIndex(p, volumeIndex, source);
    // The pair: header in .hdr, voxels in the .img beside it (optionally gzipped).
    std::filesystem::path image = path;
    std::string name = path.string();
    const char* magic = p.version == 1 ? "\"ni1\"" : "\"ni2\"";
    if (endsWith(name, ".hdr.gz")) image = name.substr(0, name.size() - 7) + ".img.gz";
    else if (endsWith(name, ".hdr")) image = name.substr(0, name.size() - 4) + ".img";
    else throw InputError(source, "magic", p.version == 1 ? "\"n+1\" (a .hdr/.img pair must be opened through its .hdr)"
                                                          : "\"n+2\" (a .hdr/.img pair must be opened through its .hdr)", magic);
    std::string expected = image.string();
    if (!std::filesystem::exists(image) && endsWith(expected, ".img")) image += ".gz";
    if (!std::filesystem::exists(image))
        throw InputError(source, "image file", "the voxels of this " + std::string(magic) + " header in " + expected + " beside it",
                         "no such file");
    std::vector<std::uint8_t> data = readFileBytes(image);
    if (isGzip(data)) data = gunzip(data, image.string(), p.bytesThrough(volumeIndex) + (1u << 16), p.bytesThrough(volumeIndex));
    if (p.dataOffset > data.size())
        throw InputError(image.string(), "vox_offset", "an offset inside the image file", std::to_string(p.dataOffset));
    VolumeData volume = build(p, std::span(data).subspan(p.dataOffset), volumeIndex, source, image.string());
    volume.files = {path, image};
    return volume;
}

}  // namespace curette::io
