#include "io/nifti_writer.h"

#include "io/gzip.h"
#include "base/atomic_file.h"
#include "base/error.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

namespace curette::io {

namespace {

constexpr std::size_t kHeaderBytes = 348;
constexpr std::size_t kVoxOffset = 352;
constexpr std::int16_t kDatatypeUint8 = 2, kDatatypeUint16 = 512;
constexpr std::int16_t kIntentLabel = 1002;
constexpr std::int16_t kXformAlignedAnat = 2;
constexpr std::uint8_t kUnitsMm = 2;
constexpr double kOrthogonalityTolerance = 1e-6;

// Stores `value` little-endian at `offset`.
template <typename T>
void store(std::vector<std::uint8_t>& bytes, std::size_t offset, T value) {
    std::uint8_t raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    if constexpr (std::endian::native == std::endian::big) std::reverse(raw, raw + sizeof(T));
    std::memcpy(&bytes.at(offset + sizeof(T) - 1) - (sizeof(T) - 1), raw, sizeof(T));   // in bounds, or throws
}

struct Qform {
    bool valid = false;
    double b = 0, c = 0, d = 0, qfac = 1;
};

// The quaternion of the rotation in `linear` = R * diag(sizes) (nifti1.h METHOD 2), when there is one.
Qform qformOf(const glm::dmat3& linear, glm::dvec3 sizes) {
    Qform q;
    glm::dmat3 r;
    for (int c = 0; c < 3; ++c) {
        if (!(sizes[c] > 0)) return q;
        r[c] = linear[c] / sizes[c];
    }
    for (int a = 0; a < 3; ++a)
        for (int b = a + 1; b < 3; ++b)
            if (std::abs(glm::dot(r[a], r[b])) > kOrthogonalityTolerance) return q;
    if (glm::determinant(r) < 0) {
        q.qfac = -1;
        r[2] = -r[2];  // the reader multiplies the third column by qfac again
    }
    // Shepperd's method on the largest of the four squared components; element (row, col) is r[col][row].
    auto e = [&](int row, int col) { return r[col][row]; };
    double trace = e(0, 0) + e(1, 1) + e(2, 2);
    double w, x, y, z;
    if (trace > 0) {
        double s = 0.5 / std::sqrt(trace + 1.0);
        w = 0.25 / s, x = (e(2, 1) - e(1, 2)) * s, y = (e(0, 2) - e(2, 0)) * s, z = (e(1, 0) - e(0, 1)) * s;
    } else if (e(0, 0) >= e(1, 1) && e(0, 0) >= e(2, 2)) {
        double s = 2.0 * std::sqrt(1.0 + e(0, 0) - e(1, 1) - e(2, 2));
        w = (e(2, 1) - e(1, 2)) / s, x = 0.25 * s, y = (e(0, 1) + e(1, 0)) / s, z = (e(0, 2) + e(2, 0)) / s;
    } else if (e(1, 1) >= e(2, 2)) {
        double s = 2.0 * std::sqrt(1.0 + e(1, 1) - e(0, 0) - e(2, 2));
        w = (e(0, 2) - e(2, 0)) / s, x = (e(0, 1) + e(1, 0)) / s, y = 0.25 * s, z = (e(1, 2) + e(2, 1)) / s;
    } else {
        double s = 2.0 * std::sqrt(1.0 + e(2, 2) - e(0, 0) - e(1, 1));
        w = (e(1, 0) - e(0, 1)) / s, x = (e(0, 2) + e(2, 0)) / s, y = (e(1, 2) + e(2, 1)) / s, z = 0.25 * s;
    }
    if (w < 0) x = -x, y = -y, z = -z;  // the reader takes a = sqrt(1 - b^2 - c^2 - d^2) >= 0
    q.valid = true;
    q.b = x, q.c = y, q.d = z;
    return q;
}

}  // namespace

std::vector<std::uint8_t> niftiHeaderBytes(const NiftiLayout& layout, std::size_t dataBytes, const std::string& source) {
    const glm::dmat4& m = layout.indexToWorld;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 3; ++r)
            if (!std::isfinite(m[c][r])) throw InputError(source, "indexToWorld", "a finite index-to-world affine");
    const glm::dmat3 linear(m);
    if (std::abs(glm::determinant(linear)) < 1e-12) throw InputError(source, "indexToWorld", "an invertible index-to-world affine", "a singular one");
    for (int a = 0; a < 3; ++a)
        if (layout.dims[a] < 1 || layout.dims[a] > 32767)
            throw InputError(source, "dim[" + std::to_string(a + 1) + "]", "a size in 1..32767 (NIfTI-1 int16)", std::to_string(layout.dims[a]));

    std::vector<std::uint8_t> b(kVoxOffset + dataBytes, 0);
    store<std::int32_t>(b, 0, static_cast<std::int32_t>(kHeaderBytes));
    store<std::int16_t>(b, 40, 3);
    for (std::size_t a = 0; a < 3; ++a) store<std::int16_t>(b, 42 + 2 * a, static_cast<std::int16_t>(layout.dims[static_cast<int>(a)]));
    for (std::size_t a = 3; a < 7; ++a) store<std::int16_t>(b, 42 + 2 * a, 1);
    store<std::int16_t>(b, 68, layout.intentCode);
    store<std::int16_t>(b, 70, layout.datatype);
    store<std::int16_t>(b, 72, layout.bitpix);

    const glm::dvec3 sizes(glm::length(linear[0]), glm::length(linear[1]), glm::length(linear[2]));
    const Qform q = qformOf(linear, sizes);
    store<float>(b, 76, static_cast<float>(q.valid ? q.qfac : (glm::determinant(linear) < 0 ? -1.0 : 1.0)));
    for (std::size_t a = 0; a < 3; ++a) store<float>(b, 80 + 4 * a, static_cast<float>(sizes[static_cast<int>(a)]));
    for (std::size_t a = 3; a < 7; ++a) store<float>(b, 80 + 4 * a, 1.0f);
    store<float>(b, 108, static_cast<float>(kVoxOffset));
    store<float>(b, 112, 1.0f);  // scl_slope
    store<float>(b, 116, 0.0f);  // scl_inter
    b[123] = kUnitsMm;
    store<float>(b, 124, static_cast<float>(layout.calMax));
    store<float>(b, 128, 0.0f);  // cal_min
    std::memcpy(b.data() + 148, layout.description.data(), std::min<std::size_t>(layout.description.size(), 79));
    store<std::int16_t>(b, 252, q.valid ? kXformAlignedAnat : std::int16_t{0});
    store<std::int16_t>(b, 254, kXformAlignedAnat);
    if (q.valid) {
        store<float>(b, 256, static_cast<float>(q.b));
        store<float>(b, 260, static_cast<float>(q.c));
        store<float>(b, 264, static_cast<float>(q.d));
    }
    for (std::size_t r = 0; r < 3; ++r) {
        store<float>(b, 268 + 4 * r, static_cast<float>(m[3][static_cast<int>(r)]));  // qoffset_x/y/z
        for (std::size_t c = 0; c < 4; ++c)
            store<float>(b, 280 + 16 * r + 4 * c, static_cast<float>(m[static_cast<int>(c)][static_cast<int>(r)]));  // srow
    }
    std::memcpy(b.data() + 328, layout.intentName.data(), std::min<std::size_t>(layout.intentName.size(), 15));
    std::memcpy(b.data() + 344, "n+1\0", 4);
    return b;
}

namespace {

std::vector<std::uint8_t> niftiBytes(const LabelMap& labels, const std::string& source) {
    if (labels.ids.size() != labels.voxelCount())
        throw InputError(source, "ids", std::to_string(labels.voxelCount()) + " label ids (dims)", std::to_string(labels.ids.size()));
    const std::uint16_t maxId = labels.ids.empty() ? 0 : *std::max_element(labels.ids.begin(), labels.ids.end());
    const bool eightBit = maxId <= 255;
    const std::size_t voxelBytes = eightBit ? 1 : 2;
    NiftiLayout layout{labels.dims, labels.indexToWorld, eightBit ? kDatatypeUint8 : kDatatypeUint16, static_cast<std::int16_t>(8 * voxelBytes),
                       kIntentLabel, static_cast<double>(maxId), "curette label map", "labels"};
    std::vector<std::uint8_t> b = niftiHeaderBytes(layout, labels.ids.size() * voxelBytes, source);
    std::uint8_t* data = b.data() + kVoxOffset;
    if (eightBit) {
        for (std::size_t n = 0; n < labels.ids.size(); ++n) data[n] = static_cast<std::uint8_t>(labels.ids[n]);
    } else {
        for (std::size_t n = 0; n < labels.ids.size(); ++n) {
            data[2 * n] = static_cast<std::uint8_t>(labels.ids[n] & 0xff);
            data[2 * n + 1] = static_cast<std::uint8_t>(labels.ids[n] >> 8);
        }
    }
    return b;
}

}  // namespace

void writeNiftiLabelmap(const std::filesystem::path& path, const LabelMap& labels) {
    std::vector<std::uint8_t> bytes = niftiBytes(labels, path.string());
    if (path.extension() == ".gz") bytes = gzipCompress(bytes);
    writeFileAtomically(path, bytes);
}

}  // namespace curette::io
