#include "io/dicom_seg_writer.h"

#include "io/dcmtk_file.h"
#include "io/dcmtk_support.h"
#include "base/error.h"

#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmfg/fgderimg.h>
#include <dcmtk/dcmfg/fgfracon.h>
#include <dcmtk/dcmfg/fgpixmsr.h>
#include <dcmtk/dcmfg/fgplanor.h>
#include <dcmtk/dcmfg/fgplanpo.h>
#include <dcmtk/dcmiod/cielabutil.h>
#include <dcmtk/dcmseg/segdoc.h>
#include <dcmtk/dcmseg/segment.h>

#include <algorithm>
#include <cmath>
#include <memory>

namespace curette::io {

namespace {

void check(OFCondition status, const std::filesystem::path& path, const std::string& what) {
    if (status.bad()) throw InputError(path.string(), what, "a value DCMTK's dcmseg accepts", status.text());
}

DcmSegTypes::E_SegmentAlgoType algorithmType(const std::string& name) {
    if (name == "MANUAL") return DcmSegTypes::SAT_MANUAL;
    if (name == "AUTOMATIC") return DcmSegTypes::SAT_AUTOMATIC;
    if (name == "SEMIAUTOMATIC") return DcmSegTypes::SAT_SEMIAUTOMATIC;
    throw std::logic_error("writeDicomSegmentation: algorithm type " + name);
}

}  // namespace

void writeDicomSegmentation(const std::filesystem::path& path, const DicomReferencedSeries& series,
                            const std::vector<DicomPlanStructure>& structures, const DicomObjectInfo& info) {
    silenceDcmtk();
    const glm::ivec3 dims = series.dims;
    const std::size_t pixels = std::size_t(dims.x) * std::size_t(dims.y);
    if (series.images.size() != std::size_t(dims.z)) throw std::logic_error("writeDicomSegmentation: one image reference per slice");
    for (const DicomPlanStructure& s : structures)
        if (s.mask.size() != pixels * std::size_t(dims.z)) throw std::logic_error("writeDicomSegmentation: a mask of another size");

    DcmSegmentation* created = nullptr;
    IODGeneralEquipmentModule::EquipmentInfo equipment("curette", "curette", "1", info.softwareVersion.empty() ? "unknown" : info.softwareVersion);
    ContentIdentificationMacro content("1", info.contentLabel, "the surgical plan of a carve", "");
    check(DcmSegmentation::createBinarySegmentation(created, Uint16(dims.y), Uint16(dims.x), equipment, content), path, "Segmentation");
    std::unique_ptr<DcmSegmentation> seg(created);

    const DicomPatientStudy& who = series.patientStudy;
    IODPatientModule& patient = seg->getPatient();
    check(patient.setPatientName(who.patientName.c_str(), false), path, "PatientName");
    check(patient.setPatientID(who.patientId.c_str(), false), path, "PatientID");
    check(patient.setPatientBirthDate(who.patientBirthDate.c_str(), false), path, "PatientBirthDate");
    check(patient.setPatientSex(who.patientSex.c_str(), false), path, "PatientSex");
    IODGeneralStudyModule& study = seg->getStudy();
    check(study.setStudyInstanceUID(who.studyInstanceUid.c_str()), path, "StudyInstanceUID");
    check(study.setStudyDate(who.studyDate.c_str(), false), path, "StudyDate");
    check(study.setStudyTime(who.studyTime.c_str(), false), path, "StudyTime");
    check(study.setStudyID(who.studyId.c_str(), false), path, "StudyID");
    check(study.setAccessionNumber(who.accessionNumber.c_str(), false), path, "AccessionNumber");
    check(study.setReferringPhysicianName(who.referringPhysicianName.c_str(), false), path, "ReferringPhysicianName");
    check(study.setStudyDescription(who.studyDescription.c_str(), false), path, "StudyDescription");
    check(seg->getFrameOfReference().setFrameOfReferenceUID(series.frameOfReferenceUid.c_str()), path, "FrameOfReferenceUID");
    check(seg->getSeries().setSeriesInstanceUID(newDicomUid().c_str()), path, "SeriesInstanceUID");
    check(seg->getSeries().setSeriesNumber(std::to_string(info.seriesNumber).c_str()), path, "SeriesNumber");
    check(seg->getSeries().setSeriesDescription(info.seriesDescription.c_str()), path, "SeriesDescription");
    check(seg->getSOPCommon().setSOPInstanceUID(newDicomUid().c_str()), path, "SOPInstanceUID");
    check(seg->getSOPCommon().setSpecificCharacterSet("ISO_IR 192"), path, "SpecificCharacterSet");
    DicomDateTime now = dicomNow();
    check(seg->getGeneralImage().setContentDate(now.date.c_str()), path, "ContentDate");
    check(seg->getGeneralImage().setContentTime(now.time.c_str()), path, "ContentTime");

    // The grid: one orientation and spacing for every frame.
    const glm::dmat3 axesRas(series.indexToWorld);
    const glm::dmat3 toLps(glm::dvec3(-1, 0, 0), glm::dvec3(0, -1, 0), glm::dvec3(0, 0, 1));
    const glm::dvec3 iAxis = toLps * axesRas[0], jAxis = toLps * axesRas[1], kAxis = toLps * axesRas[2];
    const glm::dvec3 x = glm::normalize(iAxis), y = glm::normalize(jAxis);
    std::unique_ptr<FGPlaneOrientationPatient> orientation(FGPlaneOrientationPatient::createMinimal(
        decimalString(x.x).c_str(), decimalString(x.y).c_str(), decimalString(x.z).c_str(), decimalString(y.x).c_str(),
        decimalString(y.y).c_str(), decimalString(y.z).c_str()));
    check(seg->addForAllFrames(*orientation), path, "PlaneOrientationSequence");
    FGPixelMeasures measures;
    check(measures.setPixelSpacing(decimalStrings({glm::length(jAxis), glm::length(iAxis)}).c_str()), path, "PixelSpacing");
    // Along the slice normal (PS3.3 C.7.6.2.1.1 as the source's SliceThickness would be).
    const double sliceStep = std::abs(glm::dot(kAxis, glm::normalize(glm::cross(x, y))));
    check(measures.setSliceThickness(decimalString(sliceStep).c_str()), path, "SliceThickness");
    check(measures.setSpacingBetweenSlices(decimalString(sliceStep).c_str()), path, "SpacingBetweenSlices");
    check(seg->addForAllFrames(measures), path, "PixelMeasuresSequence");

    const std::string dimensionUid = newDicomUid();
    IODMultiframeDimensionModule& dimensions = seg->getDimensions();
    check(dimensions.addDimensionIndex(DCM_ReferencedSegmentNumber, dimensionUid.c_str(), DCM_SegmentIdentificationSequence,
                                       "ReferencedSegmentNumber"),
          path, "DimensionIndexSequence");
    check(dimensions.addDimensionIndex(DCM_ImagePositionPatient, dimensionUid.c_str(), DCM_PlanePositionSequence, "ImagePositionPatient"), path,
          "DimensionIndexSequence");

    const CodeSequenceMacro derivationCode("113076", "DCM", "Segmentation");
    const CodeSequenceMacro purpose("121322", "DCM", "Source image for image processing operation");
    std::vector<std::uint8_t> frame(pixels);
    // Every frame's bits in one stream, frame after frame without padding (PS3.5 8.1.1), LSB first: written
    // over DCMTK's own PixelData below, because dcmseg 3.6.7 loses a byte per frame from the third frame on
    // when rows x columns is not a multiple of 8 (found by pydicom on the 181 x 217 head).
    std::vector<std::uint8_t> packed;
    std::size_t bit = 0;
    for (const DicomPlanStructure& s : structures) {
        if (std::none_of(s.mask.begin(), s.mask.end(), [](std::uint8_t v) { return v != 0; })) continue;
        DcmSegment* segment = nullptr;
        check(DcmSegment::create(segment, s.label.c_str(), CodeSequenceMacro(s.category.value.c_str(), s.category.scheme.c_str(), s.category.meaning.c_str()),
                                 CodeSequenceMacro(s.type.value.c_str(), s.type.scheme.c_str(), s.type.meaning.c_str()), algorithmType(s.algorithmType),
                                 s.algorithmName.c_str()),
              path, "Segment " + s.label);
        if (!s.description.empty()) check(segment->setSegmentDescription(s.description.c_str()), path, "SegmentDescription");
        double L = 0, a = 0, b = 0;
        IODCIELabUtil::rgb2DicomLab(L, a, b, s.color.r, s.color.g, s.color.b);
        check(segment->setRecommendedDisplayCIELabValue(Uint16(std::lround(L)), Uint16(std::lround(a)), Uint16(std::lround(b))), path,
              "RecommendedDisplayCIELabValue");
        Uint16 number = 0;
        OFCondition added = seg->addSegment(segment, number);
        if (added.bad()) delete segment;
        check(added, path, "SegmentSequence");

        for (int k = 0; k < dims.z; ++k) {
            const std::uint8_t* slice = s.mask.data() + std::size_t(k) * pixels;
            if (std::none_of(slice, slice + pixels, [](std::uint8_t v) { return v != 0; })) continue;
            std::copy(slice, slice + pixels, frame.begin());
            const DicomImageReference& image = series.images[std::size_t(k)];
            std::unique_ptr<FGPlanePosPatient> position(FGPlanePosPatient::createMinimal(
                decimalString(image.positionLps.x).c_str(), decimalString(image.positionLps.y).c_str(), decimalString(image.positionLps.z).c_str()));
            FGFrameContent frameContent;
            check(frameContent.setDimensionIndexValues(number, 0), path, "DimensionIndexValues");
            check(frameContent.setDimensionIndexValues(Uint32(k + 1), 1), path, "DimensionIndexValues");
            ImageSOPInstanceReferenceMacro source;
            check(source.setReferencedSOPClassUID(image.sopClassUid.c_str()), path, "ReferencedSOPClassUID");
            check(source.setReferencedSOPInstanceUID(image.sopInstanceUid.c_str()), path, "ReferencedSOPInstanceUID");
            OFVector<ImageSOPInstanceReferenceMacro> sources(1, source);
            std::unique_ptr<FGDerivationImage> derivation(FGDerivationImage::createMinimal(sources, "the carve's removed region and the atlas structures",
                                                                                           derivationCode, purpose));
            if (!derivation) throw InputError(path.string(), "DerivationImageSequence", "a source image reference DCMTK accepts");
            OFVector<FGBase*> perFrame;
            perFrame.push_back(position.get());
            perFrame.push_back(&frameContent);
            perFrame.push_back(derivation.get());
            check(seg->addFrame(frame.data(), number, perFrame), path, "frame of segment " + s.label);
            packed.resize((bit + pixels + 7) / 8, 0);
            for (std::size_t p = 0; p < pixels; ++p, ++bit)
                if (frame[p]) packed[bit >> 3] = std::uint8_t(packed[bit >> 3] | (1u << (bit & 7)));
        }
    }
    if (seg->getNumberOfSegments() == 0) throw std::logic_error("writeDicomSegmentation: no structure has voxels");

    // Every image of the series, in the Referenced Series Sequence (C.12.2).
    auto* referenced = new IODSeriesAndInstanceReferenceMacro::ReferencedSeriesItem;
    check(referenced->setSeriesInstanceUID(series.seriesInstanceUid.c_str()), path, "ReferencedSeriesSequence");
    for (const DicomImageReference& image : series.images)
        check(referenced->addReference(image.sopClassUid.c_str(), image.sopInstanceUid.c_str()), path, "ReferencedInstanceSequence");
    seg->getCommonInstanceReference().getReferencedSeriesItems().push_back(referenced);

    DcmFileFormat file;
    check(seg->writeDataset(*file.getDataset()), path, "Segmentation");
    if (packed.size() % 2) packed.push_back(0);   // even length (PS3.5 7.1.1)
    check(file.getDataset()->putAndInsertUint8Array(DCM_PixelData, packed.data(), static_cast<unsigned long>(packed.size())), path, "PixelData");
    saveDicomAtomically(file, path);
}

}  // namespace curette::io
