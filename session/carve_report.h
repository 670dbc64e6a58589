#pragma once
// The removal report of the current carve, as `curette report`, `replay --report` and the viewer produce it,
// of one interaction state (the one the image shows: its TF, bundles and meshes): the GPU removal field and tract flags (render/passes/removal_probe.h: the renderer's own clip maps and step IV's
// sample pattern), the report (plan/removal_report.h), and the plan's files:
//   report.json, structures.csv, bundles.csv           plan/report_output.h
//   removed.nii.gz       the removed region R as a labelmap on the scan grid (1 = removed)
//   removed.seg.nrrd     the same as a 3D Slicer segmentation (segment "removed", colour, extent)
//   cavity.stl, cavity.gltf  the surface of R (plan/cavity_surface.h), closed, RAS mm (LPS with --lps)
//   plan-scene.json      the state as a scene: meshes where they are now, every edited setting (session/plan_scene.h)
//   tracts/<bundle>-cut.tck, tracts/<bundle>-spared.tck
// Every file is written atomically, so an interrupted run leaves no half-written file that looks complete.

#include "session/interaction.h"
#include "session/loaded_scene.h"
#include "io/mesh_writers.h"
#include "plan/removal_report.h"
#include "plan/report_output.h"
#include "render/passes/removal_probe.h"
#include "render/renderer.h"

#include <filesystem>
#include <string>

namespace curette {

// What of a state the report depends on besides the volume, the labels and the scene's report settings: the
// clip meshes (their set's version: shapes, scales, poses), the transfer function (the tissue rule reads its
// opacity) and the bundles (a tubes edit renames them or changes which are protected). One definition, for
// the reporter and for when the viewer's plan table must be computed again.
struct ReportInputs {
    std::uint64_t meshes = 0, transferFunction = 0, tubes = 0;
    std::uint64_t removal = 0;   // the drilled removal's version (plan/removal_volume.h)
    bool operator==(const ReportInputs&) const = default;
};
ReportInputs reportInputs(const clip::ClipMeshSet& clip, const InteractionState& state);

struct PlanExportOptions {
    io::MeshSpace meshSpace = io::MeshSpace::Ras;
    bool exports = true;   // false: report.json and the CSVs only (replay --report)
};

class CarveReporter {
public:
    // Resolves the scene's report settings against its labels, prepares each bundle's probe points (they do
    // not move; only their inside flags change with the meshes) and takes the SHA-256 of the volume, label and
    // tract files now, just after the scene was loaded from them. `programVersion` is what report.json names as its
    // maker (`curette --version`'s line, handed in by the command).
    CarveReporter(const LoadedScene& loaded, const VolumeGeometry& geometry, std::string programVersion);

    // The report of `state` (its transfer function and bundles) under the clip meshes' current poses (the
    // renderer's ClipMeshSet, which the session step keeps in sync with `state`). Keeps the field and the
    // state's report inputs for the exports.
    plan::Report compute(clip::ClipMeshSet& clip, const InteractionState& state);
    const plan::RemovalField& lastField() const { return field_; }
    // The removed region R of the last compute() on the scan grid (plan::removedRegionOnGrid over the tissue the
    // report counted): 1 where removed, what removed.nii.gz holds and the slice views tint. Empty before compute().
    std::vector<std::uint8_t> removedRegion() const;
    // Wall time of the GPU parts of the last compute(): the removal field (with the maps' update) and the
    // tract flags (computeReport's own parts are in Report::timings).
    double lastFieldMs() const { return fieldMs_; }
    double lastFlagsMs() const { return flagsMs_; }
    double lastGpuMs() const { return fieldMs_ + flagsMs_; }
    const std::vector<plan::BundleInput>& bundles() const { return bundles_; }
    const plan::ReportSettings& settings() const { return settings_; }
    const std::vector<plan::LabelSet>& labelSets() const { return labelSets_; }

    // Writes the report (its provenance: now, the program, the input files' digests, the TF and the meshes'
    // poses) and (with options.exports) the plan's files into `directory` (created if needed); call after
    // compute(), whose field and TF the exports are made from. `state` is the interaction state the report
    // was computed under (plan-scene.json is written from it); another is a logic_error.
    void write(const std::filesystem::path& directory, const plan::Report& report, const InteractionState& state,
               const PlanExportOptions& options) const;

private:
    // The tissue over the last field's box (plan/tissue_mask.h), as the report counted it.
    std::vector<std::uint8_t> tissueInField() const;
    plan::ReportProvenance provenance(const InteractionState& state) const;

    const LoadedScene& loaded_;
    std::string programVersion_;
    std::vector<plan::InputFileDigest> inputFiles_;   // tracts' names are the state's, at write()
    TransferFunction transferFunction_;   // the last compute()'s state's
    ReportInputs inputs_;                 // and its inputs
    std::vector<SessionMesh> poses_;      // and its meshes' poses
    plan::ReportSettings settings_;
    std::vector<plan::LabelSet> labelSets_;
    std::vector<plan::BundleInput> bundles_;
    RemovalProbe probe_;
    plan::RemovalField field_;
    double fieldMs_ = 0, flagsMs_ = 0;
};

// `--report` and the viewer's overlay: one line per row, as the terminal summary prints it.
std::string carveSummary(const plan::Report& report);

}  // namespace curette
