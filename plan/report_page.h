#pragma once
// The plan as one page a planner prints or attaches to a case (`curette report --html`): report.html, a
// single self-contained HTML5 file (inline CSS, no script, every image a PNG data URI, RFC 2397), laid out
// for A4 printing (`--pdf` prints it through headless Chromium). Sections:
//   summary     removed mL +- its uncertainty, touched and removed-region voxels, the voxel, the tissue rule,
//               the source (file name only), when and by which curette;
//   warnings    one line each protected structure or bundle touched (Report::warnings), or "none";
//   structures  label set, name, protected, volume, removed +- u, share, depth +- u, margin +- u ("contact");
//   bundles     name, protected, streamlines, cut, share, removed length, margin +- u;
//   3-D views   and slices: the figures given, each with its caption;
//   over time   for a session: removed mL at sampled frames, an inline SVG chart;
//   notes       free lines (what the DICOM export wrote, say).
// No patient identifier is ever handed in, so none is written.

#include "plan/removal_report.h"

#include <cstdint>
#include <string>
#include <vector>

namespace curette::plan {

struct ReportFigure {
    std::string caption;
    std::vector<std::uint8_t> png;   // a PNG file's bytes
};

struct ReportPage {
    std::string title = "curette surgical plan";
    std::string createdUtc, curetteVersion;
    std::vector<ReportFigure> views, slices;
    struct RemovalSample {
        double timeS = 0, removedMl = 0;
    };
    std::vector<RemovalSample> removalOverTime;   // a session's, in time order (empty: no chart)
    std::vector<std::string> notes;
};

std::string reportPageHtml(const Report& report, const ReportPage& page);

// Text made safe inside HTML element content and attribute values (&, <, >, ", ').
std::string htmlEscaped(const std::string& text);

}  // namespace curette::plan
