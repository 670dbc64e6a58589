#include "io/dicom_reference.h"

#include "io/dcmtk_support.h"

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>

#include <cmath>

namespace curette::io {

namespace {

std::string text(DcmItem& item, const DcmTagKey& tag) {
    OFString value;
    if (item.findAndGetOFStringArray(tag, value).bad()) return {};
    return value.c_str();
}

}  // namespace

glm::dvec3 lpsOfIndex(const glm::dmat4& indexToWorld, const glm::dvec3& index) {
    glm::dvec3 ras = glm::dvec3(indexToWorld * glm::dvec4(index, 1.0));
    return {-ras.x, -ras.y, ras.z};
}

DicomSourceReading readDicomSourceSeries(const VolumeData& volume) {
    silenceDcmtk();
    DicomSourceReading reading;
    if (volume.files.size() != static_cast<std::size_t>(volume.dims.z)) {
        reading.problem = "the series is " + std::to_string(volume.files.size()) + " file(s) for " + std::to_string(volume.dims.z) +
                          " slices (multi-frame images are not referenced frame by frame)";
        return reading;
    }
    DicomReferencedSeries series;
    series.dims = volume.dims;
    series.indexToWorld = volume.indexToWorld;
    for (std::size_t k = 0; k < volume.files.size(); ++k) {
        const std::string slice = "slice " + std::to_string(k);
        DcmFileFormat file;
        if (file.loadFile(volume.files[k].c_str()).bad()) {
            reading.problem = slice + " cannot be read again";
            return reading;
        }
        DcmDataset& data = *file.getDataset();
        if (k == 0) {
            DicomPatientStudy& who = series.patientStudy;
            who.patientName = text(data, DCM_PatientName);
            who.patientId = text(data, DCM_PatientID);
            who.patientBirthDate = text(data, DCM_PatientBirthDate);
            who.patientSex = text(data, DCM_PatientSex);
            who.studyInstanceUid = text(data, DCM_StudyInstanceUID);
            who.studyDate = text(data, DCM_StudyDate);
            who.studyTime = text(data, DCM_StudyTime);
            who.studyId = text(data, DCM_StudyID);
            who.accessionNumber = text(data, DCM_AccessionNumber);
            who.referringPhysicianName = text(data, DCM_ReferringPhysicianName);
            who.studyDescription = text(data, DCM_StudyDescription);
            series.seriesInstanceUid = text(data, DCM_SeriesInstanceUID);
            series.frameOfReferenceUid = text(data, DCM_FrameOfReferenceUID);
            series.modality = text(data, DCM_Modality);
            if (who.studyInstanceUid.empty() || series.seriesInstanceUid.empty() || series.frameOfReferenceUid.empty()) {
                reading.problem = "the series has no StudyInstanceUID, SeriesInstanceUID or FrameOfReferenceUID";
                return reading;
            }
        } else if (text(data, DCM_SeriesInstanceUID) != series.seriesInstanceUid ||
                   text(data, DCM_FrameOfReferenceUID) != series.frameOfReferenceUid) {
            reading.problem = slice + " is of another series or Frame of Reference";
            return reading;
        }
        Sint32 frames = 1;
        if (data.findAndGetSint32(DCM_NumberOfFrames, frames).good() && frames > 1) {
            reading.problem = slice + " is a multi-frame image";
            return reading;
        }
        Uint16 rows = 0, columns = 0;
        data.findAndGetUint16(DCM_Rows, rows);
        data.findAndGetUint16(DCM_Columns, columns);
        if (columns != volume.dims.x || rows != volume.dims.y) {
            reading.problem = slice + " is not " + std::to_string(volume.dims.x) + " x " + std::to_string(volume.dims.y) + " pixels";
            return reading;
        }
        DicomImageReference image;
        image.sopClassUid = text(data, DCM_SOPClassUID);
        image.sopInstanceUid = text(data, DCM_SOPInstanceUID);
        glm::dvec3 expected = lpsOfIndex(volume.indexToWorld, glm::dvec3(0.0, 0.0, double(k)));
        for (int axis = 0; axis < 3; ++axis) {
            Float64 value = 0;
            if (data.findAndGetFloat64(DCM_ImagePositionPatient, value, axis).bad()) {
                reading.problem = slice + " has no ImagePositionPatient";
                return reading;
            }
            image.positionLps[axis] = value;
        }
        if (image.sopClassUid.empty() || image.sopInstanceUid.empty()) {
            reading.problem = slice + " has no SOPClassUID or SOPInstanceUID";
            return reading;
        }
        if (glm::length(image.positionLps - expected) > 0.01) {
            reading.problem = slice + "'s ImagePositionPatient is not where the volume places slice " + std::to_string(k);
            return reading;
        }
        series.images.push_back(std::move(image));
    }
    reading.series = std::move(series);
    return reading;
}

DicomPatientStudy anonymousPatientStudy() {
    DicomPatientStudy who;
    who.patientName = "Anonymized";
    who.patientId = "ANON";
    who.studyInstanceUid = newDicomUid();
    DicomDateTime now = dicomNow();
    who.studyDate = now.date;
    who.studyTime = now.time;
    return who;
}

}  // namespace curette::io
