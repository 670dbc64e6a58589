#include "io/dicom_series_writer.h"

#include "io/dcmtk_file.h"
#include "io/dcmtk_support.h"
#include "base/error.h"

#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcuid.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace curette::io {

namespace fs = std::filesystem;

namespace {

// How physical values become 16-bit stored values: stored = round((value - intercept) / slope).
struct PixelEncoding {
    bool isSigned = true;
    double slope = 1.0, intercept = 0.0;
    double lowest = 0.0;   // stored value for voxels without data
};

PixelEncoding encodingFor(const VolumeData& volume, bool ct) {
    bool integral = true;
    for (std::size_t n = 0; n < volume.voxelCount() && integral; ++n) {
        if (volume.isNoData(n)) continue;
        double v = volume.valueScale * volume.normalized(n) + volume.valueOffset;
        integral = std::abs(v - std::round(v)) < 1e-6;
    }
    PixelEncoding e;
    e.isSigned = ct || volume.minValue < 0.0;
    const double low = e.isSigned ? -32768.0 : 0.0, high = e.isSigned ? 32767.0 : 65535.0;
    if (integral && volume.minValue >= low && volume.maxValue <= high) {
        e.lowest = std::round(volume.minValue);
        return e;
    }
    double range = std::max(volume.maxValue - volume.minValue, 1e-12);
    e.slope = range / (high - low);
    e.intercept = volume.minValue - low * e.slope;
    e.lowest = low;
    return e;
}

void put(DcmDataset& data, const DcmTagKey& tag, const std::string& value) {
    OFCondition status = data.putAndInsertOFStringArray(tag, value.c_str());
    if (status.bad()) throw std::logic_error(std::string("writeDicomSeries: cannot set ") + DcmTag(tag).getTagName() + ": " + status.text());
}

void put(DcmDataset& data, const DcmTagKey& tag, Uint16 value) {
    OFCondition status = data.putAndInsertUint16(tag, value);
    if (status.bad()) throw std::logic_error(std::string("writeDicomSeries: cannot set ") + DcmTag(tag).getTagName() + ": " + status.text());
}

}  // namespace

std::string guessModality(const VolumeData& volume) { return volume.minValue < -200.0 ? "CT" : "MR"; }

DicomReferencedSeries writeDicomSeries(const fs::path& directory, const VolumeData& volume, DicomPatientStudy who,
                                       const DicomSeriesWriteOptions& options) {
    silenceDcmtk();
    const bool ct = options.modality == "CT";
    if (!ct && options.modality != "MR") throw std::logic_error("writeDicomSeries: modality " + options.modality);
    const glm::dmat3 axesRas(volume.indexToWorld);
    const glm::dmat3 toLps(glm::dvec3(-1, 0, 0), glm::dvec3(0, -1, 0), glm::dvec3(0, 0, 1));
    const glm::dvec3 iAxis = toLps * axesRas[0], jAxis = toLps * axesRas[1], kAxis = toLps * axesRas[2];
    const double columnSpacing = glm::length(iAxis), rowSpacing = glm::length(jAxis);
    if (columnSpacing <= 0 || rowSpacing <= 0 || std::abs(glm::dot(iAxis, jAxis)) > 1e-6 * columnSpacing * rowSpacing)
        throw InputError(volume.source, "affine", "orthogonal i and j axes to write the scan as a DICOM series (DICOM has no in-plane shear)");
    if (volume.dims.x > 65535 || volume.dims.y > 65535) throw InputError(volume.source, "dims", "at most 65535 columns and rows for DICOM");

    std::error_code ec;
    fs::create_directories(directory, ec);
    if (ec) throw SystemError(directory.string() + ": cannot create the directory (" + ec.message() + ")");

    DicomReferencedSeries series;
    if (who.studyInstanceUid.empty()) who.studyInstanceUid = newDicomUid();
    DicomDateTime now = dicomNow();
    if (who.studyDate.empty()) who.studyDate = now.date;
    if (who.studyTime.empty()) who.studyTime = now.time;
    series.patientStudy = who;
    series.seriesInstanceUid = newDicomUid();
    series.frameOfReferenceUid = newDicomUid();
    series.modality = options.modality;
    series.dims = volume.dims;
    series.indexToWorld = volume.indexToWorld;
    const std::string sopClass = ct ? UID_CTImageStorage : UID_MRImageStorage;
    const PixelEncoding encoding = encodingFor(volume, ct);
    const glm::dvec3 x = iAxis / columnSpacing, y = jAxis / rowSpacing;
    const std::string orientation = decimalStrings({x.x, x.y, x.z, y.x, y.y, y.z});
    const std::string spacing = decimalStrings({rowSpacing, columnSpacing});
    const double window = volume.maxValue - volume.minValue, centre = 0.5 * (volume.maxValue + volume.minValue);
    const std::size_t pixels = std::size_t(volume.dims.x) * std::size_t(volume.dims.y);

    for (int k = 0; k < volume.dims.z; ++k) {
        DcmFileFormat file;
        DcmDataset& data = *file.getDataset();
        DicomImageReference image{sopClass, newDicomUid(), lpsOfIndex(volume.indexToWorld, glm::dvec3(0.0, 0.0, double(k)))};
        put(data, DCM_SpecificCharacterSet, "ISO_IR 192");
        put(data, DCM_SOPClassUID, sopClass);
        put(data, DCM_SOPInstanceUID, image.sopInstanceUid);
        put(data, DCM_ImageType, ct ? "DERIVED\\SECONDARY\\AXIAL" : "DERIVED\\SECONDARY\\OTHER");
        put(data, DCM_StudyDate, who.studyDate);
        put(data, DCM_StudyTime, who.studyTime);
        put(data, DCM_ContentDate, now.date);
        put(data, DCM_ContentTime, now.time);
        put(data, DCM_AccessionNumber, who.accessionNumber);
        put(data, DCM_Modality, options.modality);
        put(data, DCM_Manufacturer, "curette");
        put(data, DCM_ReferringPhysicianName, who.referringPhysicianName);
        put(data, DCM_StudyDescription, who.studyDescription);
        put(data, DCM_SeriesDescription, options.seriesDescription);
        put(data, DCM_DerivationDescription, "converted by curette from a volume file");
        put(data, DCM_PatientName, who.patientName);
        put(data, DCM_PatientID, who.patientId);
        put(data, DCM_PatientBirthDate, who.patientBirthDate);
        put(data, DCM_PatientSex, who.patientSex);
        put(data, DCM_SoftwareVersions, options.softwareVersion);
        put(data, DCM_SliceThickness, decimalString(glm::length(kAxis)));
        if (ct) {
            put(data, DCM_KVP, "");
        } else {
            // MR Image module (PS3.3 C.8.3.1): what a converted volume can say; RM = research mode.
            put(data, DCM_ScanningSequence, "RM");
            put(data, DCM_SequenceVariant, "NONE");
            put(data, DCM_ScanOptions, "");
            put(data, DCM_MRAcquisitionType, "3D");
            put(data, DCM_EchoTime, "");
            put(data, DCM_RepetitionTime, "");
            put(data, DCM_EchoTrainLength, "");
            put(data, DCM_SpacingBetweenSlices, decimalString(glm::length(kAxis)));
        }
        put(data, DCM_StudyInstanceUID, who.studyInstanceUid);
        put(data, DCM_SeriesInstanceUID, series.seriesInstanceUid);
        put(data, DCM_StudyID, who.studyId);
        put(data, DCM_SeriesNumber, std::to_string(options.seriesNumber));
        put(data, DCM_Laterality, "");
        put(data, DCM_PatientPosition, "");
        put(data, DCM_AcquisitionNumber, "");
        put(data, DCM_InstanceNumber, std::to_string(k + 1));
        put(data, DCM_ImagePositionPatient, decimalStrings({image.positionLps.x, image.positionLps.y, image.positionLps.z}));
        put(data, DCM_ImageOrientationPatient, orientation);
        put(data, DCM_FrameOfReferenceUID, series.frameOfReferenceUid);
        put(data, DCM_PositionReferenceIndicator, "");
        put(data, DCM_SamplesPerPixel, Uint16(1));
        put(data, DCM_PhotometricInterpretation, "MONOCHROME2");
        put(data, DCM_Rows, Uint16(volume.dims.y));
        put(data, DCM_Columns, Uint16(volume.dims.x));
        put(data, DCM_PixelSpacing, spacing);
        put(data, DCM_BitsAllocated, Uint16(16));
        put(data, DCM_BitsStored, Uint16(16));
        put(data, DCM_HighBit, Uint16(15));
        put(data, DCM_PixelRepresentation, Uint16(encoding.isSigned ? 1 : 0));
        put(data, DCM_WindowCenter, decimalString(centre));
        put(data, DCM_WindowWidth, decimalString(std::max(window, 1.0)));
        if (ct || encoding.slope != 1.0 || encoding.intercept != 0.0) {   // not in the MR Image IOD: only when needed
            put(data, DCM_RescaleIntercept, decimalString(encoding.intercept));
            put(data, DCM_RescaleSlope, decimalString(encoding.slope));
        }
        if (ct) put(data, DCM_RescaleType, "HU");

        std::vector<Uint16> stored(pixels);
        const double low = encoding.isSigned ? -32768.0 : 0.0, high = encoding.isSigned ? 32767.0 : 65535.0;
        for (std::size_t p = 0; p < pixels; ++p) {
            std::size_t n = std::size_t(k) * pixels + p;
            double s = volume.isNoData(n) ? encoding.lowest
                                          : std::round((volume.valueScale * volume.normalized(n) + volume.valueOffset - encoding.intercept) / encoding.slope);
            s = std::clamp(s, low, high);
            stored[p] = encoding.isSigned ? static_cast<Uint16>(static_cast<Sint16>(s)) : static_cast<Uint16>(s);
        }
        OFCondition status = data.putAndInsertUint16Array(DCM_PixelData, stored.data(), static_cast<unsigned long>(stored.size()));
        if (status.bad()) throw std::logic_error(std::string("writeDicomSeries: pixel data: ") + status.text());

        char name[32];
        std::snprintf(name, sizeof name, "slice-%04d.dcm", k + 1);
        saveDicomAtomically(file, directory / name);
        series.images.push_back(std::move(image));
    }
    return series;
}

}  // namespace curette::io
