#pragma once
// Reading back what io/dicom_seg_writer.h and io/dicom_rtstruct_writer.h write (and such objects from other
// makers), for `curette info`: a DICOM Segmentation as a label volume, an RT Structure Set's ROIs. With
// DCMTK (dcmseg's DcmSegmentation for the SEG; dcmdata for the structure set).
//
// The SEG's grid: Plane Orientation and Pixel Measures (shared or of the first frame), the slices from the
// lowest to the highest frame position along the normal, SpacingBetweenSlices apart (else the smallest step
// between frame positions). Each voxel holds the lowest segment number covering it (0: none), so a voxel of
// two overlapping segments shows the first. Patient identifiers are not read.

#include "base/label_map.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace curette::io {

// SOPClassUID (0008,0016) of a DICOM file, "" when it cannot be read.
std::string dicomSopClassOf(const std::filesystem::path& file);
extern const char* const kSegmentationStorage;   // 1.2.840.10008.5.1.4.1.1.66.4
extern const char* const kRtStructureSetStorage; // 1.2.840.10008.5.1.4.1.1.481.3

struct DicomSegmentSummary {
    int number = 0;
    std::string label, algorithmType;
    glm::dvec3 color{0.5};            // sRGB 0..1 from RecommendedDisplayCIELabValue (grey when absent)
    std::size_t frames = 0;
    std::uint64_t voxels = 0;         // set pixels over its frames
};
struct DicomSegmentationVolume {
    LabelMap labels;                  // ids are segment numbers
    std::vector<DicomSegmentSummary> segments;
    std::size_t frames = 0;
    std::string seriesDescription;
};
// Throws InputError(path, field, ...) for a file that is not a BINARY or FRACTIONAL Segmentation DCMTK can
// load, or whose frames do not lie on one grid (no orientation or spacing, a frame off the slice lattice
// by more than 0.01 mm). Fractional frames count as set where their value is at least half the maximum.
DicomSegmentationVolume readDicomSegmentation(const std::filesystem::path& path);

struct DicomRoiSummary {
    int number = 0;
    std::string name, interpretedType, generationAlgorithm;
    glm::ivec3 color{0};              // ROIDisplayColor, 0..255
    std::size_t contours = 0, points = 0;
    std::size_t slices = 0;           // distinct contour planes (by z of their first point, to 0.001 mm)
};
// Throws InputError(path, ...) for a file that is not an RT Structure Set.
std::vector<DicomRoiSummary> readRtStructRois(const std::filesystem::path& path);

}  // namespace curette::io
