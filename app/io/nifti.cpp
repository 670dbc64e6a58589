#include "app/io/nifti.h"

#include "app/io/gzip.h"
#include "base/atomic_file.h"
#include "base/error.h"
#include "base/log.h"

#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>

namespace curette::io {

namespace {

constexpr std::size_t kHeaderSize = 348;          // sizeof_hdr of NIfTI-1
constexpr std::size_t kSingleFileMinOffset = 352; // header + 4-byte extension flag

// Field reader over the 348-byte header, swapping bytes when the file's endianness differs.
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
    std::int16_t i16(std::size_t o) const { return get<std::int16_t>(o); }
    std::int32_t i32(std::size_t o) const { return get<std::int32_t>(o); }
    double f32(std::size_t o) const { return get<float>(o); }

private:
    std::span<const std::uint8_t> bytes_;
    bool swap_;
};

struct ParsedHeader {
    glm::ivec3 dims{0};
    ScalarType type = ScalarType::UInt8;
    double slope = 1.0, intercept = 0.0;
    glm::dmat4 affine{1.0};
    std::uint64_t dataOffset = 0;
    std::uint64_t dataBytes = 0;
    bool bigEndian = false;
    bool pair = false;  // "ni1": data in the .img file
};

ParsedHeader parseHeader(std::span<const std::uint8_t> bytes, const std::string& source) {
    if (bytes.size() < kHeaderSize)
        throw InputError(source, "header", "a NIfTI-1 header of 348 bytes", std::to_string(bytes.size()) + " bytes");
    std::int32_t size;
    std::memcpy(&size, bytes.data(), 4);
    bool swap = false;
    if (size != static_cast<std::int32_t>(kHeaderSize)) {
        swap = static_cast<std::int32_t>(__builtin_bswap32(static_cast<std::uint32_t>(size))) == static_cast<std::int32_t>(kHeaderSize);
        if (!swap) throw InputError(source, "sizeof_hdr", "348 (NIfTI-1)", std::to_string(size));
    }
    Header h(bytes, swap);
    ParsedHeader p;
    p.bigEndian = (std::endian::native == std::endian::little) == swap;

    // magic (offset 344): "n+1\0" single file, "ni1\0" header/image pair.
    const char* magic = reinterpret_cast<const char*>(bytes.data() + 344);
    if (std::memcmp(magic, "n+1\0", 4) == 0) p.pair = false;
    else if (std::memcmp(magic, "ni1\0", 4) == 0) p.pair = true;
    else throw InputError(source, "magic", "\"n+1\" (single file) or \"ni1\" (.hdr/.img pair)", "other bytes");

    // dim[0] is the number of dimensions; dims 1-3 are space, 4+ time and more: we read 3-D volumes.
    int rank = h.i16(40);
    if (rank < 1 || rank > 7) throw InputError(source, "dim[0]", "a number of dimensions in 1..7", std::to_string(rank));
    for (int i = 1; i <= 3; ++i) {
        int d = i <= rank ? h.i16(static_cast<std::size_t>(40 + 2 * i)) : 1;
        if (d < 1) throw InputError(source, "dim[" + std::to_string(i) + "]", "a positive size", std::to_string(d));
        p.dims[i - 1] = d;
    }
    for (int i = 4; i <= rank; ++i) {
        int d = h.i16(static_cast<std::size_t>(40 + 2 * i));
        if (d > 1)
            throw InputError(source, "dim[" + std::to_string(i) + "]", "1 (curette reads 3-D volumes, not time series)",
                             std::to_string(d));
    }

    int datatype = h.i16(70), bitpix = h.i16(72);
    int expectedBits = 0;
    switch (datatype) {
        case 2: p.type = ScalarType::UInt8, expectedBits = 8; break;
        case 4: p.type = ScalarType::Int16, expectedBits = 16; break;
        case 8: p.type = ScalarType::Int32, expectedBits = 32; break;
        case 16: p.type = ScalarType::Float32, expectedBits = 32; break;
        case 64: p.type = ScalarType::Float64, expectedBits = 64; break;
        case 512: p.type = ScalarType::UInt16, expectedBits = 16; break;
        default:
            throw InputError(source, "datatype", "one of 2 (uint8), 4 (int16), 512 (uint16), 8 (int32), 16 (float32), 64 (float64)",
                             std::to_string(datatype));
    }
    if (bitpix != expectedBits)
        throw InputError(source, "bitpix", std::to_string(expectedBits) + " for datatype " + std::to_string(datatype),
                         std::to_string(bitpix));

    // scl_slope 0 (or not finite) means "no scaling" (nifti1.h); the MNI templates store NaN.
    double slope = h.f32(112), intercept = h.f32(116);
    if (slope != 0.0 && std::isfinite(slope)) {
        p.slope = slope;
        p.intercept = std::isfinite(intercept) ? intercept : 0.0;
    }

    // Spatial units (xyzt_units bits 0-2): metres and micrometres convert to millimetres; unknown is mm.
    int units = bytes[123] & 0x07;
    double toMm = units == 1 ? 1000.0 : units == 3 ? 1e-3 : 1.0;
    glm::dvec3 pixdim(h.f32(80), h.f32(84), h.f32(88));
    for (int a = 0; a < 3; ++a) {
        if (!std::isfinite(pixdim[a])) throw InputError(source, "pixdim[" + std::to_string(a + 1) + "]", "a finite voxel size");
        if (pixdim[a] <= 0.0) pixdim[a] = 1.0;  // unset sizes: treat as 1 (nifti1.h method 1 assumes > 0)
    }
    int qformCode = h.i16(252), sformCode = h.i16(254);
    if (sformCode > 0) {
        // METHOD 3: the general affine, rows srow_x, srow_y, srow_z.
        glm::dmat4 m(1.0);
        for (int row = 0; row < 3; ++row)
            for (int col = 0; col < 4; ++col) {
                double v = h.f32(static_cast<std::size_t>(280 + 16 * row + 4 * col));
                if (!std::isfinite(v)) throw InputError(source, "srow", "finite sform coefficients");
                m[col][row] = v;
            }
        p.affine = m;
    } else if (qformCode > 0) {
        double qfac = h.f32(76);
        p.affine = niftiQformAffine(h.f32(256), h.f32(260), h.f32(264), qfac, pixdim, {h.f32(268), h.f32(272), h.f32(276)});
    } else {
        // METHOD 1 (ANALYZE 7.5 compatibility): scaling only.
        p.affine = glm::dmat4(1.0);
        for (int a = 0; a < 3; ++a) p.affine[a][a] = pixdim[a];
    }
    for (int col = 0; col < 4; ++col)
        for (int row = 0; row < 3; ++row) p.affine[col][row] *= toMm;
    if (std::abs(glm::determinant(glm::dmat3(p.affine))) < 1e-12)
        throw InputError(source, sformCode > 0 ? "srow" : "pixdim", "an invertible index-to-world transform", "a singular one");

    double offset = h.f32(108);
    if (!std::isfinite(offset) || offset < 0 || offset > 1e15)
        throw InputError(source, "vox_offset", "a byte offset in [0, 1e15]", std::to_string(offset));
    p.dataOffset = static_cast<std::uint64_t>(offset);
    if (!p.pair && p.dataOffset < kSingleFileMinOffset) {
        // The MNI templates of mricron-data store 0; the data still starts after header and extension flag.
        log::warn(source + ": vox_offset " + std::to_string(p.dataOffset) + " is below 352 for a single-file NIfTI; using 352");
        p.dataOffset = kSingleFileMinOffset;
    }
    p.dataBytes = static_cast<std::uint64_t>(p.dims.x) * static_cast<std::uint64_t>(p.dims.y) *
                  static_cast<std::uint64_t>(p.dims.z) * scalarTypeSize(p.type);
    return p;
}

VolumeData build(const ParsedHeader& p, std::span<const std::uint8_t> data, const std::string& source, const std::string& dataSource) {
    if (data.size() < p.dataBytes)
        throw InputError(dataSource, "data", std::to_string(p.dataBytes) + " bytes of voxels (" + std::to_string(p.dims.x) + "x" +
                                                 std::to_string(p.dims.y) + "x" + std::to_string(p.dims.z) + " " +
                                                 scalarTypeName(p.type) + ")",
                         std::to_string(data.size()) + " bytes");
    return buildVolume(source, p.dims, p.type, data.data(), p.bigEndian, p.slope, p.intercept, p.affine);
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
    if (qfac != -1.0) qfac = 1.0;  // pixdim[0] should be +1 or -1; anything else means +1
    glm::dmat4 m(1.0);
    m[0] = glm::dvec4(r[0] * pixdim.x, 0.0);
    m[1] = glm::dvec4(r[1] * pixdim.y, 0.0);
    m[2] = glm::dvec4(r[2] * (pixdim.z * qfac), 0.0);
    m[3] = glm::dvec4(offset, 1.0);
    return m;
}

VolumeData readNiftiBytes(std::span<const std::uint8_t> bytes, const std::string& source) {
    ParsedHeader p = parseHeader(bytes, source);
    if (p.pair) throw InputError(source, "magic", "\"n+1\" for a single-file NIfTI", "\"ni1\" (a .hdr/.img pair)");
    if (p.dataOffset > bytes.size())
        throw InputError(source, "vox_offset", "an offset inside the file (" + std::to_string(bytes.size()) + " bytes)",
                         std::to_string(p.dataOffset));
    return build(p, bytes.subspan(p.dataOffset), source, source);
}

VolumeData readNifti(const std::filesystem::path& path) {
    std::string source = path.string();
    std::vector<std::uint8_t> file = readFileBytes(path);
    if (isGzip(file)) {
        // Read the header first, so the inflation is sized by what the header promises.
        std::vector<std::uint8_t> head = gunzip(file, source, 1u << 20, kHeaderSize);
        ParsedHeader p = parseHeader(head, source);
        std::uint64_t total = std::max<std::uint64_t>(p.dataOffset, kSingleFileMinOffset) + p.dataBytes;
        file = gunzip(file, source, total + (1u << 16));
    }
    ParsedHeader p = parseHeader(file, source);
    if (!p.pair) return readNiftiBytes(file, source);
    // The pair: header in .hdr, voxels in the .img beside it (optionally gzipped).
    std::filesystem::path image = path;
    std::string name = path.string();
    if (endsWith(name, ".hdr.gz")) image = name.substr(0, name.size() - 7) + ".img.gz";
    else if (endsWith(name, ".hdr")) image = name.substr(0, name.size() - 4) + ".img";
    else throw InputError(source, "magic", "\"n+1\" (a .hdr/.img pair must be opened through its .hdr)", "\"ni1\"");
    if (!std::filesystem::exists(image) && endsWith(image.string(), ".img")) image += ".gz";
    std::vector<std::uint8_t> data = readFileBytes(image);
    if (isGzip(data)) data = gunzip(data, image.string(), p.dataOffset + p.dataBytes + (1u << 16));
    if (p.dataOffset > data.size())
        throw InputError(image.string(), "vox_offset", "an offset inside the image file", std::to_string(p.dataOffset));
    return build(p, std::span(data).subspan(p.dataOffset), source, image.string());
}

}  // namespace curette::io
