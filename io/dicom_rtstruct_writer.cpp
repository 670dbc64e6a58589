#include "io/dicom_rtstruct_writer.h"

#include "io/dcmtk_file.h"
#include "io/dcmtk_support.h"
#include "io/slice_contours.h"
#include "base/error.h"

#include <dcmtk/dcmdata/dcuid.h>
#include <dcmtk/dcmrt/drtstrct.h>

#include <algorithm>
#include <cmath>

namespace curette::io {

namespace {

void check(OFCondition status, const std::filesystem::path& path, const std::string& what) {
    if (status.bad()) throw InputError(path.string(), what, "a value DCMTK's dcmrt accepts", status.text());
}

}  // namespace

void writeDicomRtStruct(const std::filesystem::path& path, const DicomReferencedSeries& series,
                        const std::vector<DicomPlanStructure>& structures, const DicomObjectInfo& info) {
    silenceDcmtk();
    const glm::ivec3 dims = series.dims;
    const std::size_t pixels = std::size_t(dims.x) * std::size_t(dims.y);
    if (series.images.size() != std::size_t(dims.z)) throw std::logic_error("writeDicomRtStruct: one image reference per slice");
    for (const DicomPlanStructure& s : structures)
        if (s.mask.size() != pixels * std::size_t(dims.z)) throw std::logic_error("writeDicomRtStruct: a mask of another size");

    DRTStructureSetIOD rt;
    const DicomPatientStudy& who = series.patientStudy;
    const DicomDateTime now = dicomNow();
    check(rt.setSpecificCharacterSet("ISO_IR 192"), path, "SpecificCharacterSet");
    check(rt.setSOPClassUID(UID_RTStructureSetStorage), path, "SOPClassUID");
    check(rt.setSOPInstanceUID(newDicomUid().c_str()), path, "SOPInstanceUID");
    check(rt.setPatientName(who.patientName.c_str(), false), path, "PatientName");
    check(rt.setPatientID(who.patientId.c_str(), false), path, "PatientID");
    check(rt.setPatientBirthDate(who.patientBirthDate.c_str(), false), path, "PatientBirthDate");
    check(rt.setPatientSex(who.patientSex.c_str(), false), path, "PatientSex");
    check(rt.setStudyInstanceUID(who.studyInstanceUid.c_str()), path, "StudyInstanceUID");
    check(rt.setStudyDate(who.studyDate.c_str(), false), path, "StudyDate");
    check(rt.setStudyTime(who.studyTime.c_str(), false), path, "StudyTime");
    check(rt.setStudyID(who.studyId.c_str(), false), path, "StudyID");
    check(rt.setAccessionNumber(who.accessionNumber.c_str(), false), path, "AccessionNumber");
    check(rt.setReferringPhysicianName(who.referringPhysicianName.c_str(), false), path, "ReferringPhysicianName");
    check(rt.setStudyDescription(who.studyDescription.c_str(), false), path, "StudyDescription");
    check(rt.setModality("RTSTRUCT"), path, "Modality");
    check(rt.setSeriesInstanceUID(newDicomUid().c_str()), path, "SeriesInstanceUID");
    check(rt.setSeriesNumber(std::to_string(info.seriesNumber).c_str()), path, "SeriesNumber");
    check(rt.setSeriesDescription(info.seriesDescription.c_str()), path, "SeriesDescription");
    check(rt.setManufacturer("curette"), path, "Manufacturer");
    check(rt.setSoftwareVersions(info.softwareVersion.c_str(), false), path, "SoftwareVersions");
    check(rt.setOperatorsName(""), path, "OperatorsName");
    check(rt.setInstanceNumber("1"), path, "InstanceNumber");
    // The Frame of Reference module, which the RT Structure Set IOD lists in current editions of PS3.3 A.19.3.
    check(rt.setFrameOfReferenceUID(series.frameOfReferenceUid.c_str()), path, "FrameOfReferenceUID");
    check(rt.setPositionReferenceIndicator(""), path, "PositionReferenceIndicator");
    check(rt.setStructureSetLabel(info.contentLabel.c_str()), path, "StructureSetLabel");
    check(rt.setStructureSetDate(now.date.c_str()), path, "StructureSetDate");
    check(rt.setStructureSetTime(now.time.c_str()), path, "StructureSetTime");

    // Referenced Frame of Reference > RT Referenced Study > RT Referenced Series > every image.
    DRTReferencedFrameOfReferenceSequence::Item* frameOfReference = nullptr;
    check(rt.getReferencedFrameOfReferenceSequence().addItem(frameOfReference), path, "ReferencedFrameOfReferenceSequence");
    check(frameOfReference->setFrameOfReferenceUID(series.frameOfReferenceUid.c_str()), path, "FrameOfReferenceUID");
    DRTRTReferencedStudySequence::Item* study = nullptr;
    check(frameOfReference->getRTReferencedStudySequence().addItem(study), path, "RTReferencedStudySequence");
    // The Study Component Management SOP Class, as the Structure Set module asks (C.8.8.5).
    check(study->setReferencedSOPClassUID("1.2.840.10008.3.1.2.3.2"), path, "ReferencedSOPClassUID");
    check(study->setReferencedSOPInstanceUID(who.studyInstanceUid.c_str()), path, "ReferencedSOPInstanceUID");
    DRTRTReferencedSeriesSequence::Item* referencedSeries = nullptr;
    check(study->getRTReferencedSeriesSequence().addItem(referencedSeries), path, "RTReferencedSeriesSequence");
    check(referencedSeries->setSeriesInstanceUID(series.seriesInstanceUid.c_str()), path, "SeriesInstanceUID");
    for (const DicomImageReference& image : series.images) {
        DRTContourImageSequence::Item* item = nullptr;
        check(referencedSeries->getContourImageSequence().addItem(item), path, "ContourImageSequence");
        check(item->setReferencedSOPClassUID(image.sopClassUid.c_str()), path, "ReferencedSOPClassUID");
        check(item->setReferencedSOPInstanceUID(image.sopInstanceUid.c_str()), path, "ReferencedSOPInstanceUID");
    }

    int roiNumber = 0;
    for (const DicomPlanStructure& s : structures) {
        if (std::none_of(s.mask.begin(), s.mask.end(), [](std::uint8_t v) { return v != 0; })) continue;
        const std::string number = std::to_string(++roiNumber);
        DRTStructureSetROISequence::Item* roi = nullptr;
        check(rt.getStructureSetROISequence().addItem(roi), path, "StructureSetROISequence");
        check(roi->setROINumber(number.c_str()), path, "ROINumber");
        check(roi->setReferencedFrameOfReferenceUID(series.frameOfReferenceUid.c_str()), path, "ReferencedFrameOfReferenceUID");
        check(roi->setROIName(s.label.c_str()), path, "ROIName");
        if (!s.description.empty()) check(roi->setROIDescription(s.description.c_str()), path, "ROIDescription");
        check(roi->setROIGenerationAlgorithm(s.algorithmType.c_str()), path, "ROIGenerationAlgorithm");

        DRTROIContourSequence::Item* contours = nullptr;
        check(rt.getROIContourSequence().addItem(contours), path, "ROIContourSequence");
        check(contours->setReferencedROINumber(number.c_str()), path, "ReferencedROINumber");
        const std::string color = std::to_string(std::lround(std::clamp(s.color.r, 0.0, 1.0) * 255)) + "\\" +
                                  std::to_string(std::lround(std::clamp(s.color.g, 0.0, 1.0) * 255)) + "\\" +
                                  std::to_string(std::lround(std::clamp(s.color.b, 0.0, 1.0) * 255));
        check(contours->setROIDisplayColor(color.c_str()), path, "ROIDisplayColor");
        int contourNumber = 0;
        for (int k = 0; k < dims.z; ++k) {
            const std::uint8_t* slice = s.mask.data() + std::size_t(k) * pixels;
            if (std::none_of(slice, slice + pixels, [](std::uint8_t v) { return v != 0; })) continue;
            const DicomImageReference& image = series.images[std::size_t(k)];
            for (const std::vector<glm::dvec2>& outline : sliceOutlines(slice, dims.x, dims.y)) {
                DRTContourSequence::Item* contour = nullptr;
                check(contours->getContourSequence().addItem(contour), path, "ContourSequence");
                check(contour->setContourNumber(std::to_string(++contourNumber).c_str()), path, "ContourNumber");
                check(contour->setContourGeometricType("CLOSED_PLANAR"), path, "ContourGeometricType");
                check(contour->setNumberOfContourPoints(std::to_string(outline.size()).c_str()), path, "NumberOfContourPoints");
                std::vector<double> points;
                points.reserve(outline.size() * 3);
                for (const glm::dvec2& p : outline) {
                    glm::dvec3 lps = lpsOfIndex(series.indexToWorld, glm::dvec3(p, double(k)));
                    points.insert(points.end(), {lps.x, lps.y, lps.z});
                }
                check(contour->setContourData(decimalStrings(points).c_str(), false), path, "ContourData");
                DRTContourImageSequence::Item* onImage = nullptr;
                check(contour->getContourImageSequence().addItem(onImage), path, "ContourImageSequence");
                check(onImage->setReferencedSOPClassUID(image.sopClassUid.c_str()), path, "ReferencedSOPClassUID");
                check(onImage->setReferencedSOPInstanceUID(image.sopInstanceUid.c_str()), path, "ReferencedSOPInstanceUID");
            }
        }

        DRTRTROIObservationsSequence::Item* observation = nullptr;
        check(rt.getRTROIObservationsSequence().addItem(observation), path, "RTROIObservationsSequence");
        check(observation->setObservationNumber(number.c_str()), path, "ObservationNumber");
        check(observation->setReferencedROINumber(number.c_str()), path, "ReferencedROINumber");
        check(observation->setRTROIInterpretedType(s.interpretedType.c_str(), false), path, "RTROIInterpretedType");
        check(observation->setROIInterpreter(""), path, "ROIInterpreter");
    }
    if (roiNumber == 0) throw std::logic_error("writeDicomRtStruct: no structure has voxels");

    DcmFileFormat file;
    check(rt.write(*file.getDataset()), path, "RT Structure Set");
    saveDicomAtomically(file, path);
}

}  // namespace curette::io
