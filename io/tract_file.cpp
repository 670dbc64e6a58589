#include "io/tract_file.h"

#include "io/gzip.h"
#include "io/trx.h"
#include "base/atomic_file.h"
#include "base/error.h"
#include "base/log.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <map>
#include <sstream>

namespace curette::io {

namespace {

template <typename T>
T load(const std::uint8_t* p, bool swap) {
    std::uint8_t raw[sizeof(T)];
    std::memcpy(raw, p, sizeof(T));
    if (swap)
        for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
    T v;
    std::memcpy(&v, raw, sizeof(T));
    return v;
}

std::string fixedString(const std::uint8_t* p, std::size_t n) {
    std::size_t length = 0;
    while (length < n && p[length]) ++length;
    return std::string(reinterpret_cast<const char*>(p), length);
}

// Axis and sign of an orientation letter: R/L -> x, A/P -> y, S/I -> z.
bool axisOf(char letter, int& axis, int& sign) {
    switch (std::toupper(static_cast<unsigned char>(letter))) {
        case 'R': axis = 0, sign = 1; return true;
        case 'L': axis = 0, sign = -1; return true;
        case 'A': axis = 1, sign = 1; return true;
        case 'P': axis = 1, sign = -1; return true;
        case 'S': axis = 2, sign = 1; return true;
        case 'I': axis = 2, sign = -1; return true;
    }
    return false;
}

// The voxel axis orientation an affine implies (nibabel's aff2axcodes): for each voxel axis, the world axis
// it moves along most and in which direction.
void affineAxisCodes(const glm::dmat4& a, int axes[3], int signs[3]) {
    bool used[3] = {false, false, false};
    for (int v = 0; v < 3; ++v) {
        int best = 0;
        double bestValue = -1;
        for (int w = 0; w < 3; ++w)
            if (!used[w] && std::abs(a[v][w]) > bestValue) best = w, bestValue = std::abs(a[v][w]);
        used[best] = true;
        axes[v] = best;
        signs[v] = a[v][best] >= 0 ? 1 : -1;
    }
}

}  // namespace

Tractogram readTrkBytes(std::span<const std::uint8_t> bytes, const std::string& source) {
    constexpr std::size_t kHeader = 1000;
    if (bytes.size() < kHeader) throw InputError(source, "header", "a 1000-byte TrackVis header", std::to_string(bytes.size()) + " bytes");
    if (std::memcmp(bytes.data(), "TRACK", 5) != 0) throw InputError(source, "id_string", "\"TRACK\"", "other bytes");
    const std::uint8_t* h = bytes.data();
    std::int32_t hdrSize;
    std::memcpy(&hdrSize, h + 996, 4);
    bool swap = false;
    if (hdrSize != 1000) {
        swap = static_cast<std::int32_t>(__builtin_bswap32(static_cast<std::uint32_t>(hdrSize))) == 1000;
        if (!swap) throw InputError(source, "hdr_size", "1000", std::to_string(hdrSize));
    }
    glm::ivec3 dims(load<std::int16_t>(h + 6, swap), load<std::int16_t>(h + 8, swap), load<std::int16_t>(h + 10, swap));
    glm::dvec3 voxelSize(load<float>(h + 12, swap), load<float>(h + 16, swap), load<float>(h + 20, swap));
    int nScalars = load<std::int16_t>(h + 36, swap), nProperties = load<std::int16_t>(h + 238, swap);
    if (nScalars < 0 || nScalars > 10) throw InputError(source, "n_scalars", "0 to 10", std::to_string(nScalars));
    if (nProperties < 0 || nProperties > 10) throw InputError(source, "n_properties", "0 to 10", std::to_string(nProperties));
    for (int a = 0; a < 3; ++a)
        if (!(voxelSize[a] > 0) || !std::isfinite(voxelSize[a]))
            throw InputError(source, "voxel_size", "three positive voxel sizes in mm", std::to_string(voxelSize[a]));
    glm::dmat4 voxToRas(0.0);
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col) voxToRas[col][row] = load<float>(h + 440 + 4 * (4 * row + col), swap);
    int version = load<std::int32_t>(h + 992, swap);
    std::int32_t count = load<std::int32_t>(h + 988, swap);
    if (version != 1 && version != 2) throw InputError(source, "version", "1 or 2", std::to_string(version));
    if (count < 0) throw InputError(source, "n_count", "a non-negative track count (0: read to the end)", std::to_string(count));

    Tractogram t;
    t.source = source;
    for (int i = 0; i < nScalars; ++i) t.scalarNames.push_back(fixedString(h + 38 + 20 * i, 20));
    for (int i = 0; i < nProperties; ++i) t.propertyNames.push_back(fixedString(h + 240 + 20 * i, 20));

    // voxmm -> world (nibabel's get_affine_trackvis_to_rasmm).
    glm::dmat4 toWorld(1.0);
    bool hasAffine = version == 2 && voxToRas[3][3] != 0.0;
    if (hasAffine) {
        glm::dmat4 scale(1.0);
        for (int a = 0; a < 3; ++a) scale[a][a] = 1.0 / voxelSize[a];
        glm::dmat4 offset(1.0);
        offset[3] = glm::dvec4(-0.5, -0.5, -0.5, 1.0);
        // When the header's voxel order disagrees with the axes the affine implies, reorient the voxel
        // coordinates (a flip maps v to dims - 1 - v) before applying the affine.
        std::string order = fixedString(h + 948, 4);
        glm::dmat4 orient(1.0);
        int affineAxes[3], affineSigns[3];
        affineAxisCodes(voxToRas, affineAxes, affineSigns);
        bool valid = order.size() >= 3;
        int headerAxes[3], headerSigns[3];
        for (int v = 0; v < 3 && valid; ++v) valid = axisOf(order[static_cast<std::size_t>(v)], headerAxes[v], headerSigns[v]);
        if (valid) {
            orient = glm::dmat4(0.0);
            orient[3][3] = 1.0;
            for (int v = 0; v < 3; ++v) {
                int target = 0;
                for (int u = 0; u < 3; ++u)
                    if (affineAxes[u] == headerAxes[v]) target = u;
                bool flip = affineSigns[target] != headerSigns[v];
                orient[v][target] = flip ? -1.0 : 1.0;
                if (flip) orient[3][target] = dims[v] - 1;
            }
        } else if (!order.empty()) {
            log::warn(source + ": voxel_order \"" + order + "\" is not three of R/L/A/P/S/I; taken as the affine's own order");
        }
        toWorld = voxToRas * orient * offset * scale;
    } else {
        toWorld[3] = glm::dvec4(-0.5 * voxelSize, 1.0);
    }

    const std::size_t perPoint = 3 + static_cast<std::size_t>(nScalars);
    std::size_t pos = kHeader;
    std::size_t track = 0;
    while (pos < bytes.size() && (count == 0 || track < static_cast<std::size_t>(count))) {
        std::string where = "track " + std::to_string(track);
        if (bytes.size() - pos < 4) throw InputError(source, where, "a 4-byte point count", "the end of the file");
        std::int32_t n = load<std::int32_t>(bytes.data() + pos, swap);
        pos += 4;
        std::size_t available = (bytes.size() - pos) / 4;
        if (n < 0 || static_cast<std::size_t>(n) * perPoint + static_cast<std::size_t>(nProperties) > available)
            throw InputError(source, where + " n_points", "a count the file holds (" + std::to_string(available / perPoint) + " points left)",
                             std::to_string(n));
        for (std::int32_t i = 0; i < n; ++i) {
            const std::uint8_t* p = bytes.data() + pos;
            glm::dvec3 voxmm(load<float>(p, swap), load<float>(p + 4, swap), load<float>(p + 8, swap));
            if (!std::isfinite(voxmm.x) || !std::isfinite(voxmm.y) || !std::isfinite(voxmm.z))
                throw InputError(source, where + " point " + std::to_string(i), "finite coordinates", "NaN or Inf");
            t.points.emplace_back(glm::vec3(toWorld * glm::dvec4(voxmm, 1.0)));
            for (int s = 0; s < nScalars; ++s) t.scalars.push_back(load<float>(p + 12 + 4 * s, swap));
            pos += 4 * perPoint;
        }
        for (int k = 0; k < nProperties; ++k) t.properties.push_back(load<float>(bytes.data() + pos + 4 * k, swap));
        pos += 4 * static_cast<std::size_t>(nProperties);
        t.offsets.push_back(static_cast<std::uint32_t>(t.points.size()));
        ++track;
    }
    if (count > 0 && track < static_cast<std::size_t>(count))
        throw InputError(source, "n_count", std::to_string(count) + " tracks", std::to_string(track) + " in the file");
    if (count > 0 && pos < bytes.size())
        throw InputError(source, "n_count", std::to_string(count) + " tracks filling the file",
                         std::to_string(bytes.size() - pos) + " bytes after the last track");
    return t;
}

Tractogram readTckBytes(std::span<const std::uint8_t> bytes, const std::string& source) {
    std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    if (text.substr(0, 13) != "mrtrix tracks") throw InputError(source, "magic", "\"mrtrix tracks\" on the first line", "other bytes");
    std::map<std::string, std::string> fields;
    std::size_t pos = text.find('\n');
    bool ended = false;
    while (pos != std::string_view::npos && pos < text.size()) {
        std::size_t end = text.find('\n', pos + 1);
        std::string line(text.substr(pos + 1, (end == std::string_view::npos ? text.size() : end) - pos - 1));
        pos = end;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line == "END") {
            ended = true;
            break;
        }
        std::size_t colon = line.find(':');
        if (colon == std::string::npos) continue;
        std::string key = line.substr(0, colon), value = line.substr(colon + 1);
        value.erase(0, value.find_first_not_of(' '));
        fields[key] = value;
    }
    if (!ended) throw InputError(source, "header", "a header ending with an END line", "none");
    auto field = [&](const char* key) -> std::string {
        auto it = fields.find(key);
        if (it == fields.end()) throw InputError(source, key, "this header field (it is required)", "nothing");
        return it->second;
    };
    std::string datatype = field("datatype");
    int size = 0;
    bool big = false;
    if (datatype == "Float32LE") size = 4;
    else if (datatype == "Float32BE") size = 4, big = true;
    else if (datatype == "Float64LE") size = 8;
    else if (datatype == "Float64BE") size = 8, big = true;
    else throw InputError(source, "datatype", "Float32LE, Float32BE, Float64LE or Float64BE", "\"" + datatype + "\"");
    bool swap = big != (std::endian::native == std::endian::big);
    std::istringstream fileField(field("file"));
    std::string dot;
    double offsetValue = -1;
    fileField >> dot >> offsetValue;
    if (dot != "." || !(offsetValue >= 0) || offsetValue > static_cast<double>(bytes.size()) || offsetValue != std::floor(offsetValue))
        throw InputError(source, "file", "\". OFFSET\" with the data inside this file", "\"" + field("file") + "\"");
    std::size_t offset = static_cast<std::size_t>(offsetValue);
    long expectedCount = -1;
    if (auto it = fields.find("count"); it != fields.end()) {
        double c = -1;
        auto [e, ec] = std::from_chars(it->second.data(), it->second.data() + it->second.size(), c);
        if (ec != std::errc() || c < 0 || c != std::floor(c) || c > 1e12)
            throw InputError(source, "count", "a non-negative integer", "\"" + it->second + "\"");
        expectedCount = static_cast<long>(c);
    }

    Tractogram t;
    t.source = source;
    auto read = [&](std::size_t at) {
        return size == 4 ? static_cast<double>(load<float>(bytes.data() + at, swap)) : load<double>(bytes.data() + at, swap);
    };
    std::size_t triplet = 3 * static_cast<std::size_t>(size);
    bool terminated = false;
    std::size_t index = 0;
    for (std::size_t at = offset; at + triplet <= bytes.size(); at += triplet, ++index) {
        double x = read(at), y = read(at + static_cast<std::size_t>(size)), z = read(at + 2 * static_cast<std::size_t>(size));
        bool nan = std::isnan(x) || std::isnan(y) || std::isnan(z), inf = std::isinf(x) || std::isinf(y) || std::isinf(z);
        if (inf) {
            terminated = true;
            break;
        }
        if (nan) {
            // A delimiter is a triplet of NaNs; a NaN among finite numbers is a corrupt coordinate.
            if (!(std::isnan(x) && std::isnan(y) && std::isnan(z)))
                throw InputError(source, "point " + std::to_string(index), "finite coordinates or a NaN delimiter", "a partial NaN");
            if (t.offsets.back() != t.points.size()) t.offsets.push_back(static_cast<std::uint32_t>(t.points.size()));
            continue;
        }
        t.points.emplace_back(glm::vec3(glm::dvec3(x, y, z)));
    }
    if (t.offsets.back() != t.points.size()) {
        // Points after the last delimiter: a streamline whose NaN never came (the file was cut short).
        throw InputError(source, "data", "streamlines each ended by a NaN triplet", "a truncated last streamline");
    }
    if (!terminated) log::warn(source + ": no Inf triplet at the end of the data (the file may have been cut short)");
    // MATLAB writers leave a stale count (nibabel's matlab_nan.tck says 615000 and holds 1). MRtrix and
    // nibabel read the data up to the Inf terminator whatever count says, so the data wins here too.
    if (expectedCount >= 0 && static_cast<std::size_t>(expectedCount) != t.streamlineCount())
        log::warn(source + ": header count " + std::to_string(expectedCount) + " disagrees with the " +
                  std::to_string(t.streamlineCount()) + " streamlines in the data; the data is read");
    return t;
}

Tractogram readTractogram(const std::filesystem::path& path) {
    std::string extension = path.extension().string();
    // TRX is a zip of arrays or a folder of them (io/trx.h); a folder is TRX whatever its name.
    if (extension == ".trx" || std::filesystem::is_directory(path)) return readTrx(path);
    std::vector<std::uint8_t> bytes = readFileBytes(path);
    if (extension == ".gz") {
        // x.trk.gz, x.tck.gz: the format is the extension under .gz. Tract files carry no trustworthy size
        // (a .tck count may be stale), so the limit only stops a gzip bomb: 8 GiB is ~700 million float32
        // points, far beyond what the tubes can draw.
        extension = path.stem().extension().string();
        if (extension == ".trk" || extension == ".tck") bytes = gunzip(bytes, path.string(), std::uint64_t{8} << 30);
        else extension += ".gz";
    }
    if (extension == ".trk") return readTrkBytes(bytes, path.string());
    if (extension == ".tck") return readTckBytes(bytes, path.string());
    throw InputError(path.string(), "extension", ".trk, .trk.gz (TrackVis), .tck, .tck.gz (MRtrix) or .trx (TRX, a zip or a folder)",
                     "\"" + extension + "\"");
}

}  // namespace curette::io
