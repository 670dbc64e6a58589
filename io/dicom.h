#pragma once
// DICOM import through GDCM (libgdcm 3.0): a folder (scanned recursively) or one file (then the files of its
// series in its folder). Files are grouped into series by SeriesInstanceUID; the images (single-frame files,
// or the frames of multi-frame and enhanced objects) are sorted along the slice normal and must form one
// regular volume: one orientation, slices stacked along their normal (no gantry tilt), uniform steps (within
// 0.01 mm), no missing slice. Otherwise the series is listed but refused with an InputError saying why.
// Positions of multi-frame images: per-frame functional groups (enhanced objects, PS3.3 C.7.6.16) or the RT
// dose GridFrameOffsetVector (C.8.8.3.2). Only files that pass io/dicom_structure.h reach GDCM.
//
// Geometry (PS3.3 C.7.6.2.1.1): ImageOrientationPatient = row direction X (the way column index i grows),
// then column direction Y; PixelSpacing = row spacing (between rows, along Y) first, then column spacing;
// P(i,j) = IPP + i PS[1] X + j PS[0] Y. The affine is converted from DICOM's LPS to curette's RAS.
//
// Patient name and identifiers are read only when asked for (`readIdentifiers`), so they cannot leak into a
// message, a description or the output otherwise.

#include "io/volume_file.h"
#include "base/volume.h"

#include <filesystem>
#include <string>
#include <vector>

namespace curette::io {

// One image of a series: a single-frame file, or one frame of a multi-frame file.
struct DicomSlice {
    std::filesystem::path file;
    unsigned frame = 0;             // 0-based frame within the file
    glm::dvec3 position{0.0};       // ImagePositionPatient (0020,0032) of its first pixel, LPS mm
    double rescaleSlope = 1.0;      // RescaleSlope (0028,1053), or DoseGridScaling (3004,000E) for RT dose
    double rescaleIntercept = 0.0;  // RescaleIntercept (0028,1052)
};

struct DicomSeries {
    std::string uid;          // SeriesInstanceUID (0020,000E)
    std::string number;       // SeriesNumber (0020,0011); "" when the files have none
    std::string description;  // SeriesDescription (0008,103E)
    std::string modality;     // Modality (0008,0060)
    bool localizer = false;   // ImageType (0008,0008) says LOCALIZER (a scout, PS3.3 C.8.2.1.1.1)
    std::vector<std::filesystem::path> files;
    std::vector<DicomSlice> slices;  // along the slice normal when the series forms a volume
    glm::ivec3 dims{0};              // columns, rows, slices
    glm::dmat4 indexToWorld{1.0};    // voxel-centre index (i,j,k) -> world mm (RAS), when it forms a volume
    // Why the images do not form one regular volume: the expected form and what was found ("" when they do).
    std::string problemExpected, problem;
    // Filled only when scanDicom was asked for identifiers; empty otherwise.
    std::string patientName, patientId, patientBirthDate, accessionNumber;

    bool formsVolume() const { return problem.empty(); }
    // `series 5 "SmartScore"`, for messages and tables.
    std::string label() const;
};

// True for a directory, a name ending in .dcm, or a file with "DICM" at byte 128 (PS3.10 7.1).
bool looksLikeDicom(const std::filesystem::path& path);

// Every image series under `path` (a folder, recursively), or the series of the file `path` (with the other
// files of that series in the same folder; copies of the same SOPInstanceUID count once, the named file
// first). Series come in the order their first file sorts by path; a file without SeriesInstanceUID is a
// series of its own. In a folder, files that are not DICOM images are passed over, and those that look like
// DICOM but cannot be read are named in a log warning; a named file that cannot be read is an InputError,
// and so is a folder without any image.
std::vector<DicomSeries> scanDicom(const std::filesystem::path& path, bool readIdentifiers = false);

struct DicomChoice {
    std::size_t index = 0;  // into the scanned series
    std::string reason;     // why this one: asked for by number or UID, or which default rule
};

// The series `wanted` names (a SeriesNumber or a SeriesInstanceUID), or when it is empty the default: the
// one with the most slices among those that form a volume. Scouts (ImageType LOCALIZER, or 1-3 images) rank
// below every other series, so when the main series does not form a volume it is still the one that opens
// (and readDicomSeries says why it cannot). Throws InputError when `wanted` matches no series, or a number
// matches several.
DicomChoice chooseDicomSeries(const std::vector<DicomSeries>& series, const std::string& wanted, const std::string& source);

// Decodes a scanned series (every transfer syntax GDCM decodes) into a volume with rescaled values
// (Hounsfield units for CT). Throws InputError naming the series when it does not form a volume.
VolumeData readDicomSeries(const DicomSeries& series, const std::string& source, const DicomChoice& choice,
                           bool showIdentifiers = false);

// scanDicom + chooseDicomSeries(options.series) + readDicomSeries: what readVolume does for DICOM.
VolumeData readDicomSeries(const std::filesystem::path& path, const VolumeReadOptions& options);

}  // namespace curette::io
