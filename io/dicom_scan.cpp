// DICOM scanning (gdcm::Scanner): the files of a folder or of one file's series, what each says about itself,
// and their grouping into series, whose images io/dicom_geometry.h places.
#include "io/dicom.h"

#include "io/dicom_geometry.h"
#include "io/dicom_structure.h"
#include "io/dicom_values.h"
#include "base/error.h"
#include "base/log.h"

#include <gdcmDataSet.h>
#include <gdcmItem.h>
#include <gdcmReader.h>
#include <gdcmScanner.h>
#include <gdcmSequenceOfItems.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <optional>
#include <set>

namespace curette::io {

namespace {

namespace fs = std::filesystem;
using dicom_detail::fmt;
using dicom_detail::number;
using dicom_detail::numbers;
using dicom_detail::trim;

// Tags by their PS3.6 keyword.
const gdcm::Tag kImageType(0x0008, 0x0008), kSopInstanceUid(0x0008, 0x0018), kAccessionNumber(0x0008, 0x0050),
    kModality(0x0008, 0x0060), kSeriesDescription(0x0008, 0x103e), kPatientName(0x0010, 0x0010),
    kPatientId(0x0010, 0x0020), kPatientBirthDate(0x0010, 0x0030), kSliceThickness(0x0018, 0x0050),
    kSpacingBetweenSlices(0x0018, 0x0088), kGantryDetectorTilt(0x0018, 0x1120), kSeriesInstanceUid(0x0020, 0x000e),
    kSeriesNumber(0x0020, 0x0011), kImagePositionPatient(0x0020, 0x0032), kImageOrientationPatient(0x0020, 0x0037),
    kSamplesPerPixel(0x0028, 0x0002), kPhotometricInterpretation(0x0028, 0x0004), kNumberOfFrames(0x0028, 0x0008),
    kRows(0x0028, 0x0010), kColumns(0x0028, 0x0011), kPixelSpacing(0x0028, 0x0030), kBitsAllocated(0x0028, 0x0100),
    kBitsStored(0x0028, 0x0101), kHighBit(0x0028, 0x0102), kPixelRepresentation(0x0028, 0x0103), kRescaleIntercept(0x0028, 0x1052),
    kRescaleSlope(0x0028, 0x1053), kGridFrameOffsetVector(0x3004, 0x000c), kDoseGridScaling(0x3004, 0x000e),
    kSharedFunctionalGroups(0x5200, 0x9229), kPerFrameFunctionalGroups(0x5200, 0x9230),
    kPlanePositionSequence(0x0020, 0x9113), kPlaneOrientationSequence(0x0020, 0x9116),
    kPixelMeasuresSequence(0x0028, 0x9110), kPixelValueTransformationSequence(0x0028, 0x9145),
    kPixelData(0x7fe0, 0x0010);

// Where one image lies: everything PS3.3 C.7.6.2 needs, and the values' rescale.
struct FrameGeometry {
    std::optional<glm::dvec3> position;                // ImagePositionPatient, LPS mm
    std::optional<std::array<double, 6>> orientation;  // ImageOrientationPatient
    std::optional<glm::dvec2> pixelSpacing;            // PixelSpacing: row spacing, column spacing
    double slope = 1.0, intercept = 0.0;
};

void setPosition(FrameGeometry& g, const std::string& text) {
    if (auto v = numbers(text); v && v->size() == 3) g.position = glm::dvec3((*v)[0], (*v)[1], (*v)[2]);
}
void setOrientation(FrameGeometry& g, const std::string& text) {
    if (auto v = numbers(text); v && v->size() == 6) g.orientation = std::array<double, 6>{(*v)[0], (*v)[1], (*v)[2], (*v)[3], (*v)[4], (*v)[5]};
}
void setPixelSpacing(FrameGeometry& g, const std::string& text) {
    if (auto v = numbers(text); v && v->size() == 2 && (*v)[0] > 0 && (*v)[1] > 0) g.pixelSpacing = glm::dvec2((*v)[0], (*v)[1]);
}
void setRescale(FrameGeometry& g, const std::string& slope, const std::string& intercept) {
    if (auto s = number(slope)) g.slope = *s;
    if (auto i = number(intercept)) g.intercept = *i;
}

// What one file says about itself.
struct FileHeader {
    fs::path path;
    std::string seriesUid, seriesNumber, seriesDescription, modality, sopInstanceUid, imageType;
    std::string patientName, patientId, patientBirthDate, accessionNumber;
    int rows = 0, columns = 0, frameCount = 1;
    std::string pixelProblem;     // why curette does not read its pixels ("" when it does)
    double sliceThickness = 0, spacingBetweenSlices = 0;
    std::string gantryDetectorTilt;
    std::vector<FrameGeometry> frames;
    std::string geometryProblem;  // why its frames cannot be placed ("" when they can)
    std::string truncation;       // why its pixel data cannot be read: it does not fit in the file ("" when it does)
};

// The text of an element with a string VR (DS, IS, CS...), "" when absent.
std::string textOf(const gdcm::DataSet& dataSet, const gdcm::Tag& tag) {
    if (!dataSet.FindDataElement(tag)) return {};
    const gdcm::ByteValue* value = dataSet.GetDataElement(tag).GetByteValue();
    if (!value || !value->GetPointer()) return {};
    return trim(std::string_view(value->GetPointer(), value->GetLength()));
}

gdcm::SmartPointer<gdcm::SequenceOfItems> sequenceOf(const gdcm::DataSet& dataSet, const gdcm::Tag& tag) {
    if (!dataSet.FindDataElement(tag)) return nullptr;
    return dataSet.GetDataElement(tag).GetValueAsSQ();
}

// One element of a functional-group macro (PS3.3 C.7.6.16): the macro's sequence holds one item. Looked up in
// the frame's group first, then in the shared group: the standard puts a macro in one of them, but real files
// (Philips, [DCM-MF]) repeat shared macros per frame.
std::string macroText(const gdcm::DataSet* perFrame, const gdcm::DataSet* shared, const gdcm::Tag& macro, const gdcm::Tag& element) {
    for (const gdcm::DataSet* group : {perFrame, shared}) {
        if (!group) continue;
        gdcm::SmartPointer<gdcm::SequenceOfItems> items = sequenceOf(*group, macro);
        if (!items || items->GetNumberOfItems() == 0) continue;
        std::string text = textOf(items->GetItem(1).GetNestedDataSet(), element);
        if (!text.empty()) return text;
    }
    return {};
}

// Enhanced (multi-frame) objects keep each frame's position, and the orientation, spacing and rescale, in
// functional groups (PS3.3 C.7.6.16). Reads the header up to the pixel data; false when there are none.
bool readFunctionalGroups(FileHeader& header) {
    gdcm::Reader reader;
    reader.SetFileName(header.path.string().c_str());
    if (!reader.ReadUpToTag(kPixelData)) return false;
    const gdcm::DataSet& dataSet = reader.GetFile().GetDataSet();
    gdcm::SmartPointer<gdcm::SequenceOfItems> perFrame = sequenceOf(dataSet, kPerFrameFunctionalGroups);
    if (!perFrame || perFrame->GetNumberOfItems() == 0) return false;
    gdcm::SmartPointer<gdcm::SequenceOfItems> sharedItems = sequenceOf(dataSet, kSharedFunctionalGroups);
    const gdcm::DataSet* shared =
        sharedItems && sharedItems->GetNumberOfItems() > 0 ? &sharedItems->GetItem(1).GetNestedDataSet() : nullptr;
    if (perFrame->GetNumberOfItems() != static_cast<std::size_t>(header.frameCount)) {
        header.geometryProblem = "PerFrameFunctionalGroupsSequence (5200,9230) with " + std::to_string(perFrame->GetNumberOfItems()) +
                                 " items for NumberOfFrames " + std::to_string(header.frameCount) + " in " + header.path.filename().string();
        return true;
    }
    header.frames.assign(static_cast<std::size_t>(header.frameCount), FrameGeometry{});
    for (std::size_t f = 0; f < header.frames.size(); ++f) {
        const gdcm::DataSet& group = perFrame->GetItem(f + 1).GetNestedDataSet();
        FrameGeometry& g = header.frames[f];
        setPosition(g, macroText(&group, shared, kPlanePositionSequence, kImagePositionPatient));
        setOrientation(g, macroText(&group, shared, kPlaneOrientationSequence, kImageOrientationPatient));
        setPixelSpacing(g, macroText(&group, shared, kPixelMeasuresSequence, kPixelSpacing));
        setRescale(g, macroText(&group, shared, kPixelValueTransformationSequence, kRescaleSlope),
                   macroText(&group, shared, kPixelValueTransformationSequence, kRescaleIntercept));
        if (f == 0)
            if (auto t = number(macroText(&group, shared, kPixelMeasuresSequence, kSliceThickness))) header.sliceThickness = *t;
    }
    return true;
}

std::vector<gdcm::Tag> scannedTags(bool readIdentifiers) {
    std::vector<gdcm::Tag> tags = {kImageType, kSopInstanceUid, kModality, kSeriesDescription, kSliceThickness,
                                   kSpacingBetweenSlices, kGantryDetectorTilt, kSeriesInstanceUid, kSeriesNumber,
                                   kImagePositionPatient, kImageOrientationPatient, kSamplesPerPixel, kPhotometricInterpretation,
                                   kBitsAllocated, kBitsStored, kHighBit, kPixelRepresentation, kNumberOfFrames,
                                   kRows, kColumns, kPixelSpacing, kRescaleIntercept, kRescaleSlope,
                                   kGridFrameOffsetVector, kDoseGridScaling};
    if (readIdentifiers) tags.insert(tags.end(), {kPatientName, kPatientId, kPatientBirthDate, kAccessionNumber});
    return tags;
}

int positiveInt(const std::string& text, int fallback) {
    auto v = number(text);
    if (!v || *v < 1 || *v > 1e9 || *v != std::floor(*v)) return fallback;
    return static_cast<int>(*v);
}

// What of the Image Pixel Module (PS3.3 C.7.6.3) curette does not read, "" when it reads it all. Checked
// before GDCM sees the pixels: its PixmapReader assert()s on values it does not expect (a SamplesPerPixel
// of 0, found by fuzz_dicom).
template <typename Text>
std::string pixelModuleProblem(const Text& text) {
    auto value = [&](const gdcm::Tag& tag) { return number(text(tag)); };
    std::optional<double> samples = value(kSamplesPerPixel), allocated = value(kBitsAllocated), stored = value(kBitsStored),
                          highBit = value(kHighBit), representation = value(kPixelRepresentation);
    const std::string photometric = text(kPhotometricInterpretation);
    if (!samples || *samples != 1) return "SamplesPerPixel " + (samples ? fmt(*samples) : std::string("missing"));
    if (photometric != "MONOCHROME1" && photometric != "MONOCHROME2")
        return "PhotometricInterpretation " + (photometric.empty() ? std::string("missing") : photometric);
    if (!allocated || (*allocated != 8 && *allocated != 16 && *allocated != 32))
        return "BitsAllocated " + (allocated ? fmt(*allocated) : std::string("missing"));
    if (!stored || *stored < 1 || *stored > *allocated || *stored != std::floor(*stored))
        return "BitsStored " + (stored ? fmt(*stored) : std::string("missing"));
    if (!highBit || *highBit != *stored - 1) return "HighBit " + (highBit ? fmt(*highBit) : std::string("missing"));
    if (!representation || (*representation != 0 && *representation != 1))
        return "PixelRepresentation " + (representation ? fmt(*representation) : std::string("missing"));
    return {};
}

// RT dose frames lie at offsets along the normal from IPP; a first offset of 0 means relative offsets,
// otherwise they are z coordinates (only with IOP 1\0\0\0\1\0). Both are IPP + (o_f - o_0) N
// (PS3.3 C.8.8.3.2).
void placeDoseFrames(FileHeader& h, const FrameGeometry& g, const std::vector<double>& offsets) {
    if (offsets.size() != static_cast<std::size_t>(h.frameCount)) {
        h.geometryProblem = "GridFrameOffsetVector (3004,000C) with " + std::to_string(offsets.size()) +
                            " values for NumberOfFrames " + std::to_string(h.frameCount);
        return;
    }
    const auto& o = *g.orientation;
    glm::dvec3 normal = glm::cross(glm::dvec3(o[0], o[1], o[2]), glm::dvec3(o[3], o[4], o[5]));
    if (glm::length(normal) > 0) normal = glm::normalize(normal);
    for (double offset : offsets) {
        FrameGeometry frame = g;
        frame.position = *g.position + (offset - offsets.front()) * normal;
        h.frames.push_back(frame);
    }
}

// The header of one scanned file; nothing when the file is not an image of a series (a DICOMDIR, a
// structure set, a report: no Rows/Columns, PS3.3 C.7.6.3).
std::optional<FileHeader> headerOf(const gdcm::Scanner& scanner, const std::string& file, bool readIdentifiers) {
    if (!scanner.IsKey(file.c_str())) return std::nullopt;
    auto text = [&](const gdcm::Tag& tag) {
        const char* value = scanner.GetValue(file.c_str(), tag);
        return value ? trim(value) : std::string();
    };
    FileHeader h;
    h.path = file;
    h.seriesUid = text(kSeriesInstanceUid);
    h.rows = positiveInt(text(kRows), 0);
    h.columns = positiveInt(text(kColumns), 0);
    if (h.rows == 0 || h.columns == 0) return std::nullopt;
    h.seriesNumber = text(kSeriesNumber);
    h.seriesDescription = text(kSeriesDescription);
    h.modality = text(kModality);
    h.sopInstanceUid = text(kSopInstanceUid);
    h.imageType = text(kImageType);
    if (readIdentifiers) {
        h.patientName = text(kPatientName);
        h.patientId = text(kPatientId);
        h.patientBirthDate = text(kPatientBirthDate);
        h.accessionNumber = text(kAccessionNumber);
    }
    h.frameCount = positiveInt(text(kNumberOfFrames), 1);
    h.pixelProblem = pixelModuleProblem(text);
    h.sliceThickness = number(text(kSliceThickness)).value_or(0.0);
    h.spacingBetweenSlices = number(text(kSpacingBetweenSlices)).value_or(0.0);
    h.gantryDetectorTilt = text(kGantryDetectorTilt);

    FrameGeometry g;
    setPosition(g, text(kImagePositionPatient));
    setOrientation(g, text(kImageOrientationPatient));
    setPixelSpacing(g, text(kPixelSpacing));
    setRescale(g, text(kRescaleSlope), text(kRescaleIntercept));
    // RT dose: "multiplied by the dose grid data ... yields grid doses in the dose units" (PS3.3 C.8.8.3).
    if (text(kRescaleSlope).empty())
        if (auto scaling = number(text(kDoseGridScaling))) g.slope = *scaling;

    if (h.frameCount == 1 && g.position && g.orientation) {
        h.frames = {g};
        return h;
    }
    // Enhanced objects always have NumberOfFrames (Multi-frame Module, PS3.3 C.7.6.6); a file without it
    // has no functional groups to read.
    if (!text(kNumberOfFrames).empty()) {
        try {
            if (readFunctionalGroups(h)) return h;
        } catch (const std::exception&) {
            // A header GDCM cannot walk: treated as one without functional groups.
        }
    }
    std::optional<std::vector<double>> offsets = numbers(text(kGridFrameOffsetVector));
    if (h.frameCount > 1 && offsets && g.position && g.orientation) {
        placeDoseFrames(h, g, *offsets);
        return h;
    }
    if (h.frameCount > 1) {
        h.geometryProblem = "NumberOfFrames " + std::to_string(h.frameCount) + " in " + h.path.filename().string() +
                            " without per-frame positions (no PerFrameFunctionalGroupsSequence (5200,9230) or "
                            "GridFrameOffsetVector (3004,000C)): a cine or projection series";
        return h;
    }
    h.frames = {g};
    return h;
}

bool endsWithDcm(const fs::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext == ".dcm";
}

std::vector<std::string> filesUnder(const fs::path& directory, bool recursive, const std::string& source) {
    std::vector<std::string> files;
    std::error_code ec;
    auto add = [&](const fs::directory_entry& entry) {
        std::error_code e;
        if (entry.is_regular_file(e)) files.push_back(entry.path().string());
    };
    if (recursive) {
        for (auto it = fs::recursive_directory_iterator(directory, fs::directory_options::skip_permission_denied, ec);
             !ec && it != fs::recursive_directory_iterator(); it.increment(ec))
            add(*it);
    } else {
        for (auto it = fs::directory_iterator(directory, fs::directory_options::skip_permission_denied, ec);
             !ec && it != fs::directory_iterator(); it.increment(ec))
            add(*it);
    }
    if (ec) throw InputError(source, "", "a readable folder", ec.message());
    std::sort(files.begin(), files.end());
    return files;
}


// The files to scan: every file under a folder, or the named file first and then the others of its folder,
// so that it stands for its SOP instance when a copy lies beside it.
std::vector<std::string> filesToScan(const fs::path& path, bool folder, const std::string& source) {
    if (folder) return filesUnder(path, true, source);
    std::vector<std::string> files;
    fs::path parent = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    files.push_back(path.string());
    for (std::string& f : filesUnder(parent, false, source)) {
        std::error_code e;
        if (!fs::equivalent(f, path, e)) files.push_back(std::move(f));
    }
    return files;
}

// The files that are well formed enough to hand to GDCM (io/dicom_structure.h), and what became of the rest.
struct ScreenedFiles {
    std::vector<std::string> candidates;
    std::vector<std::string> unreadable;           // look like DICOM, but cannot be read
    std::map<std::string, std::string> truncated;  // file -> what of its pixel data is missing
};

ScreenedFiles screenFiles(std::vector<std::string> files, bool folder) {
    ScreenedFiles screened;
    for (std::string& file : files) {
        DicomStructure structure = checkDicomStructure(file, dicom_detail::kAlwaysAcceptedBytes);
        const std::string& problem = structure.problem;
        if (problem.empty()) {
            screened.candidates.push_back(std::move(file));
        } else if (structure.onlyTruncatedPixelData) {
            screened.truncated[file] = problem;
            screened.candidates.push_back(std::move(file));
        } else if (!folder && screened.candidates.empty() && screened.unreadable.empty()) {
            throw InputError(file, "", "a well-formed DICOM image file (PS3.5 7.1, 7.5)", problem);
        } else if (looksLikeDicom(file)) {
            screened.unreadable.push_back(fs::path(file).filename().string());
        }
    }
    return screened;
}

// What placement needs of one frame of a file (io/dicom_geometry.h).
DicomSliceRecord sliceRecord(const FileHeader& h, const FrameGeometry& g, unsigned frame) {
    DicomSliceRecord r;
    r.name = h.path.filename().string();
    if (h.frameCount > 1) r.name += " frame " + std::to_string(frame + 1);
    r.columns = h.columns, r.rows = h.rows;
    r.position = g.position, r.orientation = g.orientation, r.pixelSpacing = g.pixelSpacing;
    r.sliceThickness = h.sliceThickness, r.spacingBetweenSlices = h.spacingBetweenSlices;
    r.gantryDetectorTilt = h.gantryDetectorTilt;
    r.truncation = h.truncation, r.geometryProblem = h.geometryProblem, r.pixelProblem = h.pixelProblem;
    return r;
}

// The series found so far, in the order of their first file, and each one's images.
struct SeriesGathering {
    std::map<std::string, std::size_t> byUid;
    std::vector<DicomSeries> series;
    std::vector<std::vector<DicomSliceRecord>> recordsOf;  // parallel to series[i].slices before placement
    std::vector<std::set<std::string>> instancesOf;

    std::size_t seriesOf(const FileHeader& header) {
        // A file without a SeriesInstanceUID (Type 1, but stripped by some anonymisers) is a series of its own;
        // its path cannot be mistaken for a UID (digits and dots, PS3.5 9.1).
        auto [it, added] = byUid.emplace(header.seriesUid.empty() ? header.path.string() : header.seriesUid, series.size());
        if (added) {
            DicomSeries s;
            s.uid = header.seriesUid;
            s.number = header.seriesNumber;
            s.description = header.seriesDescription;
            s.modality = header.modality;
            std::string type = header.imageType;
            std::transform(type.begin(), type.end(), type.begin(), [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
            s.localizer = type.find("LOCALIZER") != std::string::npos;
            s.patientName = header.patientName;
            s.patientId = header.patientId;
            s.patientBirthDate = header.patientBirthDate;
            s.accessionNumber = header.accessionNumber;
            series.push_back(std::move(s));
            recordsOf.emplace_back();
            instancesOf.emplace_back();
        }
        return it->second;
    }

    void add(const FileHeader& h) {
        const std::size_t index = seriesOf(h);
        // The same SOP instance twice (copies, or one image in several transfer syntaxes) is one image.
        if (!h.sopInstanceUid.empty() && !instancesOf[index].insert(h.sopInstanceUid).second) return;
        series[index].files.push_back(h.path);
        // A file whose frames cannot be placed still stands for one image, so that placement says why.
        const std::vector<FrameGeometry> frames = h.frames.empty() ? std::vector<FrameGeometry>{FrameGeometry{}} : h.frames;
        for (std::size_t f = 0; f < frames.size(); ++f) {
            DicomSlice slice;
            slice.file = h.path;
            slice.frame = static_cast<unsigned>(f);
            slice.position = frames[f].position.value_or(glm::dvec3(0.0));
            slice.rescaleSlope = frames[f].slope;
            slice.rescaleIntercept = frames[f].intercept;
            series[index].slices.push_back(slice);
            recordsOf[index].push_back(sliceRecord(h, frames[f], slice.frame));
        }
    }
};

// Not an error: folders hold other files. But a slice that is skipped at either end of a series leaves no
// gap to notice, so say which ones were.
void warnUnreadable(const std::string& source, const std::vector<std::string>& unreadable) {
    std::string names;
    for (std::size_t i = 0; i < unreadable.size() && i < 3; ++i) names += (i ? ", " : "") + unreadable[i];
    log::warn(source + ": " + std::to_string(unreadable.size()) + " file(s) that look like DICOM could not be read (" + names +
              (unreadable.size() > 3 ? ", ..." : "") + ")");
}

// Fills slices (along the normal), dims and indexToWorld, or the problem when they are not one regular volume.
void place(DicomSeries& series, const std::vector<DicomSliceRecord>& records) {
    DicomSlicePlacement placement = placeDicomSlices(records);
    std::vector<DicomSlice> slices;
    for (std::size_t k : placement.order) slices.push_back(series.slices[k]);
    series.slices = std::move(slices);
    series.dims = placement.dims;
    series.indexToWorld = placement.indexToWorld;
    series.problemExpected = std::move(placement.problemExpected);
    series.problem = std::move(placement.problem);
}

}  // namespace

bool looksLikeDicom(const fs::path& path) {
    std::error_code ec;
    if (fs::is_directory(path, ec)) return true;
    if (endsWithDcm(path)) return true;
    std::ifstream in(path, std::ios::binary);
    char head[132] = {};
    in.read(head, sizeof head);
    return in.gcount() == 132 && std::memcmp(head + 128, "DICM", 4) == 0;
}

std::vector<DicomSeries> scanDicom(const fs::path& path, bool readIdentifiers) {
    dicom_detail::forgetGdcmMessages();
    const std::string source = path.string();
    std::error_code ec;
    const bool folder = fs::is_directory(path, ec);
    if (!folder && !fs::is_regular_file(path, ec)) throw InputError(source, "", "a DICOM file or a folder of DICOM files", "no such file");
    std::vector<std::string> files = filesToScan(path, folder, source);
    const std::size_t fileCount = files.size();
    // Files that are not well formed are not handed to GDCM at all (io/dicom_structure.h).
    ScreenedFiles screened = screenFiles(std::move(files), folder);
    files = std::move(screened.candidates);
    std::vector<std::string>& unreadable = screened.unreadable;

    gdcm::Scanner scanner;
    for (const gdcm::Tag& tag : scannedTags(readIdentifiers)) scanner.AddTag(tag);
    try {
        scanner.Scan(files);
    } catch (const std::exception& e) {
        throw InputError(source, "", "DICOM files GDCM can read", e.what());
    }
    dicom_detail::forgetGdcmMessages();  // what GDCM said about the files that are not DICOM

    SeriesGathering gathering;
    std::string namedSeries;  // one file named: only its series
    for (const std::string& file : files) {
        if (!folder && file != files.front()) {
            // One file named: only its series is read; the others are not even looked at further.
            const char* uid = scanner.GetValue(file.c_str(), kSeriesInstanceUid);
            if (!uid || trim(uid) != namedSeries) continue;
        }
        std::optional<FileHeader> header;
        try {
            header = headerOf(scanner, file, readIdentifiers);
        } catch (const std::exception&) {
            header.reset();  // a file GDCM cannot walk is not part of any series
        }
        if (!header) {
            if (!folder && file == files.front())
                throw InputError(source, "", "a DICOM image file (PS3.10, with Rows and Columns)",
                                 scanner.IsKey(file.c_str()) ? "a DICOM file without an image" : "a file GDCM cannot read as DICOM");
            if (!scanner.IsKey(file.c_str()) && looksLikeDicom(file)) unreadable.push_back(fs::path(file).filename().string());
            continue;
        }
        if (!folder && file == files.front()) namedSeries = header->seriesUid;
        if (auto t = screened.truncated.find(file); t != screened.truncated.end()) header->truncation = t->second;
        gathering.add(*header);
    }
    if (folder && !unreadable.empty()) warnUnreadable(source, unreadable);
    if (gathering.series.empty())
        throw InputError(source, "", "a folder holding DICOM image files",
                         "none of its " + std::to_string(fileCount) + " files is a DICOM image GDCM can read");
    for (std::size_t i = 0; i < gathering.series.size(); ++i) place(gathering.series[i], gathering.recordsOf[i]);
    return std::move(gathering.series);
}

}  // namespace curette::io
