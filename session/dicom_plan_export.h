#pragma once
// The plan as DICOM, for PACS and navigation systems (`curette report --dicom`): seg.dcm (a Segmentation,
// io/dicom_seg_writer.h) and rtstruct.dcm (an RT Structure Set, io/dicom_rtstruct_writer.h) of the removed
// region and of every protected or touched structure, on the scan's grid, referencing
//   - the DICOM series the scan was read from (same Study, Frame of Reference and images), when it came from
//     DICOM as one single-frame image per slice and --anonymize is not given; or
//   - the scan written as a DICOM series into `scan-dicom/` (io/dicom_series_writer.h: new UIDs, one Frame of
//     Reference), when it came from NIfTI, NRRD or MetaImage, when the DICOM source cannot be referenced
//     slice by slice, or with --anonymize (so that nothing links the objects back to the patient).
// The objects carry the source's patient and study identifiers (none for a non-DICOM scan); --anonymize
// replaces them (io/dicom_reference.h anonymousPatientStudy). The summary names neither.
//
// Segments and ROIs, in order:
//   "removed region": the carve's removed region R (removed.nii.gz's 1s); category 309825002 SCT "Spatial
//   and Relational Concept", type REMOVED 99CURETTE "Planned removal region" (no standard code names a
//   planned resection volume), SEMIAUTOMATIC "curette carve", RTROIInterpretedType CAVITY;
//   each structure the report lists as protected or touched, in the report's order: its label's voxels;
//   category 91723000 SCT "Anatomical Structure", type L<set>-<id> 99CURETTE "<label name>" (atlas labels
//   carry no SNOMED code), AUTOMATIC "curette label resampling", the label table's colour, CAVITY's
//   counterpart AVOIDANCE when protected, ORGAN otherwise.
// Empty regions are left out (a nothing-removed carve writes its structures only; nothing at all: no files).

#include "session/loaded_scene.h"
#include "plan/removal_report.h"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace curette {

struct DicomExportOptions {
    bool anonymize = false;
    std::string programVersion;   // SoftwareVersions
};

// Writes the files into `directory` (which exists) and returns the terminal's lines saying what was written
// and which series the objects reference, and why.
std::string writePlanDicom(const std::filesystem::path& directory, const LoadedScene& loaded, const plan::Report& report,
                           const std::vector<std::uint8_t>& removedRegion, const DicomExportOptions& options);

}  // namespace curette
