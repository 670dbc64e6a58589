#include "io/nifti_uint64.h"

#include "io/gzip.h"
#include "io/nifti_writer.h"
#include "base/atomic_file.h"
#include "base/error.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <optional>

namespace curette::io {

namespace {

constexpr std::int16_t kDatatypeUint64 = 1280;   // nifti1.h DT_UINT64
constexpr std::int32_t kHeaderBytes = 348;

template <typename T>
T load(std::span<const std::uint8_t> bytes, std::size_t offset, bool swap) {
    std::uint8_t raw[sizeof(T)];
    std::memcpy(raw, bytes.data() + offset, sizeof(T));
    if (swap) std::reverse(raw, raw + sizeof(T));
    T value;
    std::memcpy(&value, raw, sizeof(T));
    return value;
}

}  // namespace

void writeNiftiUint64(const std::filesystem::path& path, glm::ivec3 dims, const glm::dmat4& indexToWorld, int words,
                      const std::string& description, const Uint64Planes& plane) {
    if (words < 1 || words > kMaxNiftiUint64Words)
        throw InputError(path.string(), "words", "1.." + std::to_string(kMaxNiftiUint64Words), std::to_string(words));
    const std::size_t planeWords = static_cast<std::size_t>(dims.x) * static_cast<std::size_t>(dims.y);
    const std::size_t count = planeWords * static_cast<std::size_t>(dims.z) * static_cast<std::size_t>(words);
    NiftiLayout layout{dims, indexToWorld, kDatatypeUint64, 64, 0, 0.0, description, ""};
    std::vector<std::uint8_t> header = niftiHeaderBytes(layout, 0, path.string());
    if (words > 1) {   // dim[0] 4, dim[4] the words (the header is little-endian)
        header[40] = 4, header[41] = 0;
        header[48] = static_cast<std::uint8_t>(words), header[49] = 0;
    }
    const bool gz = path.extension() == ".gz";
    std::optional<GzipCompressor> compressor;
    std::vector<std::uint8_t> file;   // uncompressed: the whole file
    if (gz) compressor.emplace(), compressor->add(header);
    else file = std::move(header), file.reserve(file.size() + 8 * count);
    std::vector<std::uint64_t> values(planeWords);
    std::vector<std::uint8_t> bytes(8 * planeWords);
    for (int w = 0; w < words; ++w)   // the word slowest, then z
        for (int z = 0; z < dims.z; ++z) {
            std::fill(values.begin(), values.end(), 0);
            plane(w, z, values);
            for (std::size_t n = 0; n < planeWords; ++n)
                for (std::size_t k = 0; k < 8; ++k) bytes[8 * n + k] = static_cast<std::uint8_t>(values[n] >> (8 * k));   // little-endian
            if (gz) compressor->add(bytes);
            else file.insert(file.end(), bytes.begin(), bytes.end());
        }
    if (gz) file = compressor->finish();
    writeFileAtomically(path, file);
}

void writeNiftiUint64(const std::filesystem::path& path, const Uint64Volume& volume, const std::string& description) {
    const std::size_t planeWords = static_cast<std::size_t>(volume.dims.x) * static_cast<std::size_t>(volume.dims.y);
    const std::size_t count = planeWords * static_cast<std::size_t>(volume.dims.z) * static_cast<std::size_t>(volume.words);
    const bool wordsValid = volume.words >= 1 && volume.words <= kMaxNiftiUint64Words;   // else the writer below names them
    if (wordsValid && volume.values.size() != count)
        throw InputError(path.string(), "values", std::to_string(count) + " values (dims and words)", std::to_string(volume.values.size()));
    writeNiftiUint64(path, volume.dims, volume.indexToWorld, volume.words, description, [&](int w, int z, std::span<std::uint64_t> out) {
        const std::size_t first = (static_cast<std::size_t>(w) * volume.dims.z + static_cast<std::size_t>(z)) * planeWords;
        std::copy_n(volume.values.begin() + static_cast<std::ptrdiff_t>(first), planeWords, out.begin());
    });
}

Uint64Volume readNiftiUint64Bytes(std::span<const std::uint8_t> b, const std::string& source) {
    if (b.size() < kNiftiVoxOffset) throw InputError(source, "header", "a NIfTI-1 header (348 bytes and the extension flag)", std::to_string(b.size()) + " bytes");
    bool swap = false;
    if (load<std::int32_t>(b, 0, false) != kHeaderBytes) {
        swap = true;
        if (load<std::int32_t>(b, 0, true) != kHeaderBytes) throw InputError(source, "sizeof_hdr", "348 (a NIfTI-1 file)");
    }
    if (std::memcmp(b.data() + 344, "n+1", 4) != 0) throw InputError(source, "magic", "\"n+1\" (a single-file NIfTI-1)");
    std::int16_t rank = load<std::int16_t>(b, 40, swap);
    if (rank != 3 && rank != 4) throw InputError(source, "dim[0]", "3 or 4 (a 3-D volume, or its words per voxel in dim[4])", std::to_string(rank));
    Uint64Volume v;
    if (rank == 4) {
        v.words = load<std::int16_t>(b, 48, swap);
        if (v.words < 1 || v.words > kMaxNiftiUint64Words)
            throw InputError(source, "dim[4]", "1.." + std::to_string(kMaxNiftiUint64Words) + " words per voxel", std::to_string(v.words));
    }
    for (int a = 0; a < 3; ++a) {
        int d = load<std::int16_t>(b, 42 + 2 * static_cast<std::size_t>(a), swap);
        if (d < 1) throw InputError(source, "dim[" + std::to_string(a + 1) + "]", "a size of at least 1", std::to_string(d));
        v.dims[a] = d;
    }
    std::int16_t datatype = load<std::int16_t>(b, 70, swap), bitpix = load<std::int16_t>(b, 72, swap);
    if (datatype != kDatatypeUint64) throw InputError(source, "datatype", "1280 (DT_UINT64: words of sub-cell bits)", std::to_string(datatype));
    if (bitpix != 64) throw InputError(source, "bitpix", "64 for datatype 1280", std::to_string(bitpix));
    float slope = load<float>(b, 112, swap), inter = load<float>(b, 116, swap);
    if (!(slope == 0.0f || slope == 1.0f) || inter != 0.0f)
        throw InputError(source, "scl_slope", "0 or 1 with scl_inter 0 (the stored words are the bits)");
    if (load<std::int16_t>(b, 254, swap) <= 0) throw InputError(source, "sform_code", "above 0 (the affine is the srow rows)");
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) v.indexToWorld[c][r] = load<float>(b, 280 + 16 * static_cast<std::size_t>(r) + 4 * static_cast<std::size_t>(c), swap);
    float offset = load<float>(b, 108, swap);
    const std::size_t count = static_cast<std::size_t>(v.dims.x) * v.dims.y * v.dims.z * v.words;
    if (!(offset >= static_cast<float>(kNiftiVoxOffset)) || offset != std::floor(offset) ||
        static_cast<std::size_t>(offset) + count * 8 > b.size())
        throw InputError(source, "vox_offset", "352 or more, with " + std::to_string(count * 8) + " bytes of voxels after it",
                         std::to_string(offset) + " in a file of " + std::to_string(b.size()) + " bytes");
    v.values.resize(count);
    const std::uint8_t* data = b.data() + static_cast<std::size_t>(offset);
    // The voxels are in the header's byte order.
    for (std::size_t n = 0; n < count; ++n) v.values[n] = load<std::uint64_t>(std::span<const std::uint8_t>(data + 8 * n, 8), 0, swap);
    return v;
}

Uint64Volume readNiftiUint64(const std::filesystem::path& path) {
    std::vector<std::uint8_t> bytes = readFileBytes(path);
    if (isGzip(bytes)) {
        // No more than the header claims (8 bytes a voxel, and room for extensions), so a small file cannot
        // claim gigabytes; a header the parser then refuses gets the header's size.
        std::vector<std::uint8_t> head = gunzip(bytes, path.string(), 1u << 20, kNiftiVoxOffset);
        std::uint64_t claimed = 0;
        if (head.size() >= kNiftiVoxOffset) {
            bool swap = load<std::int32_t>(head, 0, false) != kHeaderBytes;
            claimed = 8;
            if (load<std::int16_t>(head, 40, swap) == 4) claimed *= static_cast<std::uint64_t>(std::clamp<std::int16_t>(load<std::int16_t>(head, 48, swap), 1, kMaxNiftiUint64Words));
            for (int a = 0; a < 3; ++a) claimed *= static_cast<std::uint64_t>(std::max<std::int16_t>(1, load<std::int16_t>(head, 42 + 2 * static_cast<std::size_t>(a), swap)));
        }
        bytes = gunzip(bytes, path.string(), kNiftiVoxOffset + claimed + (std::uint64_t(1) << 20));
    }
    return readNiftiUint64Bytes(bytes, path.string());
}

}  // namespace curette::io
