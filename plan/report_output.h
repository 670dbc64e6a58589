#pragma once
// The report on disk and on the terminal. Files (written atomically, base/atomic_file.h):
//
// report.json (schema "curette.report/1"; every number carries its unit in its key; distances that are
// infinite because nothing is removed are null):
//   { "schema": "curette.report/1",
//     "volume": { "source": str, "dims": [i, j, k], "spacing_mm": [x, y, z], "voxel_volume_ml": num },
//     "tissue": { "rule": "opacity" | "labels" | "all", "opacity_threshold": num },
//     "field": { "origin": [i, j, k], "size": [i, j, k], "samples_per_voxel": int },
//     "removed_ml": num, "touched_voxels": int, "removed_region_voxels": int,
//     "structures": [ { "label_set": str, "id": int, "name": str, "protected": bool, "touched": bool,
//                       "voxels": int, "touched_voxels": int, "volume_ml": num, "removed_ml": num,
//                       "share_fraction": num, "intrusion_depth_mm": num, "margin_mm": num | null } ],
//     "bundles": [ { "name": str, "protected": bool, "streamlines": int, "cut_streamlines": int,
//                    "share_fraction": num, "total_length_mm": num, "removed_length_mm": num,
//                    "margin_mm": num | null } ],
//     "warnings": [ str ],
//     "timings_ms": { "tissue_ms": num, "distance_ms": num, "structures_ms": num, "intrusion_ms": num,
//                     "bundles_ms": num, "total_ms": num },
//     "provenance": { "created_utc": "YYYY-MM-DDTHH:MM:SSZ", "curette_version": str (as `curette --version`),
//                     "files": [ { "role": "volume" | "labels" | "label_table" | "label_colors" | "tracts",
//                                  "name": str (label set or bundle; absent for the volume), "path": str,
//                                  "files": int, "sha256": str } ],
//                     "transfer_function": { the TF the report used, as a TF file (io/transfer_function_file.h) },
//                     "clip_meshes": [ { "name": str, "position_mm": [x, y, z], "orientation_wxyz": [w, x, y, z],
//                                        "rotation_deg": [x, y, z], "scale": [x, y, z] } ] } }
// A file entry's path is the one the scene names, made absolute. Read from one file, "sha256" is its SHA-256 as
// sha256sum prints it; from several ("files" > 1: a DICOM series, a header and its data file), the SHA-256 of
// their digests, each as 64 hex digits and a line feed, the files in the order of their paths; their names are
// not written (a DICOM file name can be a UID). No patient identifier is written.
// structures.csv: label_set,id,name,protected,touched,voxels,touched_voxels,volume_ml,removed_ml,
//                 share_fraction,intrusion_depth_mm,margin_mm
// bundles.csv:    name,protected,streamlines,cut_streamlines,share_fraction,total_length_mm,removed_length_mm,
//                 margin_mm
// CSV: a header row, RFC 4180 (fields with a comma, quote or line break in double quotes, quotes doubled),
// CRLF line ends; booleans as true/false; an infinite margin is an empty field.

#include "plan/removal_report.h"

#include <glm/gtc/quaternion.hpp>

#include <filesystem>
#include <string>

namespace curette::plan {

// What a report was made from, as data: plan/ knows neither the program's version nor the scene's files
// (session/carve_report.h gathers them).
struct InputFileDigest {
    std::string role;          // "volume", "labels", "label_table", "label_colors", "tracts"
    std::string name;          // the label set or bundle; empty for the volume
    std::string path;          // absolute
    std::size_t files = 1;
    std::string sha256;        // 64 lower-case hex digits (above)
};
struct MeshPoseRecord {
    std::string name;
    glm::dvec3 positionMm{0.0};
    glm::dquat orientation{1.0, 0.0, 0.0, 0.0};
    glm::dvec3 rotationDeg{0.0};   // the same orientation as a scene's "rotation_deg"
    glm::dvec3 scale{1.0};
};
struct ReportProvenance {
    std::string createdUtc;        // ISO 8601
    std::string curetteVersion;
    std::vector<InputFileDigest> files;
    std::string transferFunctionJson;
    std::vector<MeshPoseRecord> meshes;
};

std::string reportJson(const Report& report, const ReportProvenance& provenance);  // report.json's text, indented
std::string structuresCsv(const Report& report);
std::string bundlesCsv(const Report& report);

// Writes report.json, structures.csv and bundles.csv into `directory` (created when missing).
void writeReportFiles(const Report& report, const ReportProvenance& provenance, const std::filesystem::path& directory);

// A short table for the terminal: removed mL, the touched or protected structures, the bundles, and a
// WARNING line for each protected structure or bundle the carve touches.
std::string reportSummary(const Report& report);

// One CSV field, quoted per RFC 4180 when needed (exposed for tests).
std::string csvField(const std::string& text);

}  // namespace curette::plan
