#pragma once
// The plan as a DICOM Segmentation (PS3.3 A.51, Segmentation IOD), written with DCMTK's dcmseg
// (DcmSegmentation, the implementation dcmqi and 3D Slicer's SEG support are built on): BINARY, one frame per
// segment and slice where the segment has voxels (frames of an empty slice are left out, PS3.3 C.8.20.2.3
// allows it), on the referenced series' grid:
//   Patient, General Study and Frame of Reference as the referenced series has them (the same Study Instance
//   UID and Frame of Reference UID); a new Series and SOP Instance UID;
//   Shared Functional Groups: Plane Orientation (the series' ImageOrientationPatient), Pixel Measures
//   (PixelSpacing, SliceThickness, SpacingBetweenSlices);
//   Per-frame: Plane Position (slice k's ImagePositionPatient), Frame Content (dimension index values:
//   segment number, k + 1; the dimensions are ReferencedSegmentNumber and ImagePositionPatient), Derivation
//   Image (slice k's SOP Class and Instance UID, purpose 121322 DCM "Source image for image processing
//   operation"), Segment Identification (the segment number);
//   Referenced Series Sequence (Common Instance Reference module): every image of the series;
//   segments: label, description, algorithm type and name, category and type codes, and the colour as
//   RecommendedDisplayCIELabValue (sRGB -> CIELab D65 -> DICOM's 0..65535 scaling, DCMTK's IODCIELabUtil).
// Structures without any voxel are not written (a segment needs a frame).

#include "io/dicom_plan_structure.h"
#include "io/dicom_reference.h"

#include <filesystem>
#include <vector>

namespace curette::io {

// Atomic. Throws std::logic_error when a mask is not the series' size, SystemError when the file cannot be
// written, InputError(path, ...) when DCMTK refuses a value (a label too long, say).
void writeDicomSegmentation(const std::filesystem::path& path, const DicomReferencedSeries& series,
                            const std::vector<DicomPlanStructure>& structures, const DicomObjectInfo& info);

}  // namespace curette::io
