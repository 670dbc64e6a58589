#pragma once
// One region of the plan as the DICOM objects carry it: a segment of the Segmentation (PS3.3 C.8.20.2,
// Segment Description macro) and an ROI of the RT Structure Set (C.8.8.5, C.8.8.6, C.8.8.8), with its
// voxels on the referenced series' grid.

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace curette::io {

// A coded concept (PS3.3 8.8 Code Sequence macro): value, coding scheme designator, meaning.
struct DicomCode {
    std::string value, scheme, meaning;
};

struct DicomPlanStructure {
    std::string label;              // SegmentLabel / ROIName (LO: at most 64 characters, no backslash)
    std::string description;        // SegmentDescription / ROIDescription
    glm::dvec3 color{0.5};          // sRGB 0..1: RecommendedDisplayCIELabValue (SEG), ROIDisplayColor (RTSTRUCT)
    DicomCode category, type;       // SegmentedPropertyCategory/TypeCodeSequence (CID 7150, 7151)
    std::string algorithmType = "SEMIAUTOMATIC";  // SegmentAlgorithmType: MANUAL, SEMIAUTOMATIC or AUTOMATIC
    std::string algorithmName;      // SegmentAlgorithmName (non-MANUAL)
    std::string interpretedType;    // RTROIInterpretedType (C.8.8.8): CAVITY, ORGAN, AVOIDANCE, ...
    std::vector<std::uint8_t> mask; // the grid's voxels, i fastest; non-zero is inside
};

// The series-level text of an object curette writes.
struct DicomObjectInfo {
    std::string seriesDescription;
    int seriesNumber = 100;
    std::string contentLabel = "CURETTE_PLAN";   // ContentLabel / StructureSetLabel (CS: upper case, digits, '_', space)
    std::string softwareVersion;                 // SoftwareVersions
};

}  // namespace curette::io
