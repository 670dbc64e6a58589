#include "plan/report_output.h"

#include "base/atomic_file.h"
#include "base/error.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <system_error>

namespace curette::plan {

namespace {

nlohmann::json distanceOrNull(double mm) { return std::isfinite(mm) ? nlohmann::json(mm) : nlohmann::json(nullptr); }

std::string number(double x) {
    if (!std::isfinite(x)) return {};
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.6g", x);
    return buffer;
}

const char* boolean(bool b) { return b ? "true" : "false"; }

std::string row(std::initializer_list<std::string> fields) {
    std::string line;
    for (const std::string& f : fields) {
        if (!line.empty()) line += ',';
        line += f;
    }
    return line + "\r\n";
}

// A figure with its uncertainty, "3.459 +-0.012" ("-" when infinite).
std::string withUncertainty(double value, double uncertainty, int decimals) {
    if (!std::isfinite(value)) return "-";
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*f +-%.*f", decimals, value, decimals, uncertainty);
    return buffer;
}

nlohmann::json vec3(const glm::dvec3& v) { return {v.x, v.y, v.z}; }

nlohmann::json provenanceJson(const ReportProvenance& p) {
    nlohmann::json files = nlohmann::json::array();
    for (const InputFileDigest& f : p.files) {
        nlohmann::json entry = {{"role", f.role}};
        if (!f.name.empty()) entry["name"] = f.name;
        entry["path"] = f.path;
        entry["files"] = f.files;
        entry["sha256"] = f.sha256;
        files.push_back(entry);
    }
    nlohmann::json meshes = nlohmann::json::array();
    for (const MeshPoseRecord& m : p.meshes)
        meshes.push_back({{"name", m.name},
                          {"position_mm", vec3(m.positionMm)},
                          {"orientation_wxyz", {m.orientation.w, m.orientation.x, m.orientation.y, m.orientation.z}},
                          {"rotation_deg", vec3(m.rotationDeg)},
                          {"scale", vec3(m.scale)}});
    return {{"created_utc", p.createdUtc},
            {"curette_version", p.curetteVersion},
            {"files", files},
            {"transfer_function", nlohmann::json::parse(p.transferFunctionJson)},
            {"clip_meshes", meshes}};
}

}  // namespace

std::string csvField(const std::string& text) {
    if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
    std::string quoted = "\"";
    for (char c : text) {
        if (c == '"') quoted += '"';
        quoted += c;
    }
    return quoted + "\"";
}

std::string reportJson(const Report& r, const ReportProvenance& provenance) {
    nlohmann::json j;
    j["schema"] = "curette.report/1";
    j["volume"] = {{"source", r.volumeSource},
                   {"dims", {r.dims.x, r.dims.y, r.dims.z}},
                   {"spacing_mm", {r.spacingMm.x, r.spacingMm.y, r.spacingMm.z}},
                   {"voxel_volume_ml", r.voxelVolumeMl}};
    j["tissue"] = {{"rule", tissueRuleName(r.tissue)}, {"opacity_threshold", r.opacityThreshold}};
    j["field"] = {{"origin", {r.fieldBox.origin.x, r.fieldBox.origin.y, r.fieldBox.origin.z}},
                  {"size", {r.fieldBox.size.x, r.fieldBox.size.y, r.fieldBox.size.z}},
                  {"samples_per_voxel", r.samplesPerVoxel}};
    j["removed_ml"] = r.removedMl;
    j["removed_ml_uncertainty"] = r.removedUncertaintyMl;
    j["face_placement_mm"] = r.facePlacementMm;
    j["touched_voxels"] = r.touchedVoxels;
    j["partial_voxels"] = r.partialVoxels;
    j["removed_region_voxels"] = r.removedRegionVoxels;
    j["structures"] = nlohmann::json::array();
    for (const StructureRow& s : r.structures)
        j["structures"].push_back({{"label_set", s.labelSet}, {"id", s.id}, {"name", s.name}, {"protected", s.isProtected},
                                   {"touched", s.touched}, {"voxels", s.voxels}, {"touched_voxels", s.touchedVoxels},
                                   {"volume_ml", s.volumeMl}, {"removed_ml", s.removedMl},
                                   {"removed_ml_uncertainty", s.removedUncertaintyMl}, {"share_fraction", s.share},
                                   {"intrusion_depth_mm", s.intrusionDepthMm}, {"intrusion_depth_uncertainty_mm", s.intrusionUncertaintyMm},
                                   {"margin_mm", distanceOrNull(s.marginMm)}, {"margin_uncertainty_mm", s.marginUncertaintyMm}});
    j["bundles"] = nlohmann::json::array();
    for (const BundleRow& b : r.bundles)
        j["bundles"].push_back({{"name", b.name}, {"protected", b.isProtected}, {"streamlines", b.streamlines},
                                {"cut_streamlines", b.cut}, {"share_fraction", b.share}, {"total_length_mm", b.totalLengthMm},
                                {"removed_length_mm", b.removedLengthMm}, {"margin_mm", distanceOrNull(b.marginMm)},
                                {"margin_uncertainty_mm", b.marginUncertaintyMm}});
    j["warnings"] = r.warnings();
    j["timings_ms"] = {{"tissue_ms", r.timings.tissueMs},         {"distance_ms", r.timings.distanceMs},
                       {"structures_ms", r.timings.structuresMs}, {"intrusion_ms", r.timings.intrusionMs},
                       {"bundles_ms", r.timings.bundlesMs},       {"total_ms", r.timings.totalMs}};
    j["provenance"] = provenanceJson(provenance);
    return j.dump(2) + "\n";
}

std::string structuresCsv(const Report& r) {
    std::string out = row({"label_set", "id", "name", "protected", "touched", "voxels", "touched_voxels", "volume_ml",
                           "removed_ml", "removed_ml_uncertainty", "share_fraction", "intrusion_depth_mm",
                           "intrusion_depth_uncertainty_mm", "margin_mm", "margin_uncertainty_mm"});
    for (const StructureRow& s : r.structures)
        out += row({csvField(s.labelSet), std::to_string(s.id), csvField(s.name), boolean(s.isProtected), boolean(s.touched),
                    std::to_string(s.voxels), std::to_string(s.touchedVoxels), number(s.volumeMl), number(s.removedMl),
                    number(s.removedUncertaintyMl), number(s.share), number(s.intrusionDepthMm), number(s.intrusionUncertaintyMm),
                    number(s.marginMm), number(s.marginUncertaintyMm)});
    return out;
}

std::string bundlesCsv(const Report& r) {
    std::string out = row({"name", "protected", "streamlines", "cut_streamlines", "share_fraction", "total_length_mm",
                           "removed_length_mm", "margin_mm", "margin_uncertainty_mm"});
    for (const BundleRow& b : r.bundles)
        out += row({csvField(b.name), boolean(b.isProtected), std::to_string(b.streamlines), std::to_string(b.cut),
                    number(b.share), number(b.totalLengthMm), number(b.removedLengthMm), number(b.marginMm),
                    number(b.marginUncertaintyMm)});
    return out;
}

void writeReportFiles(const Report& report, const ReportProvenance& provenance, const std::filesystem::path& directory) {
    std::error_code error;
    std::filesystem::create_directories(directory, error);
    if (error) throw SystemError("cannot create " + directory.string() + ": " + error.message());
    writeFileAtomically(directory / "report.json", reportJson(report, provenance));
    writeFileAtomically(directory / "structures.csv", structuresCsv(report));
    writeFileAtomically(directory / "bundles.csv", bundlesCsv(report));
}

std::string reportSummary(const Report& r) {
    std::string out;
    char line[512];
    std::snprintf(line, sizeof line, "removed %s mL of tissue (%llu voxels touched, voxel %.3g x %.3g x %.3g mm, tissue rule %s)\n",
                  withUncertainty(r.removedMl, r.removedUncertaintyMl, 2).c_str(), static_cast<unsigned long long>(r.touchedVoxels),
                  r.spacingMm.x, r.spacingMm.y, r.spacingMm.z, tissueRuleName(r.tissue));
    out += line;
    if (!r.structures.empty()) {
        std::snprintf(line, sizeof line, "  %-32s %10s %15s %7s %10s %11s\n", "structure", "volume mL", "removed mL", "share",
                      "depth mm", "margin mm");
        out += line;
        for (const StructureRow& s : r.structures) {
            std::string name = s.labelSet.empty() ? s.name : s.labelSet + "/" + s.name;
            if (s.isProtected) name += " [protected]";
            std::snprintf(line, sizeof line, "  %-32.32s %10.2f %15s %6.1f%% %10s %11s\n", name.c_str(), s.volumeMl,
                          withUncertainty(s.removedMl, s.removedUncertaintyMl, 3).c_str(), 100.0 * s.share,
                          withUncertainty(s.intrusionDepthMm, s.intrusionUncertaintyMm, 1).c_str(),
                          s.touched ? "contact" : withUncertainty(s.marginMm, s.marginUncertaintyMm, s.marginUncertaintyMm < 0.1 ? 2 : 1).c_str());
            out += line;
        }
    }
    if (!r.bundles.empty()) {
        std::snprintf(line, sizeof line, "  %-32s %10s %15s %7s %10s %11s\n", "bundle", "streamlines", "cut", "share",
                      "cut mm", "margin mm");
        out += line;
        for (const BundleRow& b : r.bundles) {
            std::string name = b.isProtected ? b.name + " [protected]" : b.name;
            std::snprintf(line, sizeof line, "  %-32.32s %10llu %15llu %6.1f%% %10.1f %11s\n", name.c_str(),
                          static_cast<unsigned long long>(b.streamlines), static_cast<unsigned long long>(b.cut), 100.0 * b.share,
                          b.removedLengthMm, withUncertainty(b.marginMm, b.marginUncertaintyMm, 1).c_str());
            out += line;
        }
    }
    for (const std::string& w : r.warnings()) out += w + "\n";
    return out;
}

}  // namespace curette::plan
