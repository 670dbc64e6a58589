#pragma once
// The plan as a DICOM RT Structure Set (PS3.3 A.19), written with DCMTK's dcmrt (DRTStructureSetIOD): the
// representation radiotherapy and many planning and navigation systems take. Each structure is an ROI:
//   Structure Set ROI Sequence: ROINumber (1, 2, ... in the order given), the Frame of Reference UID of the
//   referenced series, ROIName = the label, ROIGenerationAlgorithm SEMIAUTOMATIC or AUTOMATIC (MANUAL as is);
//   ROI Contour Sequence: ROIDisplayColor (0..255), one CLOSED_PLANAR contour per outline of the structure on
//   each slice (io/slice_contours.h: along pixel edges, so each slice's contours enclose exactly its voxels),
//   ContourData in LPS mm on the slice's plane, each contour's Contour Image Sequence naming slice k's image;
//   RT ROI Observations: RTROIInterpretedType as given (CAVITY, ORGAN, AVOIDANCE), ROIInterpreter empty.
// Referenced Frame of Reference Sequence > RT Referenced Study > RT Referenced Series > Contour Image
// Sequence: every image of the series. Patient and study as the referenced series has them; new Series and
// SOP Instance UIDs. Structures without any voxel are not written.

#include "io/dicom_plan_structure.h"
#include "io/dicom_reference.h"

#include <filesystem>
#include <vector>

namespace curette::io {

// Atomic. Throws std::logic_error for a mask of another size, SystemError when the file cannot be written,
// InputError(path, ...) when DCMTK refuses a value.
void writeDicomRtStruct(const std::filesystem::path& path, const DicomReferencedSeries& series,
                        const std::vector<DicomPlanStructure>& structures, const DicomObjectInfo& info);

}  // namespace curette::io
