#include "io/nrrd.h"

#include "io/gzip.h"
#include "io/volume_file.h"
#include "base/atomic_file.h"
#include "base/error.h"
#include "base/log.h"
#include "base/text.h"

#include <algorithm>
#include <charconv>
#include <optional>
#include <cmath>
#include <cstring>
#include <map>
#include <optional>
#include <sstream>

namespace curette::io {

namespace {

std::string lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

double parseNumber(const std::string& text, const std::string& source, const std::string& field) {
    std::string t(trim(text));
    double v = 0;
    auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (ec != std::errc() || end != t.data() + t.size()) throw InputError(source, field, "a number", "\"" + t + "\"");
    return v;
}

// An integer field in [min, max] (checked before any conversion, so absurd values are errors, not UB).
long parseInteger(const std::string& text, const std::string& source, const std::string& field, long min, long max) {
    double v = parseNumber(text, source, field);
    if (!(v >= static_cast<double>(min) && v <= static_cast<double>(max)) || v != std::floor(v))
        throw InputError(source, field, "an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "]", "\"" + std::string(trim(text)) + "\"");
    return static_cast<long>(v);
}

std::vector<std::string> words(const std::string& text) {
    std::istringstream in(text);
    std::vector<std::string> list;
    for (std::string w; in >> w;) list.push_back(w);
    return list;
}

// "(a,b,c)" -> three numbers.
glm::dvec3 parseVector(const std::string& text, const std::string& source, const std::string& field) {
    std::string t(trim(text));
    if (t.size() < 2 || t.front() != '(' || t.back() != ')') throw InputError(source, field, "a vector like (1,0,0)", "\"" + t + "\"");
    std::string inner = t.substr(1, t.size() - 2);
    std::vector<double> v;
    std::size_t start = 0;
    while (true) {
        std::size_t comma = inner.find(',', start);
        v.push_back(parseNumber(inner.substr(start, comma - start), source, field));
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    if (v.size() != 3) throw InputError(source, field, "a 3-vector (curette reads 3-D spaces)", "\"" + t + "\"");
    return {v[0], v[1], v[2]};
}

// Space directions: one "(x,y,z)" or "none" per axis.
std::vector<std::optional<glm::dvec3>> parseDirections(const std::string& text, const std::string& source) {
    std::vector<std::optional<glm::dvec3>> list;
    std::string t(trim(text));
    std::size_t i = 0;
    while (i < t.size()) {
        if (std::isspace(static_cast<unsigned char>(t[i]))) {
            ++i;
            continue;
        }
        if (t.compare(i, 4, "none") == 0) {
            list.push_back(std::nullopt);
            i += 4;
            continue;
        }
        std::size_t close = t.find(')', i);
        if (t[i] != '(' || close == std::string::npos)
            throw InputError(source, "space directions", "vectors like (1,0,0) or none, one per axis", "\"" + t + "\"");
        list.push_back(parseVector(t.substr(i, close - i + 1), source, "space directions"));
        i = close + 1;
    }
    return list;
}

ScalarType parseType(const std::string& text, const std::string& source) {
    std::string t = lower(std::string(trim(text)));
    static const std::map<std::string, ScalarType> names = {
        {"uchar", ScalarType::UInt8},          {"unsigned char", ScalarType::UInt8},  {"uint8", ScalarType::UInt8},
        {"uint8_t", ScalarType::UInt8},        {"short", ScalarType::Int16},          {"short int", ScalarType::Int16},
        {"signed short", ScalarType::Int16},   {"signed short int", ScalarType::Int16}, {"int16", ScalarType::Int16},
        {"int16_t", ScalarType::Int16},        {"ushort", ScalarType::UInt16},        {"unsigned short", ScalarType::UInt16},
        {"unsigned short int", ScalarType::UInt16}, {"uint16", ScalarType::UInt16},   {"uint16_t", ScalarType::UInt16},
        {"int", ScalarType::Int32},            {"signed int", ScalarType::Int32},     {"int32", ScalarType::Int32},
        {"int32_t", ScalarType::Int32},        {"float", ScalarType::Float32},        {"double", ScalarType::Float64}};
    auto it = names.find(t);
    if (it == names.end())
        throw InputError(source, "type", "uchar, short, ushort, int, float or double (and their NRRD aliases)", "\"" + std::string(trim(text)) + "\"");
    return it->second;
}

struct Header {
    std::map<std::string, std::string> fields;  // lower-case keys
    std::size_t dataStart = 0;                   // attached: offset of the data in the file
};

Header parseHeader(std::span<const std::uint8_t> bytes, const std::string& source) {
    if (bytes.size() < 8 || std::memcmp(bytes.data(), "NRRD000", 7) != 0 || bytes[7] < '1' || bytes[7] > '5')
        throw InputError(source, "magic", "\"NRRD0001\" .. \"NRRD0005\" on the first line", "other bytes");
    Header h;
    std::size_t pos = 0;
    bool first = true;
    while (pos < bytes.size()) {
        std::size_t end = pos;
        while (end < bytes.size() && bytes[end] != '\n') ++end;
        std::string line(reinterpret_cast<const char*>(bytes.data() + pos), end - pos);
        pos = end < bytes.size() ? end + 1 : end;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (first) {
            first = false;
            continue;
        }
        if (line.empty()) {  // the blank line ends the header of an attached file
            h.dataStart = pos;
            return h;
        }
        if (line[0] == '#') continue;
        if (line.find(":=") != std::string::npos) continue;  // key/value pairs: metadata we do not use
        std::size_t colon = line.find(": ");
        if (colon == std::string::npos) throw InputError(source, "header line", "\"field: value\"", "\"" + line + "\"");
        h.fields[lower(std::string(trim(line.substr(0, colon))))] = trim(line.substr(colon + 2));
    }
    h.dataStart = bytes.size();  // no blank line: a detached header (.nhdr) ends with the file
    return h;
}

std::vector<std::uint8_t> decodeAscii(std::span<const std::uint8_t> text, ScalarType type, std::uint64_t count, const std::string& source) {
    // Every value takes at least one character and one separator: refuse before allocating what the header
    // claims when the text cannot hold it.
    if (text.size() + 1 < 2 * count)
        throw InputError(source, "data", std::to_string(count) + " ascii values", "only " + std::to_string(text.size()) + " bytes of text");
    std::vector<std::uint8_t> out(count * scalarTypeSize(type));
    std::string_view s(reinterpret_cast<const char*>(text.data()), text.size());
    std::size_t i = 0;
    for (std::uint64_t n = 0; n < count; ++n) {
        while (i < s.size() && (std::isspace(static_cast<unsigned char>(s[i])) || s[i] == ',')) ++i;
        std::size_t j = i;
        while (j < s.size() && !std::isspace(static_cast<unsigned char>(s[j])) && s[j] != ',') ++j;
        if (j == i) throw InputError(source, "data", std::to_string(count) + " ascii values", std::to_string(n));
        double v = parseNumber(std::string(s.substr(i, j - i)), source, "data");
        i = j;
        std::uint8_t* dst = out.data() + n * scalarTypeSize(type);
        auto store = [&](auto value) { std::memcpy(dst, &value, sizeof value); };
        switch (type) {
            case ScalarType::UInt8: store(static_cast<std::uint8_t>(std::clamp(v, 0.0, 255.0))); break;
            case ScalarType::Int16: store(static_cast<std::int16_t>(std::clamp(v, -32768.0, 32767.0))); break;
            case ScalarType::UInt16: store(static_cast<std::uint16_t>(std::clamp(v, 0.0, 65535.0))); break;
            case ScalarType::Int32: store(static_cast<std::int32_t>(std::clamp(v, -2147483648.0, 2147483647.0))); break;
            case ScalarType::Float32: store(static_cast<float>(v)); break;
            case ScalarType::Float64: store(v); break;
        }
    }
    return out;
}

VolumeData readWithHeader(const Header& h, std::span<const std::uint8_t> fileBytes, const std::string& source,
                          const std::filesystem::path& baseDirectory) {
    auto field = [&](const char* name) -> const std::string* {
        auto it = h.fields.find(name);
        return it == h.fields.end() ? nullptr : &it->second;
    };
    auto require = [&](const char* name, const char* expected) -> const std::string& {
        const std::string* v = field(name);
        if (!v) throw InputError(source, name, expected, "nothing (the field is required)");
        return *v;
    };
    ScalarType type = parseType(require("type", "a scalar type"), source);
    int dimension = static_cast<int>(parseInteger(require("dimension", "3"), source, "dimension", 1, 16));
    std::vector<std::string> sizeWords = words(require("sizes", "one size per axis"));
    if (dimension != static_cast<int>(sizeWords.size()))
        throw InputError(source, "sizes", std::to_string(dimension) + " sizes (dimension)", std::to_string(sizeWords.size()));
    std::vector<long> sizes;
    for (const std::string& w : sizeWords) sizes.push_back(parseInteger(w, source, "sizes", 1, 1L << 30));
    // A leading axis of size 1 (a 4-D NRRD of one component) is accepted.
    int skipAxis = 0;
    if (dimension == 4 && sizes[0] == 1) skipAxis = 1;
    else if (dimension != 3)
        throw InputError(source, "dimension", "3 (or 4 with a first axis of size 1)", std::to_string(dimension));
    double voxels = 1;
    for (int a = 0; a < 3; ++a) voxels *= static_cast<double>(sizes[static_cast<std::size_t>(skipAxis + a)]);
    if (voxels > 68719476736.0)  // 2^36 voxels: far beyond any GPU, and the byte count must not overflow
        throw InputError(source, "sizes", "at most 2^36 voxels", std::to_string(voxels));
    glm::ivec3 dims(static_cast<int>(sizes[static_cast<std::size_t>(skipAxis)]), static_cast<int>(sizes[static_cast<std::size_t>(skipAxis) + 1]),
                    static_cast<int>(sizes[static_cast<std::size_t>(skipAxis) + 2]));

    std::string encoding = lower(require("encoding", "raw, gzip or ascii"));
    bool gzip = encoding == "gzip" || encoding == "gz";
    bool ascii = encoding == "ascii" || encoding == "text" || encoding == "txt";
    if (!gzip && !ascii && encoding != "raw")
        throw InputError(source, "encoding", "raw, gzip (gz) or ascii (text, txt)", "\"" + encoding + "\"");
    bool bigEndian = false;
    if (const std::string* e = field("endian")) {
        std::string v = lower(*e);
        if (v != "little" && v != "big") throw InputError(source, "endian", "little or big", "\"" + *e + "\"");
        bigEndian = v == "big";
    } else if (scalarTypeSize(type) > 1 && !ascii) {
        throw InputError(source, "endian", "little or big (required for multi-byte types)", "nothing");
    }

    // Where the data lives.
    std::vector<std::uint8_t> detached;
    std::span<const std::uint8_t> data = fileBytes.subspan(std::min(h.dataStart, fileBytes.size()));
    std::string dataSource = source;
    std::optional<std::filesystem::path> detachedPath;
    const std::string* dataFile = field("data file");
    if (!dataFile) dataFile = field("datafile");
    if (dataFile) {
        std::vector<std::string> parts = words(*dataFile);
        if (parts.empty() || parts[0] == "LIST" || parts.size() > 1 || dataFile->find('%') != std::string::npos)
            throw InputError(source, "data file", "a single file name (LIST and format-string forms are not supported)",
                             "\"" + *dataFile + "\"");
        std::filesystem::path p = parts[0];
        if (p.is_relative()) p = baseDirectory / p;
        dataSource = p.string();
        if (!std::filesystem::exists(p)) throw InputError(source, "data file", "an existing data file", "\"" + p.string() + "\" (missing)");
        detached = readFileBytes(p);
        data = detached;
        detachedPath = p;
    }
    // line skip, then (after decompression) byte skip.
    if (const std::string* ls = field("line skip")) {
        long lines = parseInteger(*ls, source, "line skip", 0, 1L << 30);
        std::size_t pos = 0;
        for (long n = 0; n < lines; ++n) {
            while (pos < data.size() && data[pos] != '\n') ++pos;
            if (pos >= data.size()) throw InputError(dataSource, "line skip", "that many lines before the data", *ls);
            ++pos;
        }
        data = data.subspan(pos);
    }
    const std::uint64_t count = static_cast<std::uint64_t>(dims.x) * static_cast<std::uint64_t>(dims.y) * static_cast<std::uint64_t>(dims.z);
    const std::uint64_t expected = count * scalarTypeSize(type);
    long byteSkip = 0;
    if (const std::string* bs = field("byte skip")) {
        byteSkip = parseInteger(*bs, source, "byte skip", -1, 1L << 50);
        if (byteSkip == -1 && encoding != "raw") throw InputError(source, "byte skip", "-1 only with raw encoding", *bs);
    }
    std::vector<std::uint8_t> decoded;
    if (gzip) {
        decoded = gunzip(data, dataSource, expected + static_cast<std::uint64_t>(std::max(byteSkip, 0L)) + 1);
        data = decoded;
    }
    if (byteSkip == -1) {
        if (data.size() < expected) throw InputError(dataSource, "data", std::to_string(expected) + " bytes", std::to_string(data.size()) + " bytes");
        data = data.subspan(data.size() - expected);
    } else if (byteSkip > 0) {
        if (static_cast<std::size_t>(byteSkip) > data.size()) throw InputError(dataSource, "byte skip", "an offset inside the data", std::to_string(byteSkip));
        data = data.subspan(static_cast<std::size_t>(byteSkip));
    }
    if (ascii) {
        decoded = decodeAscii(data, type, count, dataSource);
        data = decoded;
        bigEndian = std::endian::native == std::endian::big;
    }
    if (data.size() < expected)
        throw InputError(dataSource, "data", std::to_string(expected) + " bytes (" + std::to_string(dims.x) + "x" + std::to_string(dims.y) +
                                                 "x" + std::to_string(dims.z) + " " + scalarTypeName(type) + ")",
                         std::to_string(data.size()) + " bytes");

    // Geometry: space directions + origin, converted to RAS; else spacings.
    glm::dmat4 affine(1.0);
    if (const std::string* dirs = field("space directions")) {
        auto list = parseDirections(*dirs, source);
        if (static_cast<int>(list.size()) != dimension)
            throw InputError(source, "space directions", std::to_string(dimension) + " entries (one per axis)", std::to_string(list.size()));
        for (int a = 0; a < 3; ++a) {
            const auto& d = list[static_cast<std::size_t>(a + skipAxis)];
            if (!d) throw InputError(source, "space directions", "a vector for each spatial axis", "none");
            affine[a] = glm::dvec4(*d, 0.0);
        }
        if (const std::string* o = field("space origin")) affine[3] = glm::dvec4(parseVector(*o, source, "space origin"), 1.0);
    } else if (const std::string* sp = field("spacings")) {
        std::vector<std::string> list = words(*sp);
        if (static_cast<int>(list.size()) != dimension)
            throw InputError(source, "spacings", std::to_string(dimension) + " spacings", std::to_string(list.size()));
        for (int a = 0; a < 3; ++a) {
            double v = parseNumber(list[static_cast<std::size_t>(a + skipAxis)], source, "spacings");
            affine[a][a] = std::isfinite(v) && v > 0 ? v : 1.0;
        }
    }
    const std::string* spaceField = field("space");
    std::string space = spaceField ? lower(*spaceField) : std::string("right-anterior-superior");
    glm::dvec3 flip(1.0);
    if (space == "left-posterior-superior" || space == "lps") flip = {-1, -1, 1};
    else if (space == "left-anterior-superior" || space == "las") flip = {-1, 1, 1};
    else if (space != "right-anterior-superior" && space != "ras")
        log::warn(source + ": space \"" + space + "\" is taken as RAS millimetres");
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 3; ++r) affine[c][r] *= flip[r];
    if (std::abs(glm::determinant(glm::dmat3(affine))) < 1e-12)
        throw InputError(source, "space directions", "linearly independent axes", "a singular set");
    VolumeData volume = buildVolume(source, dims, type, data.data(), bigEndian, 1.0, 0.0, affine);
    if (detachedPath) volume.files = {std::filesystem::path(source), *detachedPath};
    return volume;
}

}  // namespace

VolumeData readNrrdBytes(std::span<const std::uint8_t> bytes, const std::string& source, const std::filesystem::path& baseDirectory) {
    return readWithHeader(parseHeader(bytes, source), bytes, source, baseDirectory);
}

VolumeData readNrrd(const std::filesystem::path& path) {
    std::vector<std::uint8_t> bytes = readFileBytes(path);
    return readNrrdBytes(bytes, path.string(), path.parent_path());
}

}  // namespace curette::io
