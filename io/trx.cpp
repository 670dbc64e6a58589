#include "io/trx.h"

#include "base/atomic_file.h"
#include "base/error.h"
#include "base/json_reader.h"

#include <zip.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>

namespace curette::io {

namespace {

namespace fs = std::filesystem;

// header.json is a few hundred bytes; anything near this is not a TRX header.
constexpr std::uint64_t kMaxHeaderBytes = 1u << 20;
// Deflate cannot expand data by more than about 1032:1 (RFC 1951: a 258-byte match costs at least two bits),
// so an entry claiming more is corrupt; checking this before allocating keeps a small file from asking for
// gigabytes.
constexpr std::uint64_t kMaxDeflateRatio = 1032;

// One top-level member of the archive (a zip entry or a file in the folder).
struct Member {
    std::string name;
    std::uint64_t size = 0;
    std::uint64_t index = 0;  // zip entry index, or position in the folder listing
};

// A zip archive or a folder, seen as its top-level members. Sub-folders (dpv/, dps/, groups/, dpg/) hold data
// curette does not draw, so they are not listed at all.
class Archive {
public:
    virtual ~Archive() = default;
    const std::vector<Member>& members() const { return members_; }
    // The member's bytes; exactly member.size of them, or InputError.
    virtual std::vector<std::uint8_t> read(const Member& member) = 0;

protected:
    std::vector<Member> members_;
};

// zip_discard for a read-only archive; as a unique_ptr deleter so that an error thrown while the
// constructor lists the entries still closes the archive.
struct ZipDiscard {
    void operator()(zip_t* zip) const { zip_discard(zip); }
};

class ZipArchive final : public Archive {
public:
    ZipArchive(std::span<const std::uint8_t> bytes, const std::string& source) : source_(source) {
        zip_error_t error;
        zip_error_init(&error);
        zip_source_t* input = zip_source_buffer_create(bytes.data(), bytes.size(), 0, &error);
        if (input) {
            zip_.reset(zip_open_from_source(input, ZIP_RDONLY, &error));
            if (!zip_) zip_source_free(input);
        }
        if (!zip_) {
            std::string reason = zip_error_strerror(&error);
            zip_error_fini(&error);
            throw InputError(source, "zip archive", "a zip archive (a .trx file is a zip of arrays and header.json)", reason);
        }
        zip_error_fini(&error);
        zip_int64_t count = zip_get_num_entries(zip_.get(), 0);
        for (zip_int64_t i = 0; i < count; ++i) {
            auto index = static_cast<zip_uint64_t>(i);
            zip_stat_t stat;
            const char* name = zip_get_name(zip_.get(), index, 0);
            if (!name || zip_stat_index(zip_.get(), index, 0, &stat) != 0) fail("entry " + std::to_string(i));
            std::string entry(name);
            if (entry.find('/') != std::string::npos) continue;
            constexpr zip_uint64_t kNeeded = ZIP_STAT_SIZE | ZIP_STAT_COMP_SIZE;
            if ((stat.valid & kNeeded) != kNeeded) fail(entry);
            if (stat.comp_size > bytes.size() || stat.size > stat.comp_size * kMaxDeflateRatio + 64)
                throw InputError(source, entry, "a size the archive can hold (deflate expands at most 1032:1)",
                                 std::to_string(stat.size) + " bytes from " + std::to_string(stat.comp_size) + " compressed");
            members_.push_back({entry, stat.size, index});
        }
    }
    std::vector<std::uint8_t> read(const Member& member) override {
        zip_file_t* file = zip_fopen_index(zip_.get(), member.index, 0);
        if (!file) fail(member.name);
        std::vector<std::uint8_t> out(member.size);
        zip_int64_t got = member.size ? zip_fread(file, out.data(), member.size) : 0;
        // Reading past the end is what makes libzip compare the CRC-32 and the size with the directory's.
        std::uint8_t extra;
        zip_int64_t more = got >= 0 ? zip_fread(file, &extra, 1) : 0;
        std::string reason = zip_file_strerror(file);
        zip_fclose(file);
        if (got < 0 || more < 0)
            throw InputError(source_, member.name, "an entry libzip can decompress", reason);
        if (static_cast<std::uint64_t>(got) != member.size || more != 0)
            throw InputError(source_, member.name, std::to_string(member.size) + " bytes (the zip directory's size)",
                             more != 0 ? "more" : std::to_string(got));
        return out;
    }

private:
    [[noreturn]] void fail(const std::string& what) const {
        throw InputError(source_, what, "a readable zip entry", zip_strerror(zip_.get()));
    }

    std::string source_;
    std::unique_ptr<zip_t, ZipDiscard> zip_;
};

class FolderArchive final : public Archive {
public:
    explicit FolderArchive(const fs::path& folder) {
        std::error_code error;
        for (const fs::directory_entry& entry : fs::directory_iterator(folder, error)) {
            if (!entry.is_regular_file()) continue;  // sub-folders: dpv/, dps/, groups/, dpg/
            paths_.push_back(entry.path());
            members_.push_back({entry.path().filename().string(), entry.file_size(), paths_.size() - 1});
        }
        if (error) throw SystemError(folder.string() + ": cannot list the TRX folder: " + error.message());
    }

    std::vector<std::uint8_t> read(const Member& member) override {
        std::vector<std::uint8_t> bytes = readFileBytes(paths_[member.index]);
        if (bytes.size() != member.size)
            throw InputError(paths_[member.index].string(), member.name, std::to_string(member.size) + " bytes (it changed while read)",
                             std::to_string(bytes.size()));
        return bytes;
    }

private:
    std::vector<fs::path> paths_;
};

// IEEE 754 binary16 -> binary32 (exact: every half is a float). Sign 1, exponent 5 (bias 15), fraction 10.
float halfToFloat(std::uint16_t h) {
    std::uint32_t sign = static_cast<std::uint32_t>(h & 0x8000u) << 16;
    std::uint32_t exponent = (h >> 10) & 0x1fu, fraction = h & 0x3ffu;
    std::uint32_t bits;
    if (exponent == 0x1f) {
        bits = sign | 0x7f800000u | (fraction << 13);  // Inf, NaN (payload kept)
    } else if (exponent != 0) {
        bits = sign | ((exponent + 127 - 15) << 23) | (fraction << 13);
    } else if (fraction == 0) {
        bits = sign;  // +-0
    } else {
        // Subnormal: fraction * 2^-24; normalise it into a float's implicit leading one.
        int shift = std::countl_zero(fraction) - 21;  // leading zeros within the 10-bit field, plus one
        fraction = (fraction << shift) & 0x3ffu;
        bits = sign | (static_cast<std::uint32_t>(127 - 15 + 1 - shift) << 23) | (fraction << 13);
    }
    return std::bit_cast<float>(bits);
}

template <typename T>
T loadLittle(const std::uint8_t* p) {
    std::uint8_t raw[sizeof(T)];
    std::memcpy(raw, p, sizeof(T));
    if constexpr (std::endian::native == std::endian::big)
        for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
    return std::bit_cast<T>(raw);
}

// A member name `name[.cols].dtype` (TRX spec, "Generals"): cols is 1 when absent.
struct ArrayName {
    std::string base, dtype;
    std::uint64_t columns = 1;
};

std::optional<ArrayName> splitArrayName(const std::string& name) {
    std::size_t first = name.find('.'), last = name.rfind('.');
    if (first == std::string::npos) return std::nullopt;
    ArrayName a{name.substr(0, first), name.substr(last + 1)};
    if (first != last) {
        std::string columns = name.substr(first + 1, last - first - 1);
        if (columns.empty() || columns.size() > 6 || columns.find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
        a.columns = std::stoull(columns);
    }
    return a;
}

// The one member whose base name is `base`; nullptr when there is none.
const Member* findArray(const Archive& archive, const std::string& base, const std::string& source) {
    const Member* found = nullptr;
    for (const Member& m : archive.members()) {
        std::optional<ArrayName> a = splitArrayName(m.name);
        if (!a || a->base != base) continue;
        if (found) throw InputError(source, base, "one " + base + " array", "both " + found->name + " and " + m.name);
        found = &m;
    }
    return found;
}

struct Header {
    std::uint64_t streamlines = 0, vertices = 0;
};

Header readHeader(Archive& archive, const std::string& source) {
    const Member* member = nullptr;
    for (const Member& m : archive.members())
        if (m.name == "header.json") member = &m;
    if (!member) throw InputError(source, "header.json", "a TRX header.json at the top level", "none");
    if (member->size > kMaxHeaderBytes)
        throw InputError(source, "header.json", "a JSON header of at most 1 MiB", std::to_string(member->size) + " bytes");
    std::vector<std::uint8_t> bytes = archive.read(*member);
    std::string file = source + "/header.json";
    nlohmann::json json = parseJson(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), file);
    JsonReader root(json, file);
    if (!root.isObject()) root.fail("a JSON object with VOXEL_TO_RASMM, DIMENSIONS, NB_STREAMLINES and NB_VERTICES");
    // Positions are already in RAS millimetres, so the affine and the grid only describe the reference
    // image; they are required by the spec and checked for form, not applied. Other keys are allowed (no
    // finish()): writers may add their own.
    for (const JsonReader& row : root.at("VOXEL_TO_RASMM").elements(4, 4)) row.numbers(4);
    for (const JsonReader& d : root.at("DIMENSIONS").elements(3, 3)) d.unsignedInteger(std::numeric_limits<std::uint32_t>::max());
    // Tractogram offsets are 32-bit: at most 2^32 - 1 vertices and one streamline fewer.
    constexpr std::uint64_t kMax = std::numeric_limits<std::uint32_t>::max();
    Header h;
    h.streamlines = root.at("NB_STREAMLINES").unsignedInteger(kMax - 1);
    h.vertices = root.at("NB_VERTICES").unsignedInteger(kMax);
    return h;
}

std::vector<glm::vec3> readPositions(Archive& archive, const Header& h, const std::string& source) {
    const Member* member = findArray(archive, "positions", source);
    if (!member) throw InputError(source, "positions", "a positions.3.float16|float32|float64 array", "none");
    ArrayName a = *splitArrayName(member->name);
    std::size_t width = a.dtype == "float16" ? 2 : a.dtype == "float32" ? 4 : a.dtype == "float64" ? 8 : 0;
    if (width == 0) throw InputError(source, member->name, "positions of dtype float16, float32 or float64", "\"" + a.dtype + "\"");
    if (a.columns != 3) throw InputError(source, member->name, "3 columns (x, y, z)", std::to_string(a.columns));
    std::uint64_t expected = h.vertices * 3 * width;
    if (member->size != expected)
        throw InputError(source, member->name, std::to_string(h.vertices) + " vertices (NB_VERTICES) = " + std::to_string(expected) + " bytes",
                         std::to_string(member->size) + " bytes");
    std::vector<std::uint8_t> bytes = archive.read(*member);
    std::vector<glm::vec3> points(h.vertices);
    for (std::size_t i = 0; i < points.size(); ++i) {
        for (std::size_t c = 0; c < 3; ++c) {
            const std::uint8_t* p = bytes.data() + (3 * i + c) * width;
            float v = width == 2   ? halfToFloat(loadLittle<std::uint16_t>(p))
                      : width == 4 ? loadLittle<float>(p)
                                   : static_cast<float>(loadLittle<double>(p));
            if (!std::isfinite(v)) throw InputError(source, member->name + " vertex " + std::to_string(i), "finite coordinates", "NaN or Inf");
            points[i][static_cast<glm::length_t>(c)] = v;
        }
    }
    return points;
}

std::vector<std::uint32_t> readOffsets(Archive& archive, const Header& h, const std::string& source) {
    const Member* member = findArray(archive, "offsets", source);
    if (!member) throw InputError(source, "offsets", "an offsets.uint32|uint64 array", "none");
    ArrayName a = *splitArrayName(member->name);
    std::size_t width = a.dtype == "uint32" ? 4 : a.dtype == "uint64" ? 8 : 0;
    if (width == 0) throw InputError(source, member->name, "offsets of dtype uint32 or uint64", "\"" + a.dtype + "\"");
    if (a.columns != 1) throw InputError(source, member->name, "1 column", std::to_string(a.columns));
    // NB_STREAMLINES entries (spec bf1ae219) or NB_STREAMLINES + 1 with a final NB_VERTICES (spec 1e877afd,
    // trx-python).
    std::uint64_t n = h.streamlines;
    // Vertices without a streamline would belong to none (and offsets could not place them).
    if (n == 0 && h.vertices != 0) throw InputError(source, "NB_VERTICES", "0 when NB_STREAMLINES is 0", std::to_string(h.vertices));
    if (member->size != n * width && member->size != (n + 1) * width)
        throw InputError(source, member->name,
                         std::to_string(n) + " or " + std::to_string(n + 1) + " entries (NB_STREAMLINES, or one more ending with NB_VERTICES)",
                         std::to_string(member->size) + " bytes");
    std::vector<std::uint8_t> bytes = archive.read(*member);
    std::size_t entries = bytes.size() / width;
    std::vector<std::uint32_t> offsets;
    offsets.reserve(n + 1);
    for (std::size_t i = 0; i < entries; ++i) {
        const std::uint8_t* p = bytes.data() + i * width;
        std::uint64_t v = width == 4 ? loadLittle<std::uint32_t>(p) : loadLittle<std::uint64_t>(p);
        std::string field = member->name + "[" + std::to_string(i) + "]";
        if (i == 0 && v != 0) throw InputError(source, field, "0 (the first streamline starts at the first vertex)", std::to_string(v));
        if (v > h.vertices) throw InputError(source, field, "a vertex index at most NB_VERTICES (" + std::to_string(h.vertices) + ")", std::to_string(v));
        if (i > 0 && v < offsets.back())
            throw InputError(source, field, "offsets in increasing order (at least " + std::to_string(offsets.back()) + ")", std::to_string(v));
        if (i == n && v != h.vertices)
            throw InputError(source, field, "the final entry NB_VERTICES (" + std::to_string(h.vertices) + ")", std::to_string(v));
        offsets.push_back(static_cast<std::uint32_t>(v));
    }
    if (entries == n) offsets.push_back(static_cast<std::uint32_t>(h.vertices));
    return offsets;
}

Tractogram decode(Archive& archive, const std::string& source) {
    Header h = readHeader(archive, source);
    Tractogram t;
    t.source = source;
    // Positions first: when NB_VERTICES is wrong, their size says so more plainly than an offset would.
    t.points = readPositions(archive, h, source);
    t.offsets = readOffsets(archive, h, source);
    return t;
}

}  // namespace

Tractogram readTrxZipBytes(std::span<const std::uint8_t> bytes, const std::string& source) {
    ZipArchive archive(bytes, source);
    return decode(archive, source);
}

Tractogram readTrx(const std::filesystem::path& path) {
    if (fs::is_directory(path)) {
        FolderArchive archive(path);
        return decode(archive, path.string());
    }
    std::vector<std::uint8_t> bytes = readFileBytes(path);
    return readTrxZipBytes(bytes, path.string());
}

}  // namespace curette::io
