#pragma once
// Placing the images of one DICOM series in space (PS3.3 C.7.6.2.1.1): a pure function of what each image's
// header says, so that ordering, spacing and the index-to-world affine are tested without writing files.
// GDCM-free; io/dicom_scan.cpp fills the records.

#include <glm/glm.hpp>

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace curette::io {

// What placement needs of one image: a single-frame file, or one frame of a multi-frame file.
struct DicomSliceRecord {
    std::string name;  // "a.dcm", or "a.dcm frame 3" for a frame of a multi-frame file: names it in messages
    int columns = 0, rows = 0;
    std::optional<glm::dvec3> position;                // ImagePositionPatient (0020,0032), LPS mm
    std::optional<std::array<double, 6>> orientation;  // ImageOrientationPatient (0020,0037): row X, column Y
    std::optional<glm::dvec2> pixelSpacing;            // PixelSpacing (0028,0030): row spacing, column spacing
    // Of its file. The first record's stand in for the step of a single slice, and its tilt is quoted.
    double sliceThickness = 0, spacingBetweenSlices = 0;
    std::string gantryDetectorTilt;  // GantryDetectorTilt (0018,1120) as written
    // What the scan found wrong with its file ("" when nothing): pixel data cut short, frames without
    // positions, pixels curette does not read.
    std::string truncation, geometryProblem, pixelProblem;
};

struct DicomSlicePlacement {
    // Indices into the records along the slice normal; in input order when refused before they were sorted.
    std::vector<std::size_t> order;
    glm::ivec3 dims{0};            // columns, rows, slices (the first record's size)
    glm::dvec3 spacing{0.0};       // mm between columns, rows and slices, when placed
    glm::dmat4 indexToWorld{1.0};  // voxel-centre index (i,j,k) -> world mm (RAS), when placed
    // Why the records are not one regular volume: the expected form and what was found ("" when placed).
    std::string problemExpected, problem;

    bool placed() const { return problem.empty(); }
};

// Sorts the records along the normal of their one orientation and checks that they form one regular volume:
// one size, one orientation and pixel spacing, one image per position, stacked along the normal (no gantry
// tilt), uniform steps within 0.01 mm (no missing slice). Never throws; a refusal names the image and field.
DicomSlicePlacement placeDicomSlices(const std::vector<DicomSliceRecord>& records);

}  // namespace curette::io
