// curette report --scene S [--session F --frame N] --out DIR: what the carve removes, per structure and per
// tract bundle, with margins to what must be spared, and the plan's exports (session/carve_report.h lists the
// files). The summary goes to the terminal; report.json is the machine-readable form.
#include "session/carve_report.h"
#include "session/dicom_plan_export.h"
#include "session/live_input.h"
#include "session/report_figures.h"
#include "tools/page_pdf.h"
#include "base/atomic_file.h"
#include "plan/report_page.h"
#include "tools/command_line.h"
#include "tools/commands/commands.h"
#include "session/loaded_scene.h"
#include "session/removal_file.h"
#include "session/session.h"
#include "session/session_step.h"
#include "base/error.h"

#include <cstdio>

namespace curette::commands {

namespace {

// The removed mL at up to 12 frames spread over a session up to `last` (the page's chart), each from the state
// at that frame as `report --session F --frame N` computes it.
std::vector<plan::ReportPage::RemovalSample> removalOverTime(const Session& session, const std::string& file, const LoadedScene& loaded,
                                                             const std::filesystem::path& scenePath, Renderer& renderer,
                                                             const VolumeGeometry& geometry, int last) {
    SessionStep step(InteractionState::fromSessionStart(session.header, loaded.scene, scenePath.parent_path(), file),
                     initialFrame(loaded.scene, geometry));
    step.attachRemoval(loaded.volume.dims, loaded.volume.indexToWorld, sessionStartRemoval(session, loaded).get());
    CarveReporter reporter(loaded, geometry, programVersion());
    const int samples = std::min(12, last + 1);
    std::vector<plan::ReportPage::RemovalSample> out;
    int next = 0;
    for (int n = 0; n <= last; ++n) {
        step.follow(session.frames[std::size_t(n)], scenePath.parent_path(), file + " line " + std::to_string(n + 2));
        if (n != (last * next) / std::max(samples - 1, 1)) continue;
        ++next;
        step.syncTo(renderer, loaded.tracts);
        out.push_back({session.frames[std::size_t(n)].time, reporter.compute(renderer.clipMeshes(), step.state()).removedMl});
    }
    return out;
}

int report(const CommandLine& cl) {
    if (!cl.positional().empty()) throw InputError("<command line>", cl.positional()[0], "no positional arguments for report");
    std::filesystem::path out = cl.required("out");
    if (cl.value("frame") && !cl.value("session")) throw InputError("<command line>", "--frame", "together with --session");
    if (cl.flag("anonymize") && !cl.flag("dicom")) throw InputError("<command line>", "--anonymize", "together with --dicom");
    if (cl.flag("dicom") && cl.flag("no-exports")) throw InputError("<command line>", "--dicom", "without --no-exports");
    if (cl.flag("pdf") && !cl.flag("html")) throw InputError("<command line>", "--pdf", "together with --html");
    std::optional<Session> session;
    std::filesystem::path scenePath;
    if (auto s = cl.value("session")) {
        session = readSession(*s, false);
        scenePath = session->header.scene;
        if (scenePath.is_relative()) scenePath = std::filesystem::path(*s).parent_path() / scenePath;
    }
    if (auto s = cl.value("scene")) scenePath = *s;
    if (scenePath.empty()) throw InputError("<command line>", "--scene", "a scene file (or --session)");

    LoadedScene loaded = loadSceneWithVolume(scenePath);
    auto context = gl::createHeadlessContext(gpuChoice(cl));
    Renderer renderer(*context, loaded.volume, loaded.scene.transferFunction);
    configureRenderer(loaded, renderer);
    VolumeGeometry geometry{loaded.volume.dims, loaded.volume.indexToWorld};
    std::optional<SessionStep> step;
    int reportedFrame = -1;
    std::string where = scenePath.string();
    if (session) {
        if (session->frames.empty()) throw InputError(*cl.value("session"), "frames", "at least one recorded frame", "none");
        int last = static_cast<int>(session->frames.size()) - 1;
        int frame = cl.value("frame") ? CommandLine::parseInt("frame", *cl.value("frame"), 0, last) : last;
        reportedFrame = frame;
        step.emplace(InteractionState::fromSessionStart(session->header, loaded.scene, scenePath.parent_path(), *cl.value("session")),
                     initialFrame(loaded.scene, geometry));
        step->attachRemoval(loaded.volume.dims, loaded.volume.indexToWorld, sessionStartRemoval(*session, loaded).get());
        for (int n = 0; n <= frame; ++n)
            step->follow(session->frames[std::size_t(n)], scenePath.parent_path(), *cl.value("session") + " line " + std::to_string(n + 2));
        step->syncTo(renderer, loaded.tracts);   // the renderer in the state at that frame, its meshes and settings
        where = *cl.value("session") + " frame " + std::to_string(frame);
    }
    InteractionState state = step ? step->state() : InteractionState::fromScene(loaded.scene);
    if (!step && loaded.removal) state.removal = std::make_shared<plan::RemovalVolume>(*loaded.removal);   // the scene's drilling

    CarveReporter reporter(loaded, geometry, programVersion());
    plan::Report report = reporter.compute(renderer.clipMeshes(), state);
    PlanExportOptions options;
    options.meshSpace = cl.flag("lps") ? io::MeshSpace::Lps : io::MeshSpace::Ras;
    options.exports = !cl.flag("no-exports");
    reporter.write(out, report, state, options);
    std::string dicom, page;
    std::vector<std::uint8_t> removed;
    if (cl.flag("dicom") || cl.flag("html")) removed = reporter.removedRegion();
    if (cl.flag("dicom")) dicom = writePlanDicom(out, loaded, report, removed, {cl.flag("anonymize"), programVersion()});
    if (cl.flag("html")) {
        plan::ReportPage content;
        content.createdUtc = currentTimeIso8601();
        content.curetteVersion = programVersion();
        content.views = reportViews(renderer, loaded, 320);
        if (session) content.removalOverTime = removalOverTime(*session, *cl.value("session"), loaded, scenePath, renderer, geometry,
                                                               reportedFrame);
        if (session) step->syncTo(renderer, loaded.tracts);   // back to the reported frame's state
        content.slices = reportSlices(loaded, state, removed);
        if (!dicom.empty()) content.notes.push_back(dicom.substr(0, dicom.size() - 1));
        writeFileAtomically(out / "report.html", plan::reportPageHtml(report, content));
        page = "page: report.html";
        if (cl.flag("pdf"))
            page += printPageToPdf(out / "report.html", out / "report.pdf") ? " and report.pdf (headless Chromium)"
                                                                            : "; no chromium on PATH, so no report.pdf (apt-get install chromium)";
        page += "\n";
    }
    std::printf("curette report: %s\n%s%s%s", where.c_str(), carveSummary(report).c_str(), dicom.c_str(), page.c_str());
    std::printf("report in %.0f ms (GPU field and tract flags %.0f ms); wrote %s\n", report.timings.totalMs + reporter.lastGpuMs(),
                reporter.lastGpuMs(), out.c_str());
    return 0;
}

}  // namespace

Command reportCommand() {
    return {{"report", "--scene S --out DIR", "what the carve removes (mL, per structure, per tract bundle, margins) and the plan's exports: labelmap (.nii.gz, .seg.nrrd), cavity surface (STL, glTF), plan scene, cut and spared tracts (.tck)",
             withGpuOption({{"scene", true, "scene file (JSON; default with --session: the session's scene)"},
              {"session", true, "a recorded session (JSONL): report the carve at one of its frames"},
              {"frame", true, "with --session: the frame index (default: the last frame)"},
              {"out", true, "directory for report.json, the CSVs and the exports"},
              {"lps", false, "write the cavity surface in LPS (default RAS)"},
              {"no-exports", false, "only report.json and the CSVs"},
              {"dicom", false, "also seg.dcm (DICOM Segmentation) and rtstruct.dcm (RT Structure Set) on the source series (a non-DICOM scan is written as a DICOM series into scan-dicom/)"},
              {"html", false, "also report.html: one self-contained page (summary, warnings, tables, 3-D views, slices through the cavity)"},
              {"pdf", false, "with --html: also report.pdf, printed by headless Chromium when it is on PATH"},
              {"anonymize", false, "with --dicom: replace the patient and study identifiers (the scan is written again under new UIDs)"}})},
            &report};
}

}  // namespace curette::commands
