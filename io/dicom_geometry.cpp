// Slice placement (PS3.3 C.7.6.2.1.1): the checks run in the order of their messages' importance, the first
// that fails is the refusal.
#include "io/dicom_geometry.h"

#include "io/dicom_values.h"

#include <algorithm>
#include <cmath>

namespace curette::io {

namespace {

using dicom_detail::fmt;

// Slicer's threshold for "the slice steps differ" [SL-DCM], used for every position comparison.
constexpr double kPositionToleranceMm = 0.01;
// Direction cosines are written with 4-6 decimals; two orientations within this are the same.
constexpr double kOrientationTolerance = 1e-4;

struct Refusal {
    std::string expected, got;
};
using Check = std::optional<Refusal>;

std::string orientationText(const std::array<double, 6>& o) {
    std::string text;
    for (std::size_t i = 0; i < 6; ++i) {
        if (i) text += '\\';
        text += fmt(o[i]);  // appended piece by piece: g++ 12 warns falsely on `"literal" + string` (GCC bug 105329)
    }
    return text;
}

// Every image readable, of one size, grey-scale, with a position, an orientation and a pixel spacing.
Check checkEachImage(const std::vector<DicomSliceRecord>& records) {
    const DicomSliceRecord& first = records.front();
    for (const DicomSliceRecord& r : records) {
        if (!r.truncation.empty()) return Refusal{"image files that hold all their pixel data", r.name + " is truncated: " + r.truncation};
        if (!r.geometryProblem.empty()) return Refusal{"the position of every frame of a multi-frame image", r.geometryProblem};
        if (r.columns != first.columns || r.rows != first.rows)
            return Refusal{"images of one size (Columns x Rows)",
                           "images of " + std::to_string(first.columns) + " x " + std::to_string(first.rows) + " (" + first.name + ") and " +
                               std::to_string(r.columns) + " x " + std::to_string(r.rows) + " (" + r.name + ")"};
        if (!r.pixelProblem.empty())
            return Refusal{"grey-scale pixels (Image Pixel Module, PS3.3 C.7.6.3: SamplesPerPixel 1, MONOCHROME1 or 2, "
                           "BitsAllocated 8, 16 or 32, BitsStored up to it, HighBit BitsStored - 1, PixelRepresentation 0 or 1)",
                           r.pixelProblem + " in " + r.name};
        if (!r.position || !r.orientation)
            return Refusal{"ImagePositionPatient (0020,0032) and ImageOrientationPatient (0020,0037) in every image (slices of a volume)",
                           "no ImagePositionPatient or ImageOrientationPatient in " + r.name + " (a projection or secondary-capture image?)"};
        if (!r.pixelSpacing) return Refusal{"PixelSpacing (0028,0030) in every image (two positive numbers)", "no PixelSpacing in " + r.name};
    }
    return std::nullopt;
}

// One orientation (PS3.3 C.7.6.2.1.1): X = row direction, Y = column direction, unit and orthogonal; and
// one pixel spacing.
Check checkOneOrientationAndSpacing(const std::vector<DicomSliceRecord>& records) {
    const DicomSliceRecord& first = records.front();
    const std::array<double, 6>& o = *first.orientation;
    glm::dvec3 x(o[0], o[1], o[2]), y(o[3], o[4], o[5]);
    if (std::abs(glm::length(x) - 1) > 1e-3 || std::abs(glm::length(y) - 1) > 1e-3 || std::abs(glm::dot(x, y)) > 1e-3)
        return Refusal{"ImageOrientationPatient (0020,0037): two orthogonal unit vectors",
                       "ImageOrientationPatient " + orientationText(o) + " in " + first.name};
    std::vector<const DicomSliceRecord*> orientations{&first};
    for (const DicomSliceRecord& r : records) {
        bool known = std::any_of(orientations.begin(), orientations.end(), [&](const DicomSliceRecord* seen) {
            for (std::size_t i = 0; i < 6; ++i)
                if (std::abs((*seen->orientation)[i] - (*r.orientation)[i]) > kOrientationTolerance) return false;
            return true;
        });
        if (!known) orientations.push_back(&r);
    }
    if (orientations.size() > 1)
        return Refusal{"one ImageOrientationPatient (0020,0037) for every slice",
                       std::to_string(orientations.size()) + " different orientations among " + std::to_string(records.size()) + " images (" +
                           orientationText(*orientations[0]->orientation) + " in " + orientations[0]->name + ", " +
                           orientationText(*orientations[1]->orientation) + " in " + orientations[1]->name +
                           "): a localizer or several stacks in one series"};
    const glm::dvec2 pixelSpacing = *first.pixelSpacing;
    for (const DicomSliceRecord& r : records)
        if (glm::length(*r.pixelSpacing - pixelSpacing) > 1e-4)
            return Refusal{"one PixelSpacing (0028,0030) for every slice",
                           "PixelSpacing " + fmt(pixelSpacing[0]) + "\\" + fmt(pixelSpacing[1]) + " in " + first.name + " and " +
                               fmt((*r.pixelSpacing)[0]) + "\\" + fmt((*r.pixelSpacing)[1]) + " in " + r.name};
    return std::nullopt;
}

// The images in slice order and their distances along the normal.
struct Stack {
    std::vector<const DicomSliceRecord*> slices;
    std::vector<double> d;
};

Check checkOneImagePerPosition(const Stack& stack) {
    const std::size_t n = stack.d.size();
    std::size_t positions = 1;
    for (std::size_t k = 1; k < n; ++k) positions += stack.d[k] - stack.d[k - 1] > kPositionToleranceMm ? 1 : 0;
    if (positions < n)
        return Refusal{"one image per slice position", std::to_string(n) + " images at " + std::to_string(positions) +
                                                           " positions (several echoes, phases or acquisitions in one series?)"};
    return std::nullopt;
}

// Stacked along the normal: the positions move only along X x Y. A step with a sideways part is gantry
// tilt (GDCM's IPPSorter calls it "always an error"); curette would need to resample it.
Check checkStackedAlongTheNormal(const Stack& stack, const glm::dvec3& normal, const std::string& gantryDetectorTilt) {
    const std::vector<double>& d = stack.d;
    const std::size_t n = d.size();
    const glm::dvec3 p0 = *stack.slices.front()->position;
    auto sideways = [&](std::size_t k) {
        glm::dvec3 step = *stack.slices[k]->position - p0;
        return step - glm::dot(step, normal) * normal;
    };
    double largestSideways = 0;
    for (std::size_t k = 1; k < n; ++k) largestSideways = std::max(largestSideways, glm::length(sideways(k)));
    if (largestSideways <= kPositionToleranceMm) return std::nullopt;
    const glm::dvec3 lastSideways = sideways(n - 1);
    double irregular = 0;
    for (std::size_t k = 1; k < n; ++k)
        irregular = std::max(irregular, glm::length(sideways(k) - (d[k] - d[0]) / (d[n - 1] - d[0]) * lastSideways));
    if (irregular > kPositionToleranceMm)
        return Refusal{"slice positions on one line along the slice normal",
                       "positions offset sideways irregularly, by up to " + fmt(largestSideways) + " mm"};
    const double degrees = std::atan2(glm::length(lastSideways), d[n - 1] - d[0]) * 180.0 / 3.14159265358979323846;
    return Refusal{"slices stacked along their normal (ImageOrientationPatient row x column)",
                   "a gantry tilt of " + fmt(degrees) + " degrees: each step moves " +
                       fmt(glm::length(lastSideways) / static_cast<double>(n - 1)) + " mm sideways" +
                       (gantryDetectorTilt.empty() ? "" : " (GantryDetectorTilt (0018,1120) " + gantryDetectorTilt + ")") +
                       "; a tilted stack needs resampling onto a regular grid, which curette does not do"};
}

// Uniform steps (Slicer warns when they differ by more than 0.01 mm [SL-DCM]). Steps that are whole
// multiples of the smallest one are missing slices.
Check checkUniformSteps(const Stack& stack) {
    const std::vector<double>& d = stack.d;
    const std::size_t n = d.size();
    double smallest = 1e300, largest = 0;
    for (std::size_t k = 1; k < n; ++k) smallest = std::min(smallest, d[k] - d[k - 1]), largest = std::max(largest, d[k] - d[k - 1]);
    if (n <= 1 || largest - smallest <= kPositionToleranceMm) return std::nullopt;
    long missing = 0;
    std::vector<std::size_t> gaps;
    bool multiples = true;
    for (std::size_t k = 1; k < n; ++k) {
        double step = d[k] - d[k - 1];
        double m = std::round(step / smallest);
        if (std::abs(step - m * smallest) > kPositionToleranceMm * m) multiples = false;
        if (m >= 2) missing += static_cast<long>(m) - 1, gaps.push_back(k);
    }
    if (multiples) {
        std::size_t k = gaps.front();
        std::string got = std::to_string(missing) + (missing == 1 ? " slice" : " slices") + " missing: the slices are " + fmt(smallest) +
                          " mm apart, but " + fmt(d[k] - d[k - 1]) + " mm lie between slice " + std::to_string(k) + " and " +
                          std::to_string(k + 1) + " of " + std::to_string(n) + " (at " + fmt(d[k - 1]) + " and " + fmt(d[k]) +
                          " mm along the normal, " + stack.slices[k - 1]->name + " and " + stack.slices[k]->name + ")";
        if (gaps.size() > 1) got += " and at " + std::to_string(gaps.size() - 1) + " more places";
        return Refusal{"every slice of a regularly spaced series",
                       got + "; a regular volume needs the missing images, or resampling, which curette does not do"};
    }
    return Refusal{"uniformly spaced slices (steps within " + fmt(kPositionToleranceMm) + " mm)",
                   "slice steps from " + fmt(smallest) + " to " + fmt(largest) +
                       " mm; a regular volume needs resampling onto a uniform grid, which curette does not do"};
}

}  // namespace

DicomSlicePlacement placeDicomSlices(const std::vector<DicomSliceRecord>& records) {
    DicomSlicePlacement placement;
    auto refuse = [&](Refusal refusal) {
        placement.problemExpected = std::move(refusal.expected);
        placement.problem = std::move(refusal.got);
        return placement;
    };
    if (records.empty()) return refuse({"at least one image", "none"});
    const DicomSliceRecord& first = records.front();
    const std::size_t n = records.size();
    placement.dims = {first.columns, first.rows, static_cast<int>(n)};
    for (std::size_t k = 0; k < n; ++k) placement.order.push_back(k);
    if (Check c = checkEachImage(records)) return refuse(*c);
    if (Check c = checkOneOrientationAndSpacing(records)) return refuse(*c);

    const std::array<double, 6>& o = *first.orientation;
    const glm::dvec3 x = glm::normalize(glm::dvec3(o[0], o[1], o[2])), y = glm::normalize(glm::dvec3(o[3], o[4], o[5]));
    const glm::dvec3 normal = glm::normalize(glm::cross(x, y));
    // Sorted by the distance along the normal, IPP . (X x Y) (PS3.3 C.7.6.2.1.1), never by file name or
    // InstanceNumber: that only identifies the image (C.7.6.1), and SliceLocation is optional (C.7.6.2).
    auto distance = [&](std::size_t k) { return glm::dot(*records[k].position, normal); };
    std::stable_sort(placement.order.begin(), placement.order.end(), [&](std::size_t a, std::size_t b) { return distance(a) < distance(b); });
    Stack stack;
    for (std::size_t k : placement.order) stack.slices.push_back(&records[k]), stack.d.push_back(distance(k));

    if (Check c = checkOneImagePerPosition(stack)) return refuse(*c);
    if (Check c = checkStackedAlongTheNormal(stack, normal, first.gantryDetectorTilt)) return refuse(*c);
    if (Check c = checkUniformSteps(stack)) return refuse(*c);

    // One slice has no step: its thickness stands in (SpacingBetweenSlices, else SliceThickness, else 1 mm).
    const std::vector<double>& d = stack.d;
    const double step = n > 1 ? (d[n - 1] - d[0]) / static_cast<double>(n - 1)
                        : first.spacingBetweenSlices > 0 ? first.spacingBetweenSlices
                        : first.sliceThickness > 0       ? first.sliceThickness
                                                         : 1.0;
    // P(i,j) = IPP + i PS[1] X + j PS[0] Y: PixelSpacing's first value is the row spacing, the step along Y.
    const glm::dvec2 pixelSpacing = *first.pixelSpacing;
    placement.spacing = {pixelSpacing[1], pixelSpacing[0], step};
    glm::dmat4 lps(1.0);
    lps[0] = glm::dvec4(x * pixelSpacing[1], 0.0);
    lps[1] = glm::dvec4(y * pixelSpacing[0], 0.0);
    lps[2] = glm::dvec4(normal * step, 0.0);
    lps[3] = glm::dvec4(*stack.slices.front()->position, 1.0);
    // DICOM's patient coordinates are LPS; curette's world is RAS: negate x and y.
    const glm::dmat4 lpsToRas = glm::dmat4(glm::dvec4(-1, 0, 0, 0), glm::dvec4(0, -1, 0, 0), glm::dvec4(0, 0, 1, 0), glm::dvec4(0, 0, 0, 1));
    placement.indexToWorld = lpsToRas * lps;
    return placement;
}

}  // namespace curette::io
