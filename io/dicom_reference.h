#pragma once
// The image series a DICOM plan object (io/dicom_seg_writer.h, io/dicom_rtstruct_writer.h) is drawn on, and
// whom it belongs to. A Segmentation or an RT Structure Set is matched to its scan by the Patient and General
// Study modules (PS3.3 C.7.1.1, C.7.2.1), one Frame of Reference (C.7.4.1) and references to each image by
// SOP Class and Instance UID (C.7.6.16.2.6 Derivation Image, C.8.8.5 Structure Set). Either the series the
// volume was read from (readDicomSourceSeries) or one curette writes from the volume
// (io/dicom_series_writer.h).
//
// Patient identifiers travel only inside these records and the objects written from them: no message,
// log line or description names them.

#include "base/volume.h"

#include <glm/glm.hpp>

#include <optional>
#include <string>
#include <vector>

namespace curette::io {

// Patient (C.7.1.1) and General Study (C.7.2.1) attributes, copied as the source holds them.
struct DicomPatientStudy {
    std::string patientName, patientId, patientBirthDate, patientSex;
    std::string studyInstanceUid, studyDate, studyTime, studyId, accessionNumber, referringPhysicianName, studyDescription;
};

// One image of the referenced series: slice k of the grid.
struct DicomImageReference {
    std::string sopClassUid, sopInstanceUid;
    glm::dvec3 positionLps{0.0};  // ImagePositionPatient (0020,0032): the centre of its first pixel, LPS mm
};

struct DicomReferencedSeries {
    DicomPatientStudy patientStudy;
    std::string seriesInstanceUid, frameOfReferenceUid, modality;
    glm::ivec3 dims{0};               // columns, rows, slices: the volume's grid
    glm::dmat4 indexToWorld{1.0};     // voxel centre (i,j,k) -> RAS mm, as VolumeData
    std::vector<DicomImageReference> images;  // images[k] is slice k
};

// The DICOM series `volume` was read from (its `files`, one single-frame image per slice in slice order, as
// io/dicom.h leaves them), read again with DCMTK for the identifiers and UIDs the objects must repeat. When
// the series cannot be referenced slice by slice (a multi-frame file, an image whose size or
// ImagePositionPatient is not slice k's of the grid within 0.01 mm, a missing UID), `series` is empty and
// `problem` says why, without naming the patient.
struct DicomSourceReading {
    std::optional<DicomReferencedSeries> series;
    std::string problem;
};
DicomSourceReading readDicomSourceSeries(const VolumeData& volume);

// Patient and study for objects that must not identify anyone (`--anonymize`, PS3.15 E.1: the identifying
// attributes replaced): name "Anonymized", ID "ANON", no birth date or sex, a new Study Instance UID, study
// date and time of now, no accession number or physician.
DicomPatientStudy anonymousPatientStudy();

// The LPS position of index-space point (i, j, k) under a RAS index-to-world affine (DICOM is LPS: PS3.3
// C.7.6.2.1.1).
glm::dvec3 lpsOfIndex(const glm::dmat4& indexToWorld, const glm::dvec3& index);

}  // namespace curette::io
