// DICOM import: scanning a folder into series (gdcm::Scanner), placing their images in space (PS3.3
// C.7.6.2.1.1, C.7.6.16, C.8.8.3.2), and decoding the pixels (gdcm::ImageReader, gdcm::Image::GetBuffer).
#include "io/dicom.h"

#include "io/dicom_structure.h"
#include "base/error.h"
#include "base/log.h"
#include "base/text.h"

#include <gdcmDataSet.h>
#include <gdcmImage.h>
#include <gdcmImageReader.h>
#include <gdcmItem.h>
#include <gdcmReader.h>
#include <gdcmScanner.h>
#include <gdcmSequenceOfFragments.h>
#include <gdcmSequenceOfItems.h>
#include <gdcmTrace.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <tuple>

namespace curette::io {

namespace {

namespace fs = std::filesystem;

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

// Slicer's threshold for "the slice steps differ" [SL-DCM], used for every position comparison.
constexpr double kPositionToleranceMm = 0.01;
// Direction cosines are written with 4-6 decimals; two orientations within this are the same.
constexpr double kOrientationTolerance = 1e-4;
// Compressed pixel data may decode to at most this many times its size (or to 64 MiB, whatever is larger), so
// a corrupt header cannot make curette allocate gigabytes for a few bytes of file.
constexpr double kMaxCompressionRatio = 1000.0;
constexpr std::uint64_t kAlwaysAcceptedBytes = 64ull << 20;

// GDCM writes its warnings and errors to std::cerr; curette reports problems itself, as one line. They go to
// this sink instead, which decodeFile reads for the one warning that changes the result: GDCM pads truncated
// pixel data and goes on, saying only "Incomplete Pixel Data found" (gdcmExplicitDataElement.txx).
std::ostringstream& gdcmMessages() {
    static std::ostringstream sink;
    static const bool redirected = [] {
        gdcm::Trace::SetStream(sink);
        gdcm::Trace::DebugOff();
        gdcm::Trace::WarningOn();
        gdcm::Trace::ErrorOn();
        return true;
    }();
    (void)redirected;
    return sink;
}

void forgetGdcmMessages() { gdcmMessages().str({}); }

// Values are padded to even length with a space (or a NUL for UIs), PS3.5 6.2; some writers leave tabs and line ends.
constexpr std::string_view kPadding{" \0\t\r\n", 5};

std::string fmt(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", value);
    return text;
}

// The numbers of a multi-valued DS or IS ("a\b\c", PS3.5 6.2), or nothing when any value is not a number.
std::optional<std::vector<double>> numbers(const std::string& text) {
    if (text.empty()) return std::nullopt;
    std::vector<double> values;
    std::size_t start = 0;
    while (true) {
        std::size_t end = text.find('\\', start);
        std::string item(trim(std::string_view(text).substr(start, end == std::string::npos ? std::string::npos : end - start), kPadding));
        const char* first = item.data();
        const char* last = item.data() + item.size();
        if (first != last && *first == '+') ++first;
        double value = 0;
        auto [ptr, ec] = std::from_chars(first, last, value);
        if (ec != std::errc() || ptr != last || !std::isfinite(value)) return std::nullopt;
        values.push_back(value);
        if (end == std::string::npos) break;
        start = end + 1;
    }
    return values;
}

std::optional<double> number(const std::string& text) {
    auto values = numbers(text);
    if (!values || values->size() != 1) return std::nullopt;
    return values->front();
}

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
    return std::string(trim(std::string_view(value->GetPointer(), value->GetLength()), kPadding));
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

// The header of one scanned file; nothing when the file is not an image of a series (a DICOMDIR, a
// structure set, a report: no Rows/Columns, PS3.3 C.7.6.3).
std::optional<FileHeader> headerOf(const gdcm::Scanner& scanner, const std::string& file, bool readIdentifiers) {
    if (!scanner.IsKey(file.c_str())) return std::nullopt;
    auto text = [&](const gdcm::Tag& tag) {
        const char* value = scanner.GetValue(file.c_str(), tag);
        return value ? std::string(trim(value, kPadding)) : std::string();
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
        // RT dose frames lie at offsets along the normal from IPP; a first offset of 0 means relative offsets,
        // otherwise they are z coordinates (only with IOP 1\0\0\0\1\0). Both are IPP + (o_f - o_0) N
        // (PS3.3 C.8.8.3.2).
        if (offsets->size() != static_cast<std::size_t>(h.frameCount)) {
            h.geometryProblem = "GridFrameOffsetVector (3004,000C) with " + std::to_string(offsets->size()) +
                                " values for NumberOfFrames " + std::to_string(h.frameCount);
            return h;
        }
        const auto& o = *g.orientation;
        glm::dvec3 normal = glm::cross(glm::dvec3(o[0], o[1], o[2]), glm::dvec3(o[3], o[4], o[5]));
        if (glm::length(normal) > 0) normal = glm::normalize(normal);
        for (double offset : *offsets) {
            FrameGeometry frame = g;
            frame.position = *g.position + (offset - offsets->front()) * normal;
            h.frames.push_back(frame);
        }
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

// Every JPEG-LS frame header (SOF55: FF F7, length, P, Y, X, Nf; T.87 C.2.2) in the fragments must give this
// image's rows, columns and samples, at most `bitsAllocated` bits, and there must be one per frame.
void checkJpegLsFrames(const gdcm::DataElement& pixelData, unsigned columns, unsigned rows, unsigned frames, unsigned samples,
                       unsigned bitsAllocated, const std::string& name) {
    const gdcm::SequenceOfFragments* fragments = pixelData.GetSequenceOfFragments();
    unsigned headers = 0;
    for (unsigned f = 0; fragments && f < fragments->GetNumberOfFragments(); ++f) {
        const gdcm::ByteValue* value = fragments->GetFragment(f).GetByteValue();
        if (!value) continue;
        const auto* p = reinterpret_cast<const std::uint8_t*>(value->GetPointer());
        const std::size_t n = static_cast<std::uint32_t>(value->GetLength());
        for (std::size_t i = 0; i + 10 <= n; ++i) {
            if (p[i] != 0xFF || p[i + 1] != 0xF7) continue;  // in JPEG-LS scan data FF is never followed by a byte >= 0x80
            unsigned precision = p[i + 4], y = (p[i + 5] << 8) | p[i + 6], x = (p[i + 7] << 8) | p[i + 8], components = p[i + 9];
            if (x != columns || y != rows || components != samples || precision < 2 || precision > bitsAllocated)
                throw InputError(name, "PixelData", "JPEG-LS frames of " + std::to_string(columns) + " x " + std::to_string(rows) + " x " +
                                                        std::to_string(samples) + " samples of at most " + std::to_string(bitsAllocated) + " bits",
                                 "a frame header of " + std::to_string(x) + " x " + std::to_string(y) + " x " + std::to_string(components) +
                                     " samples of " + std::to_string(precision) + " bits");
            ++headers;
        }
    }
    if (headers != frames)
        throw InputError(name, "PixelData", std::to_string(frames) + " JPEG-LS frame headers (one per frame)", std::to_string(headers));
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

// ---- placing the images of a series in space --------------------------------------------------------------

struct Frame {
    DicomSlice slice;
    FrameGeometry geometry;
    const FileHeader* header = nullptr;
};

std::string where(const Frame& frame) {
    std::string name = frame.slice.file.filename().string();
    if (frame.header->frameCount > 1) name += " frame " + std::to_string(frame.slice.frame + 1);
    return name;
}

std::string orientationText(const std::array<double, 6>& o) {
    std::string text;
    for (std::size_t i = 0; i < 6; ++i) {
        if (i) text += '\\';
        text += fmt(o[i]);  // appended piece by piece: g++ 12 warns falsely on `"literal" + string` (GCC bug 105329)
    }
    return text;
}

// Fills series.slices, dims and indexToWorld, or series.problem when the frames are not one regular volume.
void placeSlices(DicomSeries& series, std::vector<Frame> frames) {
    auto refuse = [&](std::string expected, std::string got) {
        series.problemExpected = std::move(expected);
        series.problem = std::move(got);
    };
    const FileHeader& first = *frames.front().header;
    const std::size_t n = frames.size();
    series.dims = {first.columns, first.rows, static_cast<int>(n)};
    for (const Frame& f : frames) series.slices.push_back(f.slice);
    for (const Frame& f : frames) {
        if (!f.header->truncation.empty())
            return refuse("image files that hold all their pixel data", where(f) + " is truncated: " + f.header->truncation);
        if (!f.header->geometryProblem.empty())
            return refuse("the position of every frame of a multi-frame image", f.header->geometryProblem);
        if (f.header->columns != first.columns || f.header->rows != first.rows)
            return refuse("images of one size (Columns x Rows)",
                          "images of " + std::to_string(first.columns) + " x " + std::to_string(first.rows) + " (" + where(frames.front()) + ") and " +
                              std::to_string(f.header->columns) + " x " + std::to_string(f.header->rows) + " (" + where(f) + ")");
        if (!f.header->pixelProblem.empty())
            return refuse("grey-scale pixels (Image Pixel Module, PS3.3 C.7.6.3: SamplesPerPixel 1, MONOCHROME1 or 2, "
                          "BitsAllocated 8, 16 or 32, BitsStored up to it, HighBit BitsStored - 1, PixelRepresentation 0 or 1)",
                          f.header->pixelProblem + " in " + where(f));
        if (!f.geometry.position || !f.geometry.orientation)
            return refuse("ImagePositionPatient (0020,0032) and ImageOrientationPatient (0020,0037) in every image (slices of a volume)",
                          "no ImagePositionPatient or ImageOrientationPatient in " + where(f) + " (a projection or secondary-capture image?)");
        if (!f.geometry.pixelSpacing)
            return refuse("PixelSpacing (0028,0030) in every image (two positive numbers)", "no PixelSpacing in " + where(f));
    }

    // One orientation (PS3.3 C.7.6.2.1.1): X = row direction, Y = column direction, unit and orthogonal.
    const std::array<double, 6>& o = *frames.front().geometry.orientation;
    glm::dvec3 x(o[0], o[1], o[2]), y(o[3], o[4], o[5]);
    if (std::abs(glm::length(x) - 1) > 1e-3 || std::abs(glm::length(y) - 1) > 1e-3 || std::abs(glm::dot(x, y)) > 1e-3)
        return refuse("ImageOrientationPatient (0020,0037): two orthogonal unit vectors",
                      "ImageOrientationPatient " + orientationText(o) + " in " + where(frames.front()));
    std::vector<const Frame*> orientations{&frames.front()};
    for (const Frame& f : frames) {
        bool known = std::any_of(orientations.begin(), orientations.end(), [&](const Frame* seen) {
            for (std::size_t i = 0; i < 6; ++i)
                if (std::abs((*seen->geometry.orientation)[i] - (*f.geometry.orientation)[i]) > kOrientationTolerance) return false;
            return true;
        });
        if (!known) orientations.push_back(&f);
    }
    if (orientations.size() > 1)
        return refuse("one ImageOrientationPatient (0020,0037) for every slice",
                      std::to_string(orientations.size()) + " different orientations among " + std::to_string(n) + " images (" +
                          orientationText(*orientations[0]->geometry.orientation) + " in " + where(*orientations[0]) + ", " +
                          orientationText(*orientations[1]->geometry.orientation) + " in " + where(*orientations[1]) +
                          "): a localizer or several stacks in one series");
    const glm::dvec2 pixelSpacing = *frames.front().geometry.pixelSpacing;
    for (const Frame& f : frames)
        if (glm::length(*f.geometry.pixelSpacing - pixelSpacing) > 1e-4)
            return refuse("one PixelSpacing (0028,0030) for every slice",
                          "PixelSpacing " + fmt(pixelSpacing[0]) + "\\" + fmt(pixelSpacing[1]) + " in " + where(frames.front()) + " and " +
                              fmt((*f.geometry.pixelSpacing)[0]) + "\\" + fmt((*f.geometry.pixelSpacing)[1]) + " in " + where(f));
    x = glm::normalize(x), y = glm::normalize(y);
    const glm::dvec3 normal = glm::normalize(glm::cross(x, y));

    // Sorted by the distance along the normal, IPP . (X x Y) (PS3.3 C.7.6.2.1.1), never by file name or
    // InstanceNumber: that only identifies the image (C.7.6.1), and SliceLocation is optional (C.7.6.2).
    auto distance = [&](const Frame& f) { return glm::dot(*f.geometry.position, normal); };
    std::stable_sort(frames.begin(), frames.end(), [&](const Frame& a, const Frame& b) { return distance(a) < distance(b); });
    series.slices.clear();
    for (const Frame& f : frames) series.slices.push_back(f.slice);
    std::vector<double> d(n);
    for (std::size_t k = 0; k < n; ++k) d[k] = distance(frames[k]);

    std::size_t positions = 1;
    for (std::size_t k = 1; k < n; ++k) positions += d[k] - d[k - 1] > kPositionToleranceMm ? 1 : 0;
    if (positions < n)
        return refuse("one image per slice position",
                      std::to_string(n) + " images at " + std::to_string(positions) +
                          " positions (several echoes, phases or acquisitions in one series?)");

    // Stacked along the normal: the positions move only along X x Y. A step with a sideways part is gantry
    // tilt (GDCM's IPPSorter calls it "always an error"); curette would need to resample it.
    const glm::dvec3 p0 = *frames.front().geometry.position;
    auto sideways = [&](std::size_t k) {
        glm::dvec3 step = *frames[k].geometry.position - p0;
        return step - glm::dot(step, normal) * normal;
    };
    double largestSideways = 0;
    for (std::size_t k = 1; k < n; ++k) largestSideways = std::max(largestSideways, glm::length(sideways(k)));
    if (largestSideways > kPositionToleranceMm) {
        const glm::dvec3 lastSideways = sideways(n - 1);
        double irregular = 0;
        for (std::size_t k = 1; k < n; ++k)
            irregular = std::max(irregular, glm::length(sideways(k) - (d[k] - d[0]) / (d[n - 1] - d[0]) * lastSideways));
        if (irregular > kPositionToleranceMm)
            return refuse("slice positions on one line along the slice normal",
                          "positions offset sideways irregularly, by up to " + fmt(largestSideways) + " mm");
        const double degrees = std::atan2(glm::length(lastSideways), d[n - 1] - d[0]) * 180.0 / 3.14159265358979323846;
        return refuse("slices stacked along their normal (ImageOrientationPatient row x column)",
                      "a gantry tilt of " + fmt(degrees) + " degrees: each step moves " +
                          fmt(glm::length(lastSideways) / static_cast<double>(n - 1)) + " mm sideways" +
                          (first.gantryDetectorTilt.empty() ? "" : " (GantryDetectorTilt (0018,1120) " + first.gantryDetectorTilt + ")") +
                          "; a tilted stack needs resampling onto a regular grid, which curette does not do");
    }

    // Uniform steps (Slicer warns when they differ by more than 0.01 mm [SL-DCM]). Steps that are whole
    // multiples of the smallest one are missing slices.
    double smallest = 1e300, largest = 0;
    for (std::size_t k = 1; k < n; ++k) smallest = std::min(smallest, d[k] - d[k - 1]), largest = std::max(largest, d[k] - d[k - 1]);
    if (n > 1 && largest - smallest > kPositionToleranceMm) {
        long missing = 0;
        std::vector<std::size_t> gaps;
        bool multiples = true;
        for (std::size_t k = 1; k < n; ++k) {
            double step = d[k] - d[k - 1];
            double m = std::round(step / smallest);
            if (std::abs(step - m * smallest) > kPositionToleranceMm * m) multiples = false;
            if (m >= 2) missing += static_cast<long>(m) - 1, gaps.push_back(k);
        }
        if (multiples) {
            std::size_t k = gaps.front();
            std::string got = std::to_string(missing) + (missing == 1 ? " slice" : " slices") + " missing: the slices are " +
                              fmt(smallest) + " mm apart, but " + fmt(d[k] - d[k - 1]) + " mm lie between slice " +
                              std::to_string(k) + " and " + std::to_string(k + 1) + " of " + std::to_string(n) + " (at " +
                              fmt(d[k - 1]) + " and " + fmt(d[k]) + " mm along the normal, " + where(frames[k - 1]) + " and " +
                              where(frames[k]) + ")";
            if (gaps.size() > 1) got += " and at " + std::to_string(gaps.size() - 1) + " more places";
            return refuse("every slice of a regularly spaced series",
                          got + "; a regular volume needs the missing images, or resampling, which curette does not do");
        }
        return refuse("uniformly spaced slices (steps within " + fmt(kPositionToleranceMm) + " mm)",
                      "slice steps from " + fmt(smallest) + " to " + fmt(largest) +
                          " mm; a regular volume needs resampling onto a uniform grid, which curette does not do");
    }

    // One slice has no step: its thickness stands in (SpacingBetweenSlices, else SliceThickness, else 1 mm).
    double step = n > 1 ? (d[n - 1] - d[0]) / static_cast<double>(n - 1)
                        : first.spacingBetweenSlices > 0 ? first.spacingBetweenSlices
                        : first.sliceThickness > 0       ? first.sliceThickness
                                                         : 1.0;
    // P(i,j) = IPP + i PS[1] X + j PS[0] Y: PixelSpacing's first value is the row spacing, the step along Y.
    glm::dmat4 lps(1.0);
    lps[0] = glm::dvec4(x * pixelSpacing[1], 0.0);
    lps[1] = glm::dvec4(y * pixelSpacing[0], 0.0);
    lps[2] = glm::dvec4(normal * step, 0.0);
    lps[3] = glm::dvec4(p0, 1.0);
    // DICOM's patient coordinates are LPS; curette's world is RAS: negate x and y.
    const glm::dmat4 lpsToRas = glm::dmat4(glm::dvec4(-1, 0, 0, 0), glm::dvec4(0, -1, 0, 0), glm::dvec4(0, 0, 1, 0), glm::dvec4(0, 0, 0, 1));
    series.indexToWorld = lpsToRas * lps;
}

// ---- decoding -----------------------------------------------------------------------------------------------

struct DecodedImage {
    ScalarType type = ScalarType::UInt8;
    std::vector<std::uint8_t> samples;  // frames x rows x columns, native endian, of scalarTypeSize(type)
};

// Keeps the BitsStored low bits of each integer sample and extends their sign: the bits above are not part
// of the value (PS3.5 8.1.1; old files keep overlays there).
template <typename T>
void keepStoredBits(std::vector<std::uint8_t>& samples, unsigned bitsStored, bool isSigned) {
    using Unsigned = std::make_unsigned_t<T>;
    if (bitsStored == 0 || bitsStored >= 8 * sizeof(T)) return;
    const Unsigned mask = static_cast<Unsigned>((Unsigned{1} << bitsStored) - 1);
    const Unsigned sign = static_cast<Unsigned>(Unsigned{1} << (bitsStored - 1));
    for (std::size_t i = 0; i + sizeof(T) <= samples.size(); i += sizeof(T)) {
        Unsigned v;
        std::memcpy(&v, samples.data() + i, sizeof v);
        v = static_cast<Unsigned>(v & mask);
        if (isSigned && (v & sign)) v = static_cast<Unsigned>(v | static_cast<Unsigned>(~mask));
        std::memcpy(samples.data() + i, &v, sizeof v);
    }
}

// Converts samples of type From to To (the types buildVolume takes).
template <typename From, typename To>
std::vector<std::uint8_t> widen(const std::vector<std::uint8_t>& samples) {
    std::size_t count = samples.size() / sizeof(From);
    std::vector<std::uint8_t> out(count * sizeof(To));
    for (std::size_t i = 0; i < count; ++i) {
        From v;
        std::memcpy(&v, samples.data() + i * sizeof(From), sizeof v);
        To w = static_cast<To>(v);
        std::memcpy(out.data() + i * sizeof(To), &w, sizeof w);
    }
    return out;
}

DecodedImage decodeFile(const fs::path& file, int columns, int rows, unsigned framesNeeded) {
    const std::string name = file.string();
    gdcm::ImageReader reader;
    reader.SetFileName(name.c_str());
    forgetGdcmMessages();
    if (!reader.Read()) throw InputError(name, "PixelData", "an image GDCM can read", "none GDCM can read (no PixelData, or an encoding it does not know)");
    if (gdcmMessages().str().find("Incomplete Pixel Data") != std::string::npos)
        throw InputError(name, "PixelData", "the whole pixel data", "a file that ends inside it (truncated)");
    const gdcm::Image& image = reader.GetImage();
    const unsigned frames = image.GetNumberOfDimensions() >= 3 ? image.GetDimension(2) : 1;
    if (image.GetDimension(0) != static_cast<unsigned>(columns) || image.GetDimension(1) != static_cast<unsigned>(rows) || frames < framesNeeded)
        throw InputError(name, "Columns/Rows/NumberOfFrames",
                         std::to_string(columns) + " x " + std::to_string(rows) + " x " + std::to_string(framesNeeded) + " (as scanned)",
                         std::to_string(image.GetDimension(0)) + " x " + std::to_string(image.GetDimension(1)) + " x " + std::to_string(frames));
    const gdcm::PixelFormat& format = image.GetPixelFormat();
    if (format.GetSamplesPerPixel() != 1)
        throw InputError(name, "SamplesPerPixel", "1 (grey-scale images)", std::to_string(format.GetSamplesPerPixel()));
    const gdcm::PhotometricInterpretation photometric = image.GetPhotometricInterpretation();
    if (photometric != gdcm::PhotometricInterpretation::MONOCHROME1 && photometric != gdcm::PhotometricInterpretation::MONOCHROME2)
        throw InputError(name, "PhotometricInterpretation", "MONOCHROME1 or MONOCHROME2 (grey values)",
                         photometric.GetString() ? photometric.GetString() : "unknown");

    const std::uint64_t pixels = static_cast<std::uint64_t>(columns) * static_cast<std::uint64_t>(rows) * frames;
    const std::uint64_t bytes = image.GetBufferLength();
    std::uint64_t sampleBytes = pixels ? bytes / pixels : 0;
    ScalarType type = ScalarType::UInt8;
    switch (format.GetScalarType()) {
        case gdcm::PixelFormat::UINT8: type = ScalarType::UInt8; break;
        case gdcm::PixelFormat::INT8: type = ScalarType::UInt8; break;  // widened to int16 below
        case gdcm::PixelFormat::UINT12:
        case gdcm::PixelFormat::UINT16: type = ScalarType::UInt16; break;
        case gdcm::PixelFormat::INT12:
        case gdcm::PixelFormat::INT16: type = ScalarType::Int16; break;
        case gdcm::PixelFormat::UINT32: type = ScalarType::Int32; break;  // converted to float32 below
        case gdcm::PixelFormat::INT32: type = ScalarType::Int32; break;
        case gdcm::PixelFormat::FLOAT32: type = ScalarType::Float32; break;
        case gdcm::PixelFormat::FLOAT64: type = ScalarType::Float64; break;
        default:
            throw InputError(name, "BitsAllocated", "8, 16 or 32-bit integer or float samples",
                             std::to_string(format.GetBitsAllocated()) + " bits (" + format.GetScalarTypeAsString() + ")");
    }
    if (sampleBytes != scalarTypeSize(type) || bytes != pixels * sampleBytes)
        throw InputError(name, "PixelData", std::to_string(pixels) + " samples of " + std::to_string(scalarTypeSize(type)) + " bytes",
                         std::to_string(bytes) + " bytes");

    // What the file holds must be able to give that many bytes, before they are allocated.
    const gdcm::TransferSyntax& syntax = image.GetTransferSyntax();
    const gdcm::DataElement& pixelData = image.GetDataElement();
    if (!syntax.IsEncapsulated()) {
        const gdcm::ByteValue* value = pixelData.GetByteValue();
        std::uint64_t have = value ? static_cast<std::uint64_t>(static_cast<std::uint32_t>(value->GetLength())) : 0;
        if (have < bytes)
            throw InputError(name, "PixelData", std::to_string(bytes) + " bytes (" + std::to_string(columns) + " x " + std::to_string(rows) +
                                                    " x " + std::to_string(frames) + " samples)",
                             std::to_string(have) + " bytes");
    } else {
        const gdcm::SequenceOfFragments* fragments = pixelData.GetSequenceOfFragments();
        double have = fragments ? static_cast<double>(fragments->ComputeByteLength()) : 0.0;
        if (bytes > kAlwaysAcceptedBytes && static_cast<double>(bytes) > kMaxCompressionRatio * have)
            throw InputError(name, "PixelData", "compressed data that can hold " + std::to_string(bytes) + " bytes",
                             fmt(have) + " bytes (a ratio above " + fmt(kMaxCompressionRatio) + ")");
    }

    // JPEG-LS: GDCM 3.0.21's codec asserts (aborts the process) when a stream's own frame header (SOF55, ITU-T
    // T.87 C.2.2) promises more samples than Rows x Columns. Every frame's header must describe this image.
    if (syntax == gdcm::TransferSyntax::JPEGLSLossless || syntax == gdcm::TransferSyntax::JPEGLSNearLossless)
        checkJpegLsFrames(pixelData, columns, rows, frames, format.GetSamplesPerPixel(), format.GetBitsAllocated(), name);

    DecodedImage decoded;
    decoded.samples.resize(bytes);
    if (!image.GetBuffer(reinterpret_cast<char*>(decoded.samples.data())))
        throw InputError(name, "PixelData", "pixel data GDCM can decode",
                         std::string("decoding failed (transfer syntax ") + (syntax.GetString() ? syntax.GetString() : "unknown") + ")");
    const unsigned bitsStored = format.GetBitsStored();
    const bool isSigned = format.GetPixelRepresentation() == 1;
    switch (format.GetScalarType()) {
        case gdcm::PixelFormat::UINT8:
            keepStoredBits<std::uint8_t>(decoded.samples, bitsStored, false);
            break;
        case gdcm::PixelFormat::INT8:
            keepStoredBits<std::int8_t>(decoded.samples, bitsStored, true);
            decoded.samples = widen<std::int8_t, std::int16_t>(decoded.samples);
            type = ScalarType::Int16;
            break;
        case gdcm::PixelFormat::UINT12:
        case gdcm::PixelFormat::UINT16:
        case gdcm::PixelFormat::INT12:
        case gdcm::PixelFormat::INT16:
            keepStoredBits<std::int16_t>(decoded.samples, bitsStored, isSigned);
            break;
        case gdcm::PixelFormat::UINT32:
            keepStoredBits<std::uint32_t>(decoded.samples, bitsStored, false);
            // Exact up to 2^24, like every value curette stores as float32.
            decoded.samples = widen<std::uint32_t, float>(decoded.samples);
            type = ScalarType::Float32;
            break;
        case gdcm::PixelFormat::INT32:
            keepStoredBits<std::int32_t>(decoded.samples, bitsStored, true);
            break;
        default: break;
    }
    decoded.type = type;
    return decoded;
}

double sampleAt(const std::uint8_t* p, ScalarType type) {
    switch (type) {
        case ScalarType::UInt8: return *p;
        case ScalarType::Int16: { std::int16_t v; std::memcpy(&v, p, 2); return v; }
        case ScalarType::UInt16: { std::uint16_t v; std::memcpy(&v, p, 2); return v; }
        case ScalarType::Int32: { std::int32_t v; std::memcpy(&v, p, 4); return v; }
        case ScalarType::Float32: { float v; std::memcpy(&v, p, 4); return v; }
        case ScalarType::Float64: { double v; std::memcpy(&v, p, 8); return v; }
    }
    return 0;
}

std::string seriesList(const std::vector<DicomSeries>& series) {
    std::string list;
    for (const DicomSeries& s : series) {
        if (!list.empty()) list += ", ";
        list += (s.number.empty() ? "(no number)" : s.number) + " (" + s.modality + ", " + std::to_string(s.slices.size()) +
                " images" + (s.description.empty() ? "" : ", \"" + s.description + "\"") + ", " + s.uid + ")";
    }
    return list;
}

}  // namespace

std::string DicomSeries::label() const {
    std::string text = !number.empty() ? "series " + number
                       : !uid.empty()  ? "series with SeriesInstanceUID " + uid
                       : files.empty() ? std::string("a series without number or UID")
                                       : "the series of " + files.front().filename().string();
    if (!description.empty()) text += " \"" + description + "\"";
    return text;
}

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
    forgetGdcmMessages();
    const std::string source = path.string();
    std::error_code ec;
    const bool folder = fs::is_directory(path, ec);
    if (!folder && !fs::is_regular_file(path, ec)) throw InputError(source, "", "a DICOM file or a folder of DICOM files", "no such file");
    std::vector<std::string> files;
    if (folder) {
        files = filesUnder(path, true, source);
    } else {
        // The named file first, so that it stands for its SOP instance when a copy lies beside it.
        fs::path parent = path.parent_path().empty() ? fs::path(".") : path.parent_path();
        files.push_back(path.string());
        for (std::string& f : filesUnder(parent, false, source)) {
            std::error_code e;
            if (!fs::equivalent(f, path, e)) files.push_back(std::move(f));
        }
    }

    const std::size_t fileCount = files.size();
    // Files that are not well formed are not handed to GDCM at all (io/dicom_structure.h).
    std::vector<std::string> unreadable;  // look like DICOM, but cannot be read
    std::vector<std::string> candidates;
    std::map<std::string, std::string> truncated;  // file -> what of its pixel data is missing
    for (std::string& file : files) {
        DicomStructure structure = checkDicomStructure(file, kAlwaysAcceptedBytes);
        const std::string& problem = structure.problem;
        if (problem.empty()) {
            candidates.push_back(std::move(file));
        } else if (structure.onlyTruncatedPixelData) {
            truncated[file] = problem;
            candidates.push_back(std::move(file));
        } else if (!folder && candidates.empty() && unreadable.empty()) {
            throw InputError(file, "", "a well-formed DICOM image file (PS3.5 7.1, 7.5)", problem);
        } else if (looksLikeDicom(file)) {
            unreadable.push_back(fs::path(file).filename().string());
        }
    }
    files = std::move(candidates);

    gdcm::Scanner scanner;
    for (const gdcm::Tag& tag : scannedTags(readIdentifiers)) scanner.AddTag(tag);
    try {
        scanner.Scan(files);
    } catch (const std::exception& e) {
        throw InputError(source, "", "DICOM files GDCM can read", e.what());
    }
    forgetGdcmMessages();  // what GDCM said about the files that are not DICOM

    std::vector<std::unique_ptr<FileHeader>> headers;  // stable addresses for the frames that point at them
    std::map<std::string, std::size_t> seriesByUid;
    std::vector<DicomSeries> series;
    std::vector<std::vector<Frame>> framesOf;
    std::vector<std::set<std::string>> instancesOf;
    std::string namedSeries;  // one file named: only its series
    for (const std::string& file : files) {
        if (!folder && file != files.front()) {
            // One file named: only its series is read; the others are not even looked at further.
            const char* uid = scanner.GetValue(file.c_str(), kSeriesInstanceUid);
            if (!uid || trim(uid, kPadding) != namedSeries) continue;
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
        // A file without a SeriesInstanceUID (Type 1, but stripped by some anonymisers) is a series of its own;
        // its path cannot be mistaken for a UID (digits and dots, PS3.5 9.1).
        auto [it, added] = seriesByUid.emplace(header->seriesUid.empty() ? header->path.string() : header->seriesUid, series.size());
        if (added) {
            DicomSeries s;
            s.uid = header->seriesUid;
            s.number = header->seriesNumber;
            s.description = header->seriesDescription;
            s.modality = header->modality;
            std::string type = header->imageType;
            std::transform(type.begin(), type.end(), type.begin(), [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
            s.localizer = type.find("LOCALIZER") != std::string::npos;
            s.patientName = header->patientName;
            s.patientId = header->patientId;
            s.patientBirthDate = header->patientBirthDate;
            s.accessionNumber = header->accessionNumber;
            series.push_back(std::move(s));
            framesOf.emplace_back();
            instancesOf.emplace_back();
        }
        const std::size_t index = it->second;
        // The same SOP instance twice (copies, or one image in several transfer syntaxes) is one image.
        if (!header->sopInstanceUid.empty() && !instancesOf[index].insert(header->sopInstanceUid).second) continue;
        if (auto t = truncated.find(file); t != truncated.end()) header->truncation = t->second;
        headers.push_back(std::make_unique<FileHeader>(std::move(*header)));
        const FileHeader& h = *headers.back();
        series[index].files.push_back(h.path);
        if (h.frames.empty()) {
            Frame frame;
            frame.slice.file = h.path;
            frame.header = &h;
            framesOf[index].push_back(frame);
        }
        for (std::size_t f = 0; f < h.frames.size(); ++f) {
            Frame frame;
            frame.slice.file = h.path;
            frame.slice.frame = static_cast<unsigned>(f);
            frame.slice.position = h.frames[f].position.value_or(glm::dvec3(0.0));
            frame.slice.rescaleSlope = h.frames[f].slope;
            frame.slice.rescaleIntercept = h.frames[f].intercept;
            frame.geometry = h.frames[f];
            frame.header = &h;
            framesOf[index].push_back(frame);
        }
    }
    if (folder && !unreadable.empty()) {
        // Not an error: folders hold other files. But a slice that is skipped at either end of a series
        // leaves no gap to notice, so say which ones were.
        std::string names;
        for (std::size_t i = 0; i < unreadable.size() && i < 3; ++i) names += (i ? ", " : "") + unreadable[i];
        log::warn(source + ": " + std::to_string(unreadable.size()) + " file(s) that look like DICOM could not be read (" + names +
                  (unreadable.size() > 3 ? ", ..." : "") + ")");
    }
    if (series.empty())
        throw InputError(source, "", "a folder holding DICOM image files",
                         "none of its " + std::to_string(fileCount) + " files is a DICOM image GDCM can read");
    for (std::size_t i = 0; i < series.size(); ++i) placeSlices(series[i], std::move(framesOf[i]));
    return series;
}

DicomChoice chooseDicomSeries(const std::vector<DicomSeries>& series, const std::string& wanted, const std::string& source) {
    if (series.empty()) throw InputError(source, "", "at least one DICOM series", "none");
    if (!wanted.empty()) {
        for (std::size_t i = 0; i < series.size(); ++i)
            if (series[i].uid == wanted) return {i, "asked for by its SeriesInstanceUID"};
        std::vector<std::size_t> matches;
        std::optional<double> wantedNumber = number(wanted);
        for (std::size_t i = 0; i < series.size(); ++i) {
            std::optional<double> n = number(series[i].number);
            if (series[i].number == wanted || (wantedNumber && n && *n == *wantedNumber)) matches.push_back(i);
        }
        if (matches.size() == 1) return {matches.front(), "asked for by its number"};
        if (matches.size() > 1) {
            std::string uids;
            for (std::size_t i : matches) uids += (uids.empty() ? "" : ", ") + series[i].uid;
            throw InputError(source, "series", "a number only one series has, or a SeriesInstanceUID",
                             "\"" + wanted + "\", the number of " + std::to_string(matches.size()) + " series (" + uids + ")");
        }
        throw InputError(source, "series", "the number or SeriesInstanceUID of one of the series: " + seriesList(series),
                         "\"" + wanted + "\"");
    }
    if (series.size() == 1) return {0, "the only series"};
    // The one to plan on: anything before a scout (ImageType LOCALIZER, or at most 3 images), then a volume
    // before what is not one, then the most slices; ties keep the scan order. A scout never opens by default,
    // not even when the main series does not form a volume: then that series opens, and its error says why.
    auto scout = [](const DicomSeries& s) { return s.localizer || s.slices.size() <= 3; };
    auto rank = [&](const DicomSeries& s) { return std::make_tuple(!scout(s), s.formsVolume(), s.slices.size()); };
    std::size_t best = 0;
    for (std::size_t i = 1; i < series.size(); ++i)
        if (rank(series[i]) > rank(series[best])) best = i;
    auto count = [&](auto predicate) { return static_cast<std::size_t>(std::count_if(series.begin(), series.end(), predicate)); };
    const std::size_t candidates = count([&](const DicomSeries& s) { return !scout(s); });
    const std::size_t volumes = count([&](const DicomSeries& s) { return !scout(s) && s.formsVolume(); });
    if (candidates == 0) return {best, "the default: the most slices; all " + std::to_string(series.size()) + " series are scouts of 1-3 images or localizers"};
    if (volumes == 0) return {best, "the default: the most images; none of the " + std::to_string(candidates) + " series that are not scouts forms a volume"};
    return {best, "the default: the most slices of the " + std::to_string(volumes) + " series that form a volume" +
                      (candidates < series.size() ? std::string(" (scouts and localizers aside)") : std::string())};
}

VolumeData readDicomSeries(const DicomSeries& series, const std::string& source, const DicomChoice& choice, bool showIdentifiers) {
    forgetGdcmMessages();
    if (!series.formsVolume()) throw InputError(source, series.label(), series.problemExpected, series.problem);
    const std::size_t pixelsPerSlice = static_cast<std::size_t>(series.dims.x) * static_cast<std::size_t>(series.dims.y);
    const std::size_t sliceCount = series.slices.size();

    // Each file is decoded once, however many of its frames the volume takes.
    std::vector<fs::path> fileOrder;
    std::map<fs::path, std::vector<std::pair<unsigned, std::size_t>>> framesOfFile;  // file -> (frame, slice k)
    for (std::size_t k = 0; k < sliceCount; ++k) {
        auto& frames = framesOfFile[series.slices[k].file];
        if (frames.empty()) fileOrder.push_back(series.slices[k].file);
        frames.emplace_back(series.slices[k].frame, k);
    }
    std::optional<ScalarType> type;
    std::vector<std::uint8_t> samples;
    std::size_t sliceBytes = 0;
    for (const fs::path& file : fileOrder) {
        const auto& frames = framesOfFile[file];
        unsigned framesNeeded = 0;
        for (auto [frame, k] : frames) framesNeeded = std::max(framesNeeded, frame + 1);
        DecodedImage image;
        try {
            image = decodeFile(file, series.dims.x, series.dims.y, framesNeeded);
        } catch (const InputError&) {
            throw;
        } catch (const std::exception& e) {
            throw InputError(file.string(), "PixelData", "pixel data GDCM can decode", e.what());
        }
        if (!type) {
            type = image.type;
            sliceBytes = pixelsPerSlice * scalarTypeSize(*type);
            samples.resize(sliceBytes * sliceCount);
        } else if (image.type != *type) {
            throw InputError(file.string(), "BitsAllocated/PixelRepresentation", std::string("the pixel type of the series' other images (") +
                                                                                      scalarTypeName(*type) + ")",
                             scalarTypeName(image.type));
        }
        for (auto [frame, k] : frames)
            std::memcpy(samples.data() + k * sliceBytes, image.samples.data() + frame * sliceBytes, sliceBytes);
    }

    // One rescale for every slice keeps the stored samples; slices with their own (PET, some MR) are
    // converted to their physical values in float32.
    const DicomSlice& first = series.slices.front();
    bool oneRescale = std::all_of(series.slices.begin(), series.slices.end(), [&](const DicomSlice& s) {
        return s.rescaleSlope == first.rescaleSlope && s.rescaleIntercept == first.rescaleIntercept;
    });
    VolumeData volume;
    if (oneRescale) {
        volume = buildVolume(source, series.dims, *type, samples.data(), false, first.rescaleSlope, first.rescaleIntercept, series.indexToWorld);
    } else {
        std::vector<std::uint8_t> physical(pixelsPerSlice * sliceCount * sizeof(float));
        const std::size_t size = scalarTypeSize(*type);
        for (std::size_t k = 0; k < sliceCount; ++k)
            for (std::size_t p = 0; p < pixelsPerSlice; ++p) {
                std::size_t index = k * pixelsPerSlice + p;
                float v = static_cast<float>(series.slices[k].rescaleSlope * sampleAt(samples.data() + index * size, *type) +
                                             series.slices[k].rescaleIntercept);
                std::memcpy(physical.data() + index * sizeof(float), &v, sizeof v);
            }
        volume = buildVolume(source, series.dims, ScalarType::Float32, physical.data(), false, 1.0, 0.0, series.indexToWorld);
    }
    volume.description = "DICOM " + (series.modality.empty() ? std::string("image") : series.modality) + " " + series.label() + ", " +
                         std::to_string(sliceCount) + (sliceCount == 1 ? " slice" : " slices") +
                         (series.uid.empty() ? std::string() : ", SeriesInstanceUID " + series.uid) + "; opened as " + choice.reason;
    if (showIdentifiers)
        volume.description += "; patient \"" + series.patientName + "\", PatientID \"" + series.patientId + "\"";
    return volume;
}

VolumeData readDicomSeries(const fs::path& path, const VolumeReadOptions& options) {
    const std::string source = path.string();
    if (options.volumeIndex != 0)
        throw InputError(source, "volume", "0 for a DICOM series (choose the series by its number or UID instead)",
                         std::to_string(options.volumeIndex));
    std::vector<DicomSeries> series = scanDicom(path, options.showIdentifiers);
    DicomChoice choice = chooseDicomSeries(series, options.series, source);
    return readDicomSeries(series[choice.index], source, choice, options.showIdentifiers);
}

}  // namespace curette::io
