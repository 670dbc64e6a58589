// MetaImage reading (io/metaimage.h). The facts come from Kitware/MetaIO (metaObject.cxx, metaImage.cxx,
// metaTypes.h), the MetaIO wiki page, and ITK's itkMetaImageIO.cxx for the meaning of TransformMatrix.
#include "io/metaimage.h"

#include "base/atomic_file.h"
#include "base/error.h"
#include "base/text.h"

#include <zlib.h>

#include <algorithm>
#include <bit>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstring>
#include <map>
#include <string_view>
#include <vector>

namespace curette::io {

namespace {

constexpr std::size_t kMaxHeaderBytes = std::size_t(1) << 20;
constexpr std::int64_t kMaxAxis = std::int64_t(1) << 24;

// A header value as it may appear in a message: at most 60 characters, non-printable bytes as '?'.
std::string shown(std::string_view text) {
    std::string s(text.substr(0, 60));
    for (char& c : s)
        if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) > 0x7e) c = '?';
    return "\"" + s + (text.size() > 60 ? "...\"" : "\"");
}

// Header lines are padded with spaces and tabs; a CRLF file ends each in '\r'.
constexpr std::string_view kHeaderBlanks = " \t\r";

// `Key = Value` lines up to and including ElementDataFile, which MetaIO reads last (metaImage.cxx sets
// terminateRead on it): the data of a LOCAL file begin right after that line.
struct Header {
    std::string source;
    std::map<std::string, std::string, std::less<>> fields;
    std::size_t dataStart = 0;

    const std::string* find(std::string_view key) const {
        auto it = fields.find(key);
        return it == fields.end() ? nullptr : &it->second;
    }
    const std::string& required(std::string_view key, const std::string& expected) const {
        const std::string* v = find(key);
        if (!v) throw InputError(source, std::string(key), expected, "missing");
        return *v;
    }
    // The one of several synonyms that is present (MetaIO version 0: Position and Origin for Offset, Rotation
    // and Orientation for TransformMatrix); two of them at once are ambiguous.
    const std::string* synonym(std::initializer_list<const char*> keys, const char** found) const {
        const std::string* value = nullptr;
        for (const char* key : keys)
            if (const std::string* v = find(key)) {
                if (value)
                    throw InputError(source, std::string(*found) + "/" + key, "one of " + std::string(*keys.begin()) + " and its synonyms",
                                     "both");
                value = v, *found = key;
            }
        return value;
    }
};

Header readHeader(std::span<const std::uint8_t> bytes, const std::string& source) {
    Header h;
    h.source = source;
    std::size_t pos = 0;
    int line = 0;
    while (true) {
        if (pos >= bytes.size())
            throw InputError(source, "ElementDataFile", "a header whose last line is ElementDataFile = LOCAL or a file name",
                             "the end of the file after " + std::to_string(line) + " lines");
        if (pos > kMaxHeaderBytes) throw InputError(source, "header", "a text header of at most 1 MiB ending in ElementDataFile", "more");
        std::size_t end = pos;
        while (end < bytes.size() && bytes[end] != '\n') ++end;
        std::string_view text(reinterpret_cast<const char*>(bytes.data() + pos), end - pos);
        pos = end < bytes.size() ? end + 1 : end;
        ++line;
        text = trim(text, kHeaderBlanks);
        if (text.empty()) continue;
        // Control bytes: this is binary data, so the header ended without naming where its data are.
        if (std::any_of(text.begin(), text.end(), [](char c) { return (static_cast<unsigned char>(c) < 0x20 && c != '\t') || c == 0x7f; }))
            throw InputError(source, "ElementDataFile", "a header whose last line is ElementDataFile = LOCAL or a file name",
                             "binary bytes at line " + std::to_string(line) + " before any ElementDataFile line");
        std::size_t eq = text.find('=');
        std::string_view key = eq == std::string_view::npos ? std::string_view{} : trim(text.substr(0, eq), kHeaderBlanks);
        if (key.empty())
            throw InputError(source, "line " + std::to_string(line), "Key = Value (a MetaImage header line)", shown(text));
        std::string_view value = trim(text.substr(eq + 1), kHeaderBlanks);
        if (!h.fields.emplace(std::string(key), std::string(value)).second)
            throw InputError(source, std::string(key), "given once", "given twice (line " + std::to_string(line) + ")");
        if (key == "ElementDataFile") {
            h.dataStart = pos;
            return h;
        }
    }
}

std::vector<std::string_view> words(std::string_view value) {
    std::vector<std::string_view> out;
    std::size_t i = 0;
    while (i < value.size()) {
        while (i < value.size() && (value[i] == ' ' || value[i] == '\t')) ++i;
        std::size_t start = i;
        while (i < value.size() && value[i] != ' ' && value[i] != '\t') ++i;
        if (i > start) out.push_back(value.substr(start, i - start));
    }
    return out;
}

// Exactly `count` finite numbers separated by blanks.
std::vector<double> numbers(const Header& h, const std::string& key, const std::string& value, std::size_t count,
                            const std::string& expected) {
    std::vector<double> out;
    for (std::string_view w : words(value)) {
        double v = 0;
        auto [end, error] = std::from_chars(w.data(), w.data() + w.size(), v);
        if (error != std::errc() || end != w.data() + w.size() || !std::isfinite(v)) throw InputError(h.source, key, expected, shown(value));
        out.push_back(v);
    }
    if (out.size() != count) throw InputError(h.source, key, expected, shown(value));
    return out;
}

std::int64_t integer(const Header& h, const std::string& key, const std::string& value, std::int64_t lo, std::int64_t hi,
                     const std::string& expected) {
    std::string_view t = trim(value, kHeaderBlanks);
    std::int64_t v = 0;
    auto [end, error] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (error != std::errc() || end != t.data() + t.size() || t.empty() || v < lo || v > hi)
        throw InputError(h.source, key, expected, shown(value));
    return v;
}

// MetaIO booleans: true when the first character is T, t or 1, false otherwise (MetaIO reads only that
// character).
bool boolean(const std::string* value, bool fallback) {
    if (!value || value->empty()) return fallback;
    char c = (*value)[0];
    return c == 'T' || c == 't' || c == '1';
}

// ElementType names and sizes (metaTypes.h; MET_LONG and MET_ULONG are 4 bytes there, whatever `long` is).
struct ElementType {
    const char* name;
    int size;
    char kind;  // 'u' unsigned integer, 's' signed integer, 'f' IEEE float
};
constexpr ElementType kElementTypes[] = {
    {"MET_UCHAR", 1, 'u'}, {"MET_CHAR", 1, 's'},  {"MET_USHORT", 2, 'u'},    {"MET_SHORT", 2, 's'},
    {"MET_UINT", 4, 'u'},  {"MET_INT", 4, 's'},   {"MET_ULONG", 4, 'u'},     {"MET_LONG", 4, 's'},
    {"MET_ULONG_LONG", 8, 'u'}, {"MET_LONG_LONG", 8, 's'}, {"MET_FLOAT", 4, 'f'}, {"MET_DOUBLE", 8, 'f'},
};

// The ScalarType a MetaImage element maps to without loss; int8 widens to int16, and the unsigned 32-bit and
// all 64-bit integers to float64 (stored as float32 on the GPU like int32, so above 2^24 they round).
ScalarType scalarTypeOf(const ElementType& e) {
    if (e.kind == 'f') return e.size == 4 ? ScalarType::Float32 : ScalarType::Float64;
    if (e.size == 1) return e.kind == 'u' ? ScalarType::UInt8 : ScalarType::Int16;
    if (e.size == 2) return e.kind == 'u' ? ScalarType::UInt16 : ScalarType::Int16;
    if (e.size == 4 && e.kind == 's') return ScalarType::Int32;
    return ScalarType::Float64;
}

template <typename T>
T loadSwapped(const std::uint8_t* p, bool swap) {
    std::uint8_t raw[sizeof(T)];
    std::memcpy(raw, p, sizeof(T));
    if (swap) std::reverse(raw, raw + sizeof(T));
    T v;
    std::memcpy(&v, raw, sizeof(T));
    return v;
}

// Samples of a widened element type converted to the native-endian ScalarType scalarTypeOf gives.
std::vector<std::uint8_t> widen(const ElementType& e, const std::uint8_t* samples, std::size_t count, bool swap) {
    std::vector<std::uint8_t> out;
    if (e.size == 1) {  // MET_CHAR -> int16
        out.resize(2 * count);
        for (std::size_t i = 0; i < count; ++i) {
            auto v = static_cast<std::int16_t>(static_cast<std::int8_t>(samples[i]));
            std::memcpy(out.data() + 2 * i, &v, 2);
        }
        return out;
    }
    out.resize(8 * count);  // -> float64
    for (std::size_t i = 0; i < count; ++i) {
        const std::uint8_t* p = samples + static_cast<std::size_t>(e.size) * i;
        double v = e.size == 4 ? static_cast<double>(loadSwapped<std::uint32_t>(p, swap))
                   : e.kind == 'u' ? static_cast<double>(loadSwapped<std::uint64_t>(p, swap))
                                   : static_cast<double>(loadSwapped<std::int64_t>(p, swap));
        std::memcpy(out.data() + 8 * i, &v, 8);
    }
    return out;
}

// CompressedData: a zlib stream (MetaIO writes one with compress2) or gzip; 15 + 32 lets zlib detect which.
// Inflates until `wanted` bytes are out (through the volume asked for) or the input ends. The output grows as
// it fills, so a header that promises gigabytes over a few bytes of stream costs nothing. With `toTheEnd`
// (the last volume is wanted) the stream is also run to its end, so its check value (Adler-32 or CRC-32)
// is verified.
std::vector<std::uint8_t> inflateData(std::span<const std::uint8_t> in, std::uint64_t wanted, bool toTheEnd, const std::string& source) {
    z_stream stream{};
    if (inflateInit2(&stream, 15 + 32) != Z_OK) throw SystemError(source + ": zlib could not initialise");
    std::size_t consumed = 0;
    bool ended = false;  // the stream's end, or the input ran out
    // One inflate call into [out, out + room); returns the bytes written.
    auto step = [&](std::uint8_t* out, std::size_t room) {
        std::size_t inChunk = std::min<std::size_t>(in.size() - consumed, UINT_MAX);
        std::size_t outChunk = std::min<std::size_t>(room, UINT_MAX);
        stream.next_in = const_cast<Bytef*>(in.data() + consumed);
        stream.avail_in = static_cast<uInt>(inChunk);
        stream.next_out = out;
        stream.avail_out = static_cast<uInt>(outChunk);
        int status = inflate(&stream, Z_NO_FLUSH);
        std::size_t read = inChunk - stream.avail_in, written = outChunk - stream.avail_out;
        consumed += read;
        if (status == Z_NEED_DICT || status == Z_DATA_ERROR || status == Z_MEM_ERROR || status == Z_STREAM_ERROR) {
            std::string reason = stream.msg ? stream.msg : "corrupt data";
            inflateEnd(&stream);
            throw InputError(source, "CompressedData", "a valid zlib or gzip stream", reason);
        }
        if (status == Z_STREAM_END || (read == 0 && written == 0)) ended = true;
        return written;
    };
    std::vector<std::uint8_t> out;
    std::size_t produced = 0;
    while (!ended && produced < wanted) {
        if (produced == out.size())
            out.resize(static_cast<std::size_t>(std::min<std::uint64_t>(wanted, produced + std::max<std::size_t>(produced, 1 << 16))));
        produced += step(out.data() + produced, out.size() - produced);
    }
    out.resize(produced);
    // The wanted bytes are out; the rest of the stream goes to scratch space only to reach the check value.
    std::uint8_t scratch[4096];
    while (toTheEnd && !ended) step(scratch, sizeof scratch);
    inflateEnd(&stream);
    return out;
}

struct Layout {
    glm::ivec3 dims{1};
    int volumeCount = 1;
    ElementType element{};
    bool bigEndian = false;
    glm::dmat4 affine{1.0};
};

Layout interpret(const Header& h) {
    Layout l;
    if (const std::string* type = h.find("ObjectType"); type && *type != "Image")
        throw InputError(h.source, "ObjectType", "Image", shown(*type));
    const int n = static_cast<int>(integer(h, "NDims", h.required("NDims", "3, or 4 (a series of 3-D volumes)"), 3, 4,
                                           "3, or 4 (a series of 3-D volumes)"));
    const std::string nText = std::to_string(n);

    std::vector<double> size = numbers(h, "DimSize", h.required("DimSize", nText + " sizes"), static_cast<std::size_t>(n),
                                       nText + " sizes in 1.." + std::to_string(kMaxAxis));
    for (int a = 0; a < n; ++a)
        if (size[static_cast<std::size_t>(a)] < 1 || size[static_cast<std::size_t>(a)] > static_cast<double>(kMaxAxis) ||
            size[static_cast<std::size_t>(a)] != std::floor(size[static_cast<std::size_t>(a)]))
            throw InputError(h.source, "DimSize", nText + " sizes in 1.." + std::to_string(kMaxAxis), shown(h.fields.at("DimSize")));
    for (int a = 0; a < 3; ++a) l.dims[a] = static_cast<int>(size[static_cast<std::size_t>(a)]);
    if (n == 4) {
        if (size[3] > double(1 << 30)) throw InputError(h.source, "DimSize", "at most 2^30 volumes along the fourth axis", shown(h.fields.at("DimSize")));
        l.volumeCount = static_cast<int>(size[3]);
    }

    const std::string& typeName = h.required("ElementType", "MET_UCHAR, MET_CHAR, MET_USHORT, MET_SHORT, MET_UINT, MET_INT, MET_FLOAT, ...");
    const ElementType* element = nullptr;
    for (const ElementType& e : kElementTypes)
        if (typeName == e.name) element = &e;
    if (!element)
        throw InputError(h.source, "ElementType",
                         "a scalar type: MET_UCHAR, MET_CHAR, MET_USHORT, MET_SHORT, MET_UINT, MET_INT, MET_ULONG, MET_LONG, "
                         "MET_ULONG_LONG, MET_LONG_LONG, MET_FLOAT or MET_DOUBLE",
                         shown(typeName));
    l.element = *element;
    if (const std::string* channels = h.find("ElementNumberOfChannels"))
        if (integer(h, "ElementNumberOfChannels", *channels, 1, INT_MAX, "a positive count") != 1)
            throw InputError(h.source, "ElementNumberOfChannels", "1 (curette renders scalar volumes, not vector pixels)", shown(*channels));
    if (!boolean(h.find("BinaryData"), true))
        throw InputError(h.source, "BinaryData", "True (curette reads binary MetaImage data, not ASCII)", shown(*h.find("BinaryData")));

    // ElementByteOrderMSB and BinaryDataByteOrderMSB set the same flag (metaObject.cxx).
    const std::string* msb = h.find("BinaryDataByteOrderMSB");
    const std::string* elementMsb = h.find("ElementByteOrderMSB");
    if (msb && elementMsb && boolean(msb, false) != boolean(elementMsb, false))
        throw InputError(h.source, "ElementByteOrderMSB", "the same byte order as BinaryDataByteOrderMSB", shown(*elementMsb));
    l.bigEndian = boolean(msb ? msb : elementMsb, false);

    // Spacing: ElementSpacing, else ElementSize (metaImage.cxx uses the size when the spacing is not given).
    glm::dvec3 spacing(1.0);
    const char* spacingKey = h.find("ElementSpacing") ? "ElementSpacing" : "ElementSize";
    if (const std::string* spacingText = h.find(spacingKey)) {
        std::vector<double> s = numbers(h, spacingKey, *spacingText, static_cast<std::size_t>(n), nText + " positive spacings in mm");
        for (int a = 0; a < 3; ++a) {
            if (s[static_cast<std::size_t>(a)] <= 0) throw InputError(h.source, spacingKey, nText + " positive spacings in mm", shown(*spacingText));
            spacing[a] = s[static_cast<std::size_t>(a)];
        }
    }
    const char* originKey = "Offset";
    glm::dvec3 origin(0.0);
    if (const std::string* text = h.synonym({"Offset", "Position", "Origin"}, &originKey)) {
        std::vector<double> o = numbers(h, originKey, *text, static_cast<std::size_t>(n), nText + " coordinates in mm (LPS)");
        origin = {o[0], o[1], o[2]};
    }
    // TransformMatrix[i * n + j] is component j of the direction of index axis i, in LPS (ITK's MetaImageIO
    // sets direction ii from transformMatrix[ii * n + jj]).
    const char* matrixKey = "TransformMatrix";
    glm::dmat3 direction(1.0);  // column i: direction of axis i
    if (const std::string* text = h.synonym({"TransformMatrix", "Rotation", "Orientation"}, &matrixKey)) {
        std::size_t count = static_cast<std::size_t>(n * n);
        std::vector<double> m = numbers(h, matrixKey, *text, count, std::to_string(count) + " numbers (row i: the direction of axis i, LPS)");
        auto at = [&](int i, int j) { return m[static_cast<std::size_t>(i * n + j)]; };
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) direction[i][j] = at(i, j);
        if (n == 4)
            for (int k = 0; k < 3; ++k)
                if (at(3, k) != 0.0 || at(k, 3) != 0.0)
                    throw InputError(h.source, matrixKey, "a fourth axis that does not move through space (row 4 and column 4 zero but for the last)",
                                     shown(*text));
    }
    // LPS -> RAS: negate x and y.
    const glm::dvec3 toRas(-1.0, -1.0, 1.0);
    for (int a = 0; a < 3; ++a) l.affine[a] = glm::dvec4(toRas * direction[a] * spacing[a], 0.0);
    l.affine[3] = glm::dvec4(toRas * origin, 1.0);
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 3; ++r) l.affine[c][r] += 0.0;  // -0 (a negated 0) becomes 0, as `info` prints it
    if (std::abs(glm::determinant(glm::dmat3(l.affine))) < 1e-12)
        throw InputError(h.source, matrixKey, "an invertible index-to-world transform", "a singular one");
    return l;
}

void checkVolumeIndex(const Layout& l, int index, const std::string& source) {
    if (index < 0 || index >= l.volumeCount)
        throw InputError(source, "--volume / volume.index",
                         "a volume index in 0.." + std::to_string(l.volumeCount - 1) + " (the file holds " + std::to_string(l.volumeCount) +
                             (l.volumeCount == 1 ? " volume)" : " volumes)"),
                         std::to_string(index));
}

VolumeData read(std::span<const std::uint8_t> bytes, const std::string& source, const std::filesystem::path& baseDirectory,
                int volumeIndex) {
    Header h = readHeader(bytes, source);
    Layout l = interpret(h);
    checkVolumeIndex(l, volumeIndex, source);

    const std::string& dataFile = h.fields.at("ElementDataFile");
    const bool local = dataFile == "LOCAL" || dataFile == "Local" || dataFile == "local";
    if (dataFile.starts_with("LIST"))
        throw InputError(source, "ElementDataFile", "LOCAL or the name of one data file (curette does not read LIST, one file per slice)",
                         shown(dataFile));
    if (dataFile.find('%') != std::string::npos)
        throw InputError(source, "ElementDataFile", "LOCAL or the name of one data file (curette does not read %d patterns, one file per slice)",
                         shown(dataFile));
    if (dataFile.empty()) throw InputError(source, "ElementDataFile", "LOCAL or the name of one data file", "\"\"");

    // Each axis is below 2^24, so the product is bounded in double before it is formed in 64 bits.
    if (static_cast<double>(l.dims.x) * l.dims.y * l.dims.z > double(std::uint64_t(1) << 40))
        throw InputError(source, "DimSize", "a volume of at most 2^40 voxels", shown(h.fields.at("DimSize")));
    const std::uint64_t voxels = static_cast<std::uint64_t>(l.dims.x) * static_cast<std::uint64_t>(l.dims.y) *
                                 static_cast<std::uint64_t>(l.dims.z);
    const std::uint64_t volumeBytes = voxels * static_cast<std::uint64_t>(l.element.size);
    if (static_cast<std::uint64_t>(l.volumeCount) > (std::uint64_t(1) << 62) / volumeBytes)
        throw InputError(source, "DimSize", "at most 2^62 bytes of voxels in all volumes", shown(h.fields.at("DimSize")));
    const std::uint64_t through = static_cast<std::uint64_t>(volumeIndex + 1) * volumeBytes;
    const std::uint64_t allBytes = static_cast<std::uint64_t>(l.volumeCount) * volumeBytes;

    std::vector<std::uint8_t> external;
    std::vector<std::filesystem::path> files;   // a detached data file: the header and it
    std::span<const std::uint8_t> file = bytes;
    std::string dataSource = source;
    std::uint64_t start = h.dataStart;
    if (!local) {
        std::filesystem::path path(dataFile);
        if (path.is_relative()) path = baseDirectory / path;
        dataSource = path.string();
        std::error_code ec;
        if (!std::filesystem::is_regular_file(path, ec))
            throw InputError(source, "ElementDataFile", "a data file beside the header", "no such file: " + dataSource);
        external = readFileBytes(path);
        file = external;
        files = {std::filesystem::path(source), path};
        start = 0;
    }
    const bool compressed = boolean(h.find("CompressedData"), false);
    if (const std::string* text = h.find("HeaderSize")) {
        // MetaIO seeks to HeaderSize from the start of the data stream; -1 means the data end the file.
        std::int64_t skip = integer(h, "HeaderSize", *text, -1, std::int64_t(1) << 50, "a byte count, or -1 (the data end the file)");
        if (skip == -1) {
            if (compressed) throw InputError(source, "HeaderSize", "a byte count for compressed data (-1 needs the data's size)", "-1");
            if (file.size() < allBytes)
                throw InputError(dataSource, "data", std::to_string(allBytes) + " bytes at the end of the file", std::to_string(file.size()) + " bytes");
            start = file.size() - allBytes;
        } else if (skip > 0) {
            if (local && static_cast<std::uint64_t>(skip) < h.dataStart)
                throw InputError(source, "HeaderSize", "at least the header's " + std::to_string(h.dataStart) +
                                                           " bytes (for LOCAL data it counts from the file's start)",
                                 *text);
            start = static_cast<std::uint64_t>(skip);
        }
    }
    if (start > file.size())
        throw InputError(dataSource, "data", "data from byte " + std::to_string(start), "a file of " + std::to_string(file.size()) + " bytes");

    std::vector<std::uint8_t> inflated;
    std::span<const std::uint8_t> data = file.subspan(static_cast<std::size_t>(start));
    if (compressed) {
        // Without CompressedDataSize (or with 0, as MetaIO writes when unknown) the stream runs to the end.
        if (const std::string* text = h.find("CompressedDataSize")) {
            std::int64_t n = integer(h, "CompressedDataSize", *text, 0, std::int64_t(1) << 50, "a byte count");
            if (n > 0) {
                if (static_cast<std::uint64_t>(n) > data.size())
                    throw InputError(dataSource, "CompressedDataSize", "at most the " + std::to_string(data.size()) + " bytes after the header",
                                     *text);
                data = data.first(static_cast<std::size_t>(n));
            }
        }
        inflated = inflateData(data, through, volumeIndex + 1 == l.volumeCount, dataSource);
        data = inflated;
    }
    if (data.size() < through)
        throw InputError(dataSource, "data",
                         std::to_string(volumeBytes) + " bytes of voxels (" + std::to_string(l.dims.x) + "x" + std::to_string(l.dims.y) + "x" +
                             std::to_string(l.dims.z) + " " + l.element.name + ")" +
                             (l.volumeCount > 1 ? " for volume " + std::to_string(volumeIndex) + " of " + std::to_string(l.volumeCount) : "") +
                             (compressed ? " once inflated" : ""),
                         std::to_string(data.size() > through - volumeBytes ? data.size() - (through - volumeBytes) : 0) + " bytes");

    const std::uint8_t* samples = data.data() + (through - volumeBytes);
    ScalarType type = scalarTypeOf(l.element);
    const ElementType& e = l.element;
    const bool native = e.kind == 'f' || (e.kind == 'u' && e.size <= 2) || (e.kind == 's' && (e.size == 2 || e.size == 4));
    VolumeData volume;
    if (native) {
        volume = buildVolume(source, l.dims, type, samples, l.bigEndian, 1.0, 0.0, l.affine);
    } else {
        const bool swap = l.bigEndian != (std::endian::native == std::endian::big);
        std::vector<std::uint8_t> wide = widen(l.element, samples, static_cast<std::size_t>(voxels), swap);
        volume = buildVolume(source, l.dims, type, wide.data(), std::endian::native == std::endian::big, 1.0, 0.0, l.affine);
        volume.description = std::string("MetaImage ") + l.element.name + " (read as " + scalarTypeName(type) + ")";
    }
    volume.volumeCount = l.volumeCount;
    volume.volumeIndex = volumeIndex;
    volume.files = std::move(files);
    return volume;
}

}  // namespace

VolumeData readMetaImageBytes(std::span<const std::uint8_t> bytes, const std::string& source, const std::filesystem::path& baseDirectory,
                              int volumeIndex) {
    return read(bytes, source, baseDirectory, volumeIndex);
}

VolumeData readMetaImage(const std::filesystem::path& path, int volumeIndex) {
    std::vector<std::uint8_t> bytes = readFileBytes(path);
    return read(bytes, path.string(), path.parent_path(), volumeIndex);
}

}  // namespace curette::io
