#include "session/dicom_plan_export.h"

#include "io/dicom.h"
#include "io/dicom_reference.h"
#include "io/dicom_rtstruct_writer.h"
#include "io/dicom_seg_writer.h"
#include "io/dicom_series_writer.h"

#include <algorithm>

namespace curette {

namespace fs = std::filesystem;

namespace {

// LO (PS3.5 6.2): at most 64 characters, no backslash.
std::string longString(std::string text) {
    std::replace(text.begin(), text.end(), '\\', '/');
    if (text.size() > 64) text.resize(64);
    return text;
}

bool readFromDicom(const LoadedScene& loaded) {
    const io::VolumeReadOptions& o = loaded.scene.volumeOptions;
    return o.format == io::VolumeFormat::Dicom || (o.format == io::VolumeFormat::Auto && io::looksLikeDicom(loaded.scene.volumePath));
}

std::vector<io::DicomPlanStructure> planStructures(const LoadedScene& loaded, const plan::Report& report,
                                                   const std::vector<std::uint8_t>& removedRegion) {
    std::vector<io::DicomPlanStructure> out;
    io::DicomPlanStructure removed;
    removed.label = "removed region";
    removed.description = "the voxels the carve removes (curette report)";
    removed.color = glm::dvec3(0.85, 0.2, 0.15);
    removed.category = {"309825002", "SCT", "Spatial and Relational Concept"};
    removed.type = {"REMOVED", "99CURETTE", "Planned removal region"};
    removed.algorithmType = "SEMIAUTOMATIC";
    removed.algorithmName = "curette carve";
    removed.interpretedType = "CAVITY";
    removed.mask = removedRegion;
    out.push_back(std::move(removed));
    for (const plan::StructureRow& row : report.structures) {
        if (!row.isProtected && !row.touched) continue;
        auto set = std::find_if(loaded.labels.begin(), loaded.labels.end(), [&](const LoadedLabelSet& s) { return s.name == row.labelSet; });
        if (set == loaded.labels.end()) continue;
        const std::size_t setIndex = std::size_t(set - loaded.labels.begin());
        io::DicomPlanStructure s;
        s.label = longString(row.name);
        s.description = longString(row.labelSet + " label " + std::to_string(row.id) + (row.isProtected ? ", protected" : "") +
                                   (row.touched ? ", touched by the carve" : ""));
        if (const LabelEntry* entry = set->table.find(row.id)) s.color = glm::dvec3(entry->rgba);
        s.category = {"91723000", "SCT", "Anatomical Structure"};
        s.type = {"L" + std::to_string(setIndex + 1) + "-" + std::to_string(row.id), "99CURETTE", longString(row.name)};
        s.algorithmType = "AUTOMATIC";
        s.algorithmName = "curette label resampling";
        s.interpretedType = row.isProtected ? "AVOIDANCE" : "ORGAN";
        s.mask.resize(set->onScanGrid.ids.size());
        for (std::size_t n = 0; n < s.mask.size(); ++n) s.mask[n] = set->onScanGrid.ids[n] == row.id ? 1 : 0;
        out.push_back(std::move(s));
    }
    out.erase(std::remove_if(out.begin(), out.end(),
                             [](const io::DicomPlanStructure& s) { return std::none_of(s.mask.begin(), s.mask.end(), [](std::uint8_t v) { return v != 0; }); }),
              out.end());
    return out;
}

}  // namespace

std::string writePlanDicom(const fs::path& directory, const LoadedScene& loaded, const plan::Report& report,
                           const std::vector<std::uint8_t>& removedRegion, const DicomExportOptions& options) {
    std::vector<io::DicomPlanStructure> structures = planStructures(loaded, report, removedRegion);
    if (structures.empty()) return "DICOM: nothing removed and no protected or touched structure: no seg.dcm or rtstruct.dcm\n";

    std::string which;
    std::optional<io::DicomReferencedSeries> series;
    const bool dicomSource = readFromDicom(loaded);
    if (dicomSource && !options.anonymize) {
        io::DicomSourceReading reading = io::readDicomSourceSeries(loaded.volume);
        if (reading.series) {
            series = std::move(reading.series);
            which = "they reference the source DICOM series (" + std::to_string(series->images.size()) +
                    " images; its Study and Frame of Reference)";
        } else {
            which = "the source DICOM series cannot be referenced slice by slice (" + reading.problem + "), so ";
        }
    }
    if (!series) {
        io::DicomSeriesWriteOptions write;
        write.modality = io::guessModality(loaded.volume);
        write.seriesDescription = "curette: the scan the plan was drawn on";
        write.softwareVersion = options.programVersion;
        io::DicomPatientStudy who = options.anonymize ? io::anonymousPatientStudy() : io::DicomPatientStudy{};
        series = io::writeDicomSeries(directory / "scan-dicom", loaded.volume, who, write);
        const std::string why = options.anonymize ? "--anonymize: patient and study replaced, new UIDs"
                                : dicomSource    ? "new UIDs"
                                                 : "the scan is not DICOM; new UIDs, one Frame of Reference";
        which += "the scan was written as a DICOM " + write.modality + " series, scan-dicom/ (" + std::to_string(series->images.size()) +
                 " slices; " + why + "), and they reference it";
    }

    io::DicomObjectInfo seg{"curette plan (segmentation)", 100, "CURETTE_PLAN", options.programVersion};
    io::writeDicomSegmentation(directory / "seg.dcm", *series, structures, seg);
    io::DicomObjectInfo rt{"curette plan (structure set)", 101, "CURETTE_PLAN", options.programVersion};
    io::writeDicomRtStruct(directory / "rtstruct.dcm", *series, structures, rt);
    std::string names;
    for (const io::DicomPlanStructure& s : structures) names += (names.empty() ? "" : ", ") + s.label;
    return "DICOM: seg.dcm and rtstruct.dcm (" + std::to_string(structures.size()) + (structures.size() == 1 ? " region: " : " regions: ") +
           names + "); " + which + "\n";
}

}  // namespace curette
