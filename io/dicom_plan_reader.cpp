#include "io/dicom_plan_reader.h"

#include "io/dcmtk_support.h"
#include "base/error.h"

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmfg/fginterface.h>
#include <dcmtk/dcmfg/fgpixmsr.h>
#include <dcmtk/dcmfg/fgplanor.h>
#include <dcmtk/dcmfg/fgplanpo.h>
#include <dcmtk/dcmfg/fgseg.h>
#include <dcmtk/dcmiod/cielabutil.h>
#include <dcmtk/dcmseg/segdoc.h>
#include <dcmtk/dcmseg/segment.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <set>

namespace curette::io {

namespace fs = std::filesystem;

const char* const kSegmentationStorage = "1.2.840.10008.5.1.4.1.1.66.4";
const char* const kRtStructureSetStorage = "1.2.840.10008.5.1.4.1.1.481.3";

std::string dicomSopClassOf(const fs::path& file) {
    silenceDcmtk();
    DcmFileFormat format;
    if (format.loadFile(file.c_str(), EXS_Unknown, EGL_noChange, 4096).bad()) return {};
    OFString value;
    if (format.getDataset()->findAndGetOFString(DCM_SOPClassUID, value).bad()) return {};
    return value.c_str();
}

namespace {

template <class Group>
Group* group(FGInterface& groups, Uint32 frame, DcmFGTypes::E_FGType type) {
    return dynamic_cast<Group*>(groups.get(frame, type));
}

}  // namespace

DicomSegmentationVolume readDicomSegmentation(const fs::path& path) {
    silenceDcmtk();
    const std::string file = path.string();
    DcmFileFormat format;
    if (format.loadFile(path.c_str()).bad()) throw InputError(file, "", "a DICOM file DCMTK reads");
    DcmDataset& data = *format.getDataset();
    DcmSegmentation* loaded = nullptr;
    OFCondition status = DcmSegmentation::loadDataset(data, loaded);
    std::unique_ptr<DcmSegmentation> seg(loaded);
    if (status.bad() || !seg) throw InputError(file, "SOPClassUID", "a DICOM Segmentation DCMTK's dcmseg loads", status.text());
    const bool binary = seg->getSegmentationType() == DcmSegTypes::ST_BINARY;
    if (!binary && seg->getSegmentationType() != DcmSegTypes::ST_FRACTIONAL)
        throw InputError(file, "SegmentationType", "BINARY or FRACTIONAL");
    Uint16 rows = 0, columns = 0, maximumFraction = 255;
    data.findAndGetUint16(DCM_Rows, rows);
    data.findAndGetUint16(DCM_Columns, columns);
    data.findAndGetUint16(DCM_MaximumFractionalValue, maximumFraction);
    const std::size_t frames = seg->getNumberOfFrames();
    if (frames == 0 || rows == 0 || columns == 0) throw InputError(file, "NumberOfFrames", "at least one frame of at least one pixel");
    FGInterface& groups = seg->getFunctionalGroups();

    auto* orientation = group<FGPlaneOrientationPatient>(groups, 0, DcmFGTypes::EFG_PLANEORIENTPATIENT);
    auto* measures = group<FGPixelMeasures>(groups, 0, DcmFGTypes::EFG_PIXELMEASURES);
    if (!orientation || !measures) throw InputError(file, "SharedFunctionalGroupsSequence", "Plane Orientation and Pixel Measures");
    Float64 o[6] = {};
    Float64 rowSpacing = 0, columnSpacing = 0, between = 0;
    if (orientation->getImageOrientationPatient(o[0], o[1], o[2], o[3], o[4], o[5]).bad() || measures->getPixelSpacing(rowSpacing, 0).bad() ||
        measures->getPixelSpacing(columnSpacing, 1).bad() || rowSpacing <= 0 || columnSpacing <= 0)
        throw InputError(file, "ImageOrientationPatient/PixelSpacing", "six direction cosines and two positive spacings");
    measures->getSpacingBetweenSlices(between);
    const glm::dvec3 x(o[0], o[1], o[2]), y(o[3], o[4], o[5]);
    const glm::dvec3 normal = glm::normalize(glm::cross(x, y));

    struct FrameAt {
        glm::dvec3 position;
        int segment;
    };
    std::vector<FrameAt> placed(frames);
    for (std::size_t f = 0; f < frames; ++f) {
        auto* position = group<FGPlanePosPatient>(groups, Uint32(f), DcmFGTypes::EFG_PLANEPOSPATIENT);
        auto* segmentation = group<FGSegmentation>(groups, Uint32(f), DcmFGTypes::EFG_SEGMENTATION);
        Uint16 number = 0;
        if (!position || position->getImagePositionPatient(placed[f].position.x, placed[f].position.y, placed[f].position.z).bad())
            throw InputError(file, "frame " + std::to_string(f + 1) + " PlanePositionSequence", "an ImagePositionPatient");
        if (!segmentation || segmentation->getReferencedSegmentNumber(number).bad())
            throw InputError(file, "frame " + std::to_string(f + 1) + " SegmentIdentificationSequence", "a ReferencedSegmentNumber");
        placed[f].segment = number;
    }
    std::vector<double> depths;
    for (const FrameAt& f : placed) depths.push_back(glm::dot(f.position, normal));
    std::sort(depths.begin(), depths.end());
    depths.erase(std::unique(depths.begin(), depths.end(), [](double a, double b) { return std::abs(a - b) < 1e-3; }), depths.end());
    double step = between > 0 ? between : 0;
    for (std::size_t n = 1; n < depths.size() && between <= 0; ++n) step = step == 0 ? depths[n] - depths[n - 1] : std::min(step, depths[n] - depths[n - 1]);
    if (step <= 0) step = 1.0;   // a single slice
    const double span = (depths.back() - depths.front()) / step;
    // The frames' positions decide the grid's depth: a few frames far apart at a tiny spacing must not ask
    // for gigabytes.
    if (!(span < 65535.0) || double(rows) * double(columns) * (span + 1.0) > double(1u << 31))
        throw InputError(file, "PlanePositionSequence/SpacingBetweenSlices", "frames spanning at most 2^31 voxels on the slice lattice");
    const int slices = int(std::lround(span)) + 1;
    const FrameAt& lowest = *std::min_element(placed.begin(), placed.end(),
                                              [&](const FrameAt& a, const FrameAt& b) { return glm::dot(a.position, normal) < glm::dot(b.position, normal); });

    DicomSegmentationVolume out;
    out.frames = frames;
    LabelMap& labels = out.labels;
    labels.dims = {columns, rows, slices};
    labels.source = file;
    // LPS columns (x * column spacing, y * row spacing, normal * step) and origin, then to RAS.
    const glm::dvec3 lpsToRas(-1, -1, 1);
    labels.indexToWorld = glm::dmat4(glm::dvec4(lpsToRas * x * columnSpacing, 0), glm::dvec4(lpsToRas * y * rowSpacing, 0),
                                     glm::dvec4(lpsToRas * normal * step, 0), glm::dvec4(lpsToRas * lowest.position, 1));
    labels.ids.assign(labels.voxelCount(), 0);

    for (std::size_t n = 1; n <= seg->getNumberOfSegments(); ++n) {
        DcmSegment* segment = seg->getSegment(n);
        if (!segment) continue;
        DicomSegmentSummary s;
        s.number = int(n);
        OFString label;
        segment->getSegmentLabel(label);
        s.label = label.c_str();
        s.algorithmType = DcmSegTypes::algoType2OFString(segment->getSegmentAlgorithmType()).c_str();
        Uint16 L = 0, a = 0, b = 0;
        if (segment->getRecommendedDisplayCIELabValue(L, a, b).good() && (L || a || b)) IODCIELabUtil::dicomLab2RGB(s.color.r, s.color.g, s.color.b, L, a, b);
        out.segments.push_back(s);
    }
    const std::size_t pixels = std::size_t(rows) * columns;
    // Binary frames straight from PixelData, one bit a pixel, frames not padded (PS3.5 8.1.1): dcmseg 3.6.7
    // misplaces frames whose pixel count is not a multiple of 8 (io/dicom_seg_writer.cpp).
    const Uint8* bits = nullptr;
    unsigned long length = 0;
    if (binary && (data.findAndGetUint8Array(DCM_PixelData, bits, &length).bad() || !bits || length * 8 < frames * pixels))
        throw InputError(file, "PixelData", std::to_string(frames * pixels) + " bits of " + std::to_string(frames) + " binary frames");
    for (std::size_t f = 0; f < frames; ++f) {
        const DcmIODTypes::Frame* frame = binary ? nullptr : seg->getFrame(f);
        if (!binary && !frame) throw InputError(file, "frame " + std::to_string(f + 1), "pixel data");
        glm::dvec3 offset = placed[f].position - lowest.position;
        double k = glm::dot(offset, normal) / step;
        int slice = int(std::lround(k));
        if (std::abs(k - slice) * step > 0.01 || glm::length(offset - glm::dot(offset, normal) * normal) > 0.01)
            throw InputError(file, "frame " + std::to_string(f + 1) + " ImagePositionPatient", "a position on the slice lattice of the other frames");
        const unsigned maximum = std::max<unsigned>(1, maximumFraction);
        auto summary = std::find_if(out.segments.begin(), out.segments.end(), [&](const DicomSegmentSummary& s) { return s.number == placed[f].segment; });
        if (summary != out.segments.end()) ++summary->frames;
        for (std::size_t p = 0; p < pixels; ++p) {
            const std::size_t b = f * pixels + p;
            bool on = binary ? ((bits[b >> 3] >> (b & 7)) & 1) != 0 : 2 * unsigned(frame->pixData[p]) >= maximum;
            if (!on) continue;
            if (summary != out.segments.end()) ++summary->voxels;
            std::uint16_t& id = labels.ids[labels.linearIndex(int(p % columns), int(p / columns), slice)];
            if (id == 0 || placed[f].segment < id) id = std::uint16_t(placed[f].segment);
        }
    }
    OFString description;
    seg->getSeries().getSeriesDescription(description);
    out.seriesDescription = description.c_str();
    return out;
}

std::vector<DicomRoiSummary> readRtStructRois(const fs::path& path) {
    silenceDcmtk();
    const std::string file = path.string();
    DcmFileFormat format;
    if (format.loadFile(path.c_str()).bad()) throw InputError(file, "", "a DICOM file DCMTK reads");
    DcmDataset& data = *format.getDataset();
    OFString sopClass;
    data.findAndGetOFString(DCM_SOPClassUID, sopClass);
    if (sopClass != kRtStructureSetStorage) throw InputError(file, "SOPClassUID", "RT Structure Set Storage", sopClass.c_str());
    auto text = [](DcmItem* item, const DcmTagKey& tag) {
        OFString value;
        item->findAndGetOFStringArray(tag, value);
        return std::string(value.c_str());
    };
    std::vector<DicomRoiSummary> rois;
    std::map<int, std::size_t> byNumber;
    DcmSequenceOfItems* sequence = nullptr;
    if (data.findAndGetSequence(DCM_StructureSetROISequence, sequence).good() && sequence)
        for (unsigned long n = 0; n < sequence->card(); ++n) {
            DcmItem* item = sequence->getItem(n);
            Sint32 number = 0;
            item->findAndGetSint32(DCM_ROINumber, number);
            DicomRoiSummary roi;
            roi.number = number;
            roi.name = text(item, DCM_ROIName);
            roi.generationAlgorithm = text(item, DCM_ROIGenerationAlgorithm);
            byNumber[number] = rois.size();
            rois.push_back(roi);
        }
    if (data.findAndGetSequence(DCM_ROIContourSequence, sequence).good() && sequence)
        for (unsigned long n = 0; n < sequence->card(); ++n) {
            DcmItem* item = sequence->getItem(n);
            Sint32 number = 0;
            item->findAndGetSint32(DCM_ReferencedROINumber, number);
            auto found = byNumber.find(number);
            if (found == byNumber.end()) continue;
            DicomRoiSummary& roi = rois[found->second];
            for (int c = 0; c < 3; ++c) {
                Sint32 v = 0;
                item->findAndGetSint32(DCM_ROIDisplayColor, v, unsigned(c));
                roi.color[c] = v;
            }
            DcmSequenceOfItems* contours = nullptr;
            std::set<long long> planes;
            if (item->findAndGetSequence(DCM_ContourSequence, contours).good() && contours)
                for (unsigned long c = 0; c < contours->card(); ++c) {
                    DcmItem* contour = contours->getItem(c);
                    Sint32 points = 0;
                    contour->findAndGetSint32(DCM_NumberOfContourPoints, points);
                    ++roi.contours;
                    roi.points += std::size_t(std::max(points, 0));
                    Float64 z = 0;
                    if (contour->findAndGetFloat64(DCM_ContourData, z, 2).good()) planes.insert(std::llround(z * 1000.0));
                }
            roi.slices = planes.size();
        }
    if (data.findAndGetSequence(DCM_RTROIObservationsSequence, sequence).good() && sequence)
        for (unsigned long n = 0; n < sequence->card(); ++n) {
            DcmItem* item = sequence->getItem(n);
            Sint32 number = 0;
            item->findAndGetSint32(DCM_ReferencedROINumber, number);
            auto found = byNumber.find(number);
            if (found != byNumber.end()) rois[found->second].interpretedType = text(item, DCM_RTROIInterpretedType);
        }
    return rois;
}

}  // namespace curette::io
