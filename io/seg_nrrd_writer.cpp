#include "io/seg_nrrd_writer.h"

#include "io/gzip.h"
#include "base/atomic_file.h"
#include "base/error.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <set>

namespace curette::io {

namespace {

// Shortest text that reads back as the same double; -0 written as 0.
std::string number(double v) {
    char buffer[32];
    auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, v + 0.0);
    (void)ec;
    return std::string(buffer, end);
}

std::string vector3(glm::dvec3 v) { return "(" + number(v.x) + "," + number(v.y) + "," + number(v.z) + ")"; }

// Tight index box of each segment's voxels.
struct Extent {
    glm::ivec3 lo{std::numeric_limits<int>::max()}, hi{-1};
    bool empty() const { return hi.x < 0; }
};

void checkSegments(const std::string& source, const std::vector<SegmentInfo>& segments) {
    std::set<int> values;
    std::set<std::string> ids;
    for (std::size_t n = 0; n < segments.size(); ++n) {
        const SegmentInfo& s = segments[n];
        std::string key = "Segment" + std::to_string(n);
        if (s.labelValue < 1 || s.labelValue > 65535)
            throw InputError(source, key + "_LabelValue", "a label value in 1..65535 (0 is the background)", std::to_string(s.labelValue));
        if (!values.insert(s.labelValue).second)
            throw InputError(source, key + "_LabelValue", "a label value no other segment has", std::to_string(s.labelValue));
        if (s.id.empty()) throw InputError(source, key + "_ID", "a non-empty segment id", "\"\"");
        if (!ids.insert(s.id).second) throw InputError(source, key + "_ID", "an id no other segment has", "\"" + s.id + "\"");
        if (s.id.find_first_of("\r\n") != std::string::npos) throw InputError(source, key + "_ID", "an id without line breaks");
        if (s.name.find_first_of("\r\n") != std::string::npos) throw InputError(source, key + "_Name", "a name without line breaks");
        for (int c = 0; c < 3; ++c)
            if (!(s.color[c] >= 0.0 && s.color[c] <= 1.0))
                throw InputError(source, key + "_Color", "r g b in 0..1", number(s.color.x) + " " + number(s.color.y) + " " + number(s.color.z));
    }
}

}  // namespace

void writeSlicerSegmentation(const std::filesystem::path& path, const LabelMap& labels, const std::vector<SegmentInfo>& segments) {
    const std::string source = path.string();
    checkSegments(source, segments);
    for (int a = 0; a < 3; ++a)
        if (labels.dims[a] < 1) throw InputError(source, "sizes", "at least one voxel along each axis", std::to_string(labels.dims[a]));
    if (labels.ids.size() != labels.voxelCount())
        throw InputError(source, "ids", std::to_string(labels.voxelCount()) + " label ids (dims)", std::to_string(labels.ids.size()));
    const glm::dmat4& m = labels.indexToWorld;
    if (!(std::abs(glm::determinant(glm::dmat3(m))) > 1e-12)) throw InputError(source, "space directions", "an invertible index-to-world affine");

    // One pass: each segment's extent (through a table from id to segment), and the largest id.
    std::vector<int> segmentOf(65536, -1);
    for (std::size_t n = 0; n < segments.size(); ++n) segmentOf[static_cast<std::size_t>(segments[n].labelValue)] = static_cast<int>(n);
    std::vector<Extent> extents(segments.size());
    std::uint16_t maxId = 0;
    for (int k = 0; k < labels.dims.z; ++k)
        for (int j = 0; j < labels.dims.y; ++j) {
            const std::uint16_t* row = labels.ids.data() + labels.linearIndex(0, j, k);
            for (int i = 0; i < labels.dims.x; ++i) {
                std::uint16_t id = row[i];
                maxId = std::max(maxId, id);
                int s = segmentOf[id];
                if (s < 0) continue;
                Extent& e = extents[static_cast<std::size_t>(s)];
                e.lo = glm::min(e.lo, glm::ivec3(i, j, k));
                e.hi = glm::max(e.hi, glm::ivec3(i, j, k));
            }
        }
    const bool eightBit = maxId <= 255;

    // RAS -> LPS negates x and y, of every column and of the origin.
    const glm::dvec3 toLps(-1.0, -1.0, 1.0);
    std::string h = "NRRD0004\n";
    h += "# Complete NRRD file format specification at:\n# http://teem.sourceforge.net/nrrd/format.html\n";
    h += "# written by curette: a single-layer 3D Slicer segmentation\n";
    h += std::string("type: ") + (eightBit ? "uchar" : "ushort") + "\n";
    h += "dimension: 3\n";
    h += "space: left-posterior-superior\n";
    h += "sizes: " + std::to_string(labels.dims.x) + " " + std::to_string(labels.dims.y) + " " + std::to_string(labels.dims.z) + "\n";
    h += "space directions: " + vector3(glm::dvec3(m[0]) * toLps) + " " + vector3(glm::dvec3(m[1]) * toLps) + " " +
         vector3(glm::dvec3(m[2]) * toLps) + "\n";
    h += "kinds: domain domain domain\n";
    if (!eightBit) h += "endian: little\n";
    h += "encoding: gzip\n";
    h += "space origin: " + vector3(glm::dvec3(m[3]) * toLps) + "\n";
    h += "Segmentation_ContainedRepresentationNames:=Binary labelmap|\n";
    h += "Segmentation_MasterRepresentation:=Binary labelmap\n";
    h += "Segmentation_ReferenceImageExtentOffset:=0 0 0\n";
    for (std::size_t n = 0; n < segments.size(); ++n) {
        const SegmentInfo& s = segments[n];
        const Extent& e = extents[n];
        std::string key = "Segment" + std::to_string(n);
        std::string extent = e.empty() ? "0 -1 0 -1 0 -1"
                                       : std::to_string(e.lo.x) + " " + std::to_string(e.hi.x) + " " + std::to_string(e.lo.y) + " " +
                                             std::to_string(e.hi.y) + " " + std::to_string(e.lo.z) + " " + std::to_string(e.hi.z);
        h += key + "_Color:=" + number(s.color.r) + " " + number(s.color.g) + " " + number(s.color.b) + "\n";
        h += key + "_ColorAutoGenerated:=0\n";
        h += key + "_Extent:=" + extent + "\n";
        h += key + "_ID:=" + s.id + "\n";
        h += key + "_LabelValue:=" + std::to_string(s.labelValue) + "\n";
        h += key + "_Layer:=0\n";
        h += key + "_Name:=" + s.name + "\n";
        h += key + "_NameAutoGenerated:=0\n";
        h += key + "_Tags:=\n";
    }
    h += "\n";

    std::vector<std::uint8_t> raw(labels.ids.size() * (eightBit ? 1 : 2));
    for (std::size_t n = 0; n < labels.ids.size(); ++n) {
        if (eightBit) {
            raw[n] = static_cast<std::uint8_t>(labels.ids[n]);
        } else {
            raw[2 * n] = static_cast<std::uint8_t>(labels.ids[n] & 0xff);
            raw[2 * n + 1] = static_cast<std::uint8_t>(labels.ids[n] >> 8);
        }
    }
    std::vector<std::uint8_t> file(h.begin(), h.end());
    std::vector<std::uint8_t> compressed = gzipCompress(raw);
    file.insert(file.end(), compressed.begin(), compressed.end());
    writeFileAtomically(path, file);
}

}  // namespace curette::io
