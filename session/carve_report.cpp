#include "session/carve_report.h"

#include "io/nifti_writer.h"
#include "io/seg_nrrd_writer.h"
#include "io/tck_writer.h"
#include "io/transfer_function_file.h"
#include "session/live_input.h"
#include "session/plan_scene.h"
#include "session/session_step.h"
#include "base/atomic_file.h"
#include "base/error.h"
#include "base/sha256.h"
#include "plan/cavity_surface.h"
#include "plan/tissue_mask.h"

#include <algorithm>
#include <cctype>
#include <chrono>

namespace curette {

namespace fs = std::filesystem;

namespace {

plan::ReportSettings resolveSettings(const LoadedScene& loaded) {
    const ReportSpec& spec = loaded.scene.report;
    plan::ReportSettings s;
    s.opacityThreshold = spec.opacityThreshold;
    s.tissue = spec.tissue == ReportSpec::Tissue::Opacity ? plan::TissueRule::Opacity
               : spec.tissue == ReportSpec::Tissue::Labels ? plan::TissueRule::Labels
                                                           : plan::TissueRule::All;
    if (s.tissue == plan::TissueRule::Labels) {
        const LabelTable& table = loaded.labels.front().table;
        s.tissueLabelIds = resolveLabelIds(spec.tissueLabels, table, loaded.scene.file.string(), "report.tissue_labels");
        if (spec.tissueLabels.empty())  // every label of the first set (a brain mask, say) is tissue
            for (const LabelEntry& e : table.entries)
                if (e.id > 0) s.tissueLabelIds.push_back(e.id);
    }
    return s;
}

// The digest of a file as a scene names it, read from `files` (plan/report_output.h: one file's SHA-256, or
// that of several files' digests in the order of their paths; their names are not kept).
plan::InputFileDigest digestOf(std::string role, std::string name, const fs::path& named, std::vector<fs::path> files) {
    plan::InputFileDigest d{std::move(role), std::move(name), fs::absolute(named).lexically_normal().string(), files.size(), {}};
    if (files.size() == 1) {
        d.sha256 = sha256OfFile(files.front());
    } else {
        std::sort(files.begin(), files.end());
        Sha256 digests;
        for (const fs::path& f : files) digests.update(sha256OfFile(f) + "\n");
        d.sha256 = digests.hexDigest();
    }
    return d;
}

std::vector<plan::InputFileDigest> inputFileDigests(const LoadedScene& loaded) {
    std::vector<plan::InputFileDigest> out;
    out.push_back(digestOf("volume", "", loaded.scene.volumePath, loaded.volume.files));
    for (std::size_t i = 0; i < loaded.labels.size(); ++i) {
        const LoadedLabelSet& set = loaded.labels[i];
        out.push_back(digestOf("labels", set.name, loaded.scene.labels[i].path, set.volumeFiles));
        if (set.tableFile) out.push_back(digestOf("label_table", set.name, *set.tableFile, {*set.tableFile}));
        if (set.colorsFile) out.push_back(digestOf("label_colors", set.name, *set.colorsFile, {*set.colorsFile}));
    }
    for (const SceneTubes& t : loaded.scene.tubes) out.push_back(digestOf("tracts", t.name, t.path, {t.path}));
    return out;
}

// A file-system-friendly form of a bundle name ("AF_L" stays, "left arcuate" -> "left_arcuate").
std::string fileName(const std::string& name) {
    std::string out;
    for (char c : name) out += (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.') ? c : '_';
    return out.empty() ? "bundle" : out;
}

}  // namespace

CarveReporter::CarveReporter(const LoadedScene& loaded, const VolumeGeometry& geometry, std::string programVersion)
    : loaded_(loaded),
      programVersion_(std::move(programVersion)),
      inputFiles_(inputFileDigests(loaded)),
      settings_(resolveSettings(loaded)),
      probe_(geometry, plan::kReportAntiAliasingSamples) {
    for (const LoadedLabelSet& set : loaded.labels) {
        plan::LabelSet s{set.name, &set.onScanGrid, &set.table, set.protectedIds, {}};
        // The opacity the renderer draws each id with (scene/scene_labels.h labelRendering: the set's opacity
        // where the id is shown).
        s.shownOpacity.assign(set.shown.size(), 0.0);
        for (std::size_t id = 1; id < set.shown.size(); ++id)
            if (set.shown[id]) s.shownOpacity[id] = set.opacity;
        labelSets_.push_back(std::move(s));
    }
    for (std::size_t i = 0; i < loaded.scene.tubes.size(); ++i) {
        plan::BundleInput b;   // named and protected by the state compute() reports
        b.tracts = &loaded.tracts[i];
        b.probe.stepMm = loaded.scene.report.tractStepMm;
        b.probe.points = plan::tractProbePoints(loaded.tracts[i], b.probe.stepMm, b.probe.streamlineOffsets);
        bundles_.push_back(std::move(b));
    }
}

ReportInputs reportInputs(const clip::ClipMeshSet& clip, const InteractionState& state) {
    return {clip.version(), state.transferFunctionVersion, state.tubesVersion, state.removal ? state.removal->version() : 0};
}

plan::Report CarveReporter::compute(clip::ClipMeshSet& clip, const InteractionState& state) {
    if (state.tubes.size() != bundles_.size())
        throw std::logic_error("CarveReporter::compute: a state with " + std::to_string(state.tubes.size()) + " bundles for a scene with " +
                               std::to_string(bundles_.size()));
    transferFunction_ = state.transferFunction;
    for (std::size_t i = 0; i < bundles_.size(); ++i) {
        bundles_[i].name = state.tubes[i].name;
        bundles_[i].isProtected = state.tubes[i].protectedBundle;
    }
    inputs_ = reportInputs(clip, state);
    poses_ = state.sessionPoses();
    using Clock = std::chrono::steady_clock;
    auto start = Clock::now();
    // The meshes' field, then the drilled removal folded in (plan::withDrilledRemoval: the combination step IV
    // applies); the drilled region also counts as inside for the tract probes and the margins.
    field_ = probe_.removalField(clip);
    const plan::RemovalVolume* drilled = state.removal && !state.removal->empty() ? state.removal.get() : nullptr;
    if (drilled) field_ = plan::withDrilledRemoval(field_, *drilled);
    auto fieldDone = Clock::now();
    auto withDrilled = [drilled](std::vector<std::uint8_t> flags, const std::vector<glm::dvec3>& points) {
        if (drilled)
            for (std::size_t i = 0; i < points.size(); ++i) flags[i] = flags[i] || drilled->drilledAt(points[i]);
        return flags;
    };
    for (plan::BundleInput& b : bundles_) b.probe.insideFlags = withDrilled(probe_.insideFlags(clip, b.probe.points), b.probe.points);
    fieldMs_ = std::chrono::duration<double, std::milli>(fieldDone - start).count();
    flagsMs_ = std::chrono::duration<double, std::milli>(Clock::now() - fieldDone).count();
    // Margins are refined with the renderer's own clip test, as the field was made.
    plan::PointsInside inside = [this, &clip, withDrilled](const std::vector<glm::dvec3>& points) {
        return withDrilled(probe_.insideFlags(clip, points), points);
    };
    return plan::computeReport(loaded_.volume, transferFunction_, settings_, field_, labelSets_, bundles_, inside);
}

std::vector<std::uint8_t> CarveReporter::tissueInField() const {
    if (field_.insideSamples.empty()) return {};
    return plan::reportTissue(loaded_.volume, transferFunction_, settings_, labelSets_, field_.box());
}

std::vector<std::uint8_t> CarveReporter::removedRegion() const {
    if (field_.gridDims == glm::ivec3(0)) return {};
    return plan::removedRegionOnGrid(field_, tissueInField());   // the field's grid is the scan's
}

plan::ReportProvenance CarveReporter::provenance(const InteractionState& state) const {
    plan::ReportProvenance p;
    p.createdUtc = currentTimeIso8601();
    p.curetteVersion = programVersion_;
    p.files = inputFiles_;
    std::size_t bundle = 0;
    for (plan::InputFileDigest& f : p.files)
        if (f.role == "tracts") f.name = state.tubes[bundle++].name;
    p.transferFunctionJson = io::writeTransferFunctionJson(transferFunction_);
    for (const MeshState& m : state.meshes) p.meshes.push_back({m.name, m.pose.position, m.pose.orientation, rotationDegrees(m.pose.orientation), m.scale});
    return p;
}

void CarveReporter::write(const fs::path& dir, const plan::Report& report, const InteractionState& state,
                          const PlanExportOptions& options) const {
    if (state.transferFunctionVersion != inputs_.transferFunction || state.tubesVersion != inputs_.tubes || !samePoses(state.sessionPoses(), poses_))
        throw std::logic_error("CarveReporter::write: the state is not the one the report was computed under");
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw SystemError(dir.string() + ": cannot create the output directory (" + ec.message() + ")");
    plan::writeReportFiles(report, provenance(state), dir);
    if (!options.exports) return;
    std::vector<std::uint8_t> tissue = tissueInField();
    // The removed region R on the scan grid, 1 where removed (plan/removal_report.h).
    LabelMap removed;
    removed.dims = loaded_.volume.dims;
    removed.indexToWorld = loaded_.volume.indexToWorld;
    removed.source = loaded_.volume.source + " (removed region)";
    std::vector<std::uint8_t> region = plan::removedRegionOnGrid(field_, tissue);  // the field's grid is the scan's
    removed.ids.assign(region.begin(), region.end());
    io::writeNiftiLabelmap(dir / "removed.nii.gz", removed);
    io::writeSlicerSegmentation(dir / "removed.seg.nrrd", removed, {io::SegmentInfo{1, "removed", "removed by the carve", glm::dvec3(0.85, 0.2, 0.15)}});
    clip::TriangleMesh cavity = plan::cavitySurface(field_, tissue);
    if (!cavity.triangles.empty()) {
        io::writeStl(dir / "cavity.stl", cavity, options.meshSpace);
        io::writeGltf(dir / "cavity.gltf", cavity, options.meshSpace);
    }
    std::vector<std::uint8_t> sceneBytes = readFileBytes(loaded_.scene.file);
    saveScene(dir / "plan-scene.json", loaded_.scene, std::string(sceneBytes.begin(), sceneBytes.end()), state);
    if (!report.bundles.empty()) {
        fs::create_directories(dir / "tracts", ec);
        if (ec) throw SystemError((dir / "tracts").string() + ": cannot create the directory (" + ec.message() + ")");
        for (const plan::BundleRow& b : report.bundles) {
            io::writeTck(dir / "tracts" / (fileName(b.name) + "-cut.tck"), b.cutTracts);
            io::writeTck(dir / "tracts" / (fileName(b.name) + "-spared.tck"), b.sparedTracts);
        }
    }
}

std::string carveSummary(const plan::Report& report) { return plan::reportSummary(report); }

}  // namespace curette
