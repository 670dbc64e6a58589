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

// The bound on what a gzip stream of n bytes can inflate to: deflate's largest ratio is 1032:1 (zlib's
// technical details), and a little for headers of several members.
std::uint64_t mostInflatedBytes(std::uint64_t compressed) { return 1032 * compressed + (std::uint64_t(1) << 16); }

NiftiUint64Reader::NiftiUint64Reader(const std::filesystem::path& path) : source_(path.string()), stored_(readFileBytes(path)) { open(stored_); }

NiftiUint64Reader::NiftiUint64Reader(std::span<const std::uint8_t> bytes, std::string source) : source_(std::move(source)) { open(bytes); }

NiftiUint64Reader::~NiftiUint64Reader() = default;

void NiftiUint64Reader::voxelsMissing(const std::string& found) const {
    throw InputError(source_, "vox_offset", "352 or more, with " + std::to_string(voxelBytes_) + " bytes of voxels after it", found);
}

void NiftiUint64Reader::readExactly(std::span<std::uint8_t> out) {
    std::size_t got = 0;
    if (inflater_) got = inflater_->read(out);
    else {
        got = std::min(out.size(), plain_.size() - cursor_);
        std::copy_n(plain_.begin() + static_cast<std::ptrdiff_t>(cursor_), got, out.begin());
        cursor_ += got;
    }
    if (got < out.size())
        voxelsMissing("a file that ends before them");
}

void NiftiUint64Reader::open(std::span<const std::uint8_t> stored) {
    const bool gz = isGzip(stored);
    if (gz) inflater_ = std::make_unique<Inflater>(stored, source_, ~std::uint64_t(0));
    else plain_ = stored;
    const std::uint64_t available = gz ? mostInflatedBytes(stored.size()) : stored.size();
    std::vector<std::uint8_t> b(kNiftiVoxOffset);
    std::size_t got = gz ? inflater_->read(b) : std::min(b.size(), stored.size());
    if (!gz) std::copy_n(stored.begin(), got, b.begin()), cursor_ = got;
    if (got < kNiftiVoxOffset) throw InputError(source_, "header", "a NIfTI-1 header (348 bytes and the extension flag)", std::to_string(got) + " bytes");
    std::span<const std::uint8_t> h(b);
    if (load<std::int32_t>(h, 0, false) != kHeaderBytes) {
        swap_ = true;
        if (load<std::int32_t>(h, 0, true) != kHeaderBytes) throw InputError(source_, "sizeof_hdr", "348 (a NIfTI-1 file)");
    }
    if (std::memcmp(b.data() + 344, "n+1", 4) != 0) throw InputError(source_, "magic", "\"n+1\" (a single-file NIfTI-1)");
    std::int16_t rank = load<std::int16_t>(h, 40, swap_);
    if (rank != 3 && rank != 4) throw InputError(source_, "dim[0]", "3 or 4 (a 3-D volume, or its words per voxel in dim[4])", std::to_string(rank));
    if (rank == 4) {
        words_ = load<std::int16_t>(h, 48, swap_);
        if (words_ < 1 || words_ > kMaxNiftiUint64Words)
            throw InputError(source_, "dim[4]", "1.." + std::to_string(kMaxNiftiUint64Words) + " words per voxel", std::to_string(words_));
    }
    for (int a = 0; a < 3; ++a) {
        int d = load<std::int16_t>(h, 42 + 2 * static_cast<std::size_t>(a), swap_);
        if (d < 1) throw InputError(source_, "dim[" + std::to_string(a + 1) + "]", "a size of at least 1", std::to_string(d));
        dims_[a] = d;
    }
    std::int16_t datatype = load<std::int16_t>(h, 70, swap_), bitpix = load<std::int16_t>(h, 72, swap_);
    if (datatype != kDatatypeUint64) throw InputError(source_, "datatype", "1280 (DT_UINT64: words of sub-cell bits)", std::to_string(datatype));
    if (bitpix != 64) throw InputError(source_, "bitpix", "64 for datatype 1280", std::to_string(bitpix));
    float slope = load<float>(h, 112, swap_), inter = load<float>(h, 116, swap_);
    if (!(slope == 0.0f || slope == 1.0f) || inter != 0.0f)
        throw InputError(source_, "scl_slope", "0 or 1 with scl_inter 0 (the stored words are the bits)");
    if (load<std::int16_t>(h, 254, swap_) <= 0) throw InputError(source_, "sform_code", "above 0 (the affine is the srow rows)");
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) indexToWorld_[c][r] = load<float>(h, 280 + 16 * static_cast<std::size_t>(r) + 4 * static_cast<std::size_t>(c), swap_);
    float offset = load<float>(h, 108, swap_);
    voxelBytes_ = 8 * static_cast<std::uint64_t>(dims_.x) * static_cast<std::uint64_t>(dims_.y) * static_cast<std::uint64_t>(dims_.z) *
                  static_cast<std::uint64_t>(words_);
    if (!(offset >= static_cast<float>(kNiftiVoxOffset)) || offset != std::floor(offset) || static_cast<double>(offset) + double(voxelBytes_) > double(available))
        voxelsMissing(std::to_string(offset) + " in a file of " + std::to_string(stored.size()) + (gz ? " compressed" : "") + " bytes");
    // Extensions between the header and the voxels are skipped.
    std::vector<std::uint8_t> skipped(static_cast<std::size_t>(offset) - kNiftiVoxOffset);
    readExactly(skipped);
    buffer_.resize(std::min<std::size_t>(std::size_t(1) << 16, 8 * static_cast<std::size_t>(dims_.x) * static_cast<std::size_t>(dims_.y)));
}

bool NiftiUint64Reader::next(int& word, int& z, std::span<std::uint64_t> out) {
    if (nextWord_ >= words_) return false;
    const std::size_t planeWords = static_cast<std::size_t>(dims_.x) * static_cast<std::size_t>(dims_.y);
    if (out.size() != planeWords) throw SystemError("NiftiUint64Reader::next: a plane of " + std::to_string(planeWords) + " values");
    // In parts of the buffer, so a plane's bytes are never held twice. The voxels are in the header's byte order.
    const std::size_t perPart = buffer_.size() / 8;
    for (std::size_t first = 0; first < planeWords; first += perPart) {
        const std::size_t n = std::min(perPart, planeWords - first);
        std::span<std::uint8_t> part(buffer_.data(), 8 * n);
        readExactly(part);
        for (std::size_t i = 0; i < n; ++i) out[first + i] = load<std::uint64_t>(part, 8 * i, swap_);
    }
    word = nextWord_;
    z = nextZ_;
    if (++nextZ_ == dims_.z) nextZ_ = 0, ++nextWord_;
    return true;
}

namespace {
Uint64Volume readWhole(NiftiUint64Reader& reader) {
    Uint64Volume v;
    v.dims = reader.dims();
    v.indexToWorld = reader.indexToWorld();
    v.words = reader.words();
    std::vector<std::uint64_t> plane(static_cast<std::size_t>(v.dims.x) * static_cast<std::size_t>(v.dims.y));
    int word = 0, z = 0;
    while (reader.next(word, z, plane)) v.values.insert(v.values.end(), plane.begin(), plane.end());
    return v;
}
}  // namespace

Uint64Volume readNiftiUint64Bytes(std::span<const std::uint8_t> bytes, const std::string& source) {
    NiftiUint64Reader reader(bytes, source);
    return readWhole(reader);
}

Uint64Volume readNiftiUint64(const std::filesystem::path& path) {
    NiftiUint64Reader reader(path);
    return readWhole(reader);
}

}  // namespace curette::io
