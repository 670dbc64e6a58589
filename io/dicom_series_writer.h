#pragma once
// A volume as a classic DICOM image series, so that a plan drawn on a NIfTI, NRRD or MetaImage scan has a
// DICOM scan to sit on (the SEG and RTSTRUCT reference it; a navigation system loads the pair). One
// single-frame file a slice, `slice-0001.dcm` on, explicit VR little endian, written with DCMTK's dcmdata:
//   SOP Class CT Image Storage (modality "CT", PS3.3 A.3) or MR Image Storage ("MR", A.4), new Study (when
//   the patient/study record has none), Series, Frame of Reference and SOP Instance UIDs;
//   geometry from the affine (PS3.3 C.7.6.2.1.1): ImageOrientationPatient = the LPS directions of the i and j
//   axes, PixelSpacing = their lengths (row spacing |j| first), ImagePositionPatient = slice k's voxel
//   (0, 0, k) in LPS, SliceThickness = the k axis's length;
//   pixels 16-bit: the values as they are when every one is an integer that fits (signed for CT, unsigned
//   otherwise), else mapped linearly onto the 16-bit range with RescaleSlope/RescaleIntercept (CT; MR keeps
//   them too, which dciodvfy notes as not in the IOD); voxels without data take the lowest stored value.
// The i and j axes must be orthogonal (DICOM has no shear within a slice); otherwise an InputError names
// the affine. Slices may be stacked obliquely (the positions say where).

#include "io/dicom_reference.h"
#include "base/volume.h"

#include <filesystem>
#include <string>

namespace curette::io {

struct DicomSeriesWriteOptions {
    std::string modality = "MR";      // "CT" or "MR"
    std::string seriesDescription;
    int seriesNumber = 1;
    std::string softwareVersion;      // SoftwareVersions (0018,1020)
};

// Writes the series into `directory` (created; each file atomically) and returns it as the objects will
// reference it. `patientStudy` is repeated in every file; an empty studyInstanceUid gets a new one.
DicomReferencedSeries writeDicomSeries(const std::filesystem::path& directory, const VolumeData& volume, DicomPatientStudy patientStudy,
                                       const DicomSeriesWriteOptions& options);

// CT when the values reach below -200 (air and fat in Hounsfield units), MR otherwise: what a NIfTI, NRRD or
// MetaImage file does not say.
std::string guessModality(const VolumeData& volume);

}  // namespace curette::io
