#include "plan/report_page.h"

#include "plan/tissue_mask.h"
#include "base/base64.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace curette::plan {

namespace {

std::string number(double value, int decimals) {
    if (!std::isfinite(value)) return "&ndash;";
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", decimals, value);
    return text;
}

std::string withUncertainty(double value, double uncertainty, int decimals) {
    if (!std::isfinite(value)) return "&ndash;";
    return number(value, decimals) + " &plusmn; " + number(uncertainty, decimals);
}

std::string cell(const std::string& html, bool numeric = false) { return numeric ? "<td class=\"n\">" + html + "</td>" : "<td>" + html + "</td>"; }

std::string figures(const std::string& heading, const std::vector<ReportFigure>& list) {
    if (list.empty()) return {};
    std::string out = "<h2>" + htmlEscaped(heading) + "</h2>\n<div class=\"figures\">\n";
    for (const ReportFigure& f : list)
        out += "<figure><img alt=\"" + htmlEscaped(f.caption) + "\" src=\"data:image/png;base64," + base64(f.png) + "\"><figcaption>" +
               htmlEscaped(f.caption) + "</figcaption></figure>\n";
    return out + "</div>\n";
}

}  // namespace

std::string htmlEscaped(const std::string& text) {
    std::string out;
    for (char c : text) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&#39;"; break;
            default: out += c;
        }
    }
    return out;
}

std::string reportPageHtml(const Report& r, const ReportPage& page) {
    std::string h;
    h += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" + htmlEscaped(page.title) + "</title>\n";
    h += "<style>\n"
         "@page { size: A4; margin: 14mm; }\n"
         "body { font-family: sans-serif; font-size: 10pt; color: #111; max-width: 190mm; margin: auto; }\n"
         "h1 { font-size: 16pt; margin-bottom: 2mm; } h2 { font-size: 12pt; margin-top: 6mm; border-bottom: 1px solid #999; }\n"
         "table { border-collapse: collapse; width: 100%; } th, td { padding: 1mm 2mm; border-bottom: 1px solid #ddd; text-align: left; }\n"
         "td.n, th.n { text-align: right; font-variant-numeric: tabular-nums; }\n"
         ".warning { color: #a00; font-weight: bold; } .protected { color: #a00; }\n"
         ".figures { display: flex; flex-wrap: wrap; gap: 3mm; } figure { margin: 0; width: 44mm; break-inside: avoid; }\n"
         "figure img { width: 100%; image-rendering: auto; } figcaption { font-size: 8pt; color: #444; }\n"
         "</style>\n</head>\n<body>\n";
    h += "<h1>" + htmlEscaped(page.title) + "</h1>\n";

    h += "<h2>Summary</h2>\n<table>\n";
    auto summaryRow = [&](const std::string& name, const std::string& html) { h += "<tr><th>" + htmlEscaped(name) + "</th><td>" + html + "</td></tr>\n"; };
    summaryRow("removed tissue", withUncertainty(r.removedMl, r.removedUncertaintyMl, 2) + " mL");
    summaryRow("voxels", std::to_string(r.touchedVoxels) + " touched, " + std::to_string(r.removedRegionVoxels) + " in the removed region");
    summaryRow("voxel", number(r.spacingMm.x, 3) + " &times; " + number(r.spacingMm.y, 3) + " &times; " + number(r.spacingMm.z, 3) + " mm");
    summaryRow("tissue rule", htmlEscaped(tissueRuleName(r.tissue)));
    summaryRow("scan", htmlEscaped(std::filesystem::path(r.volumeSource).filename().string()));
    summaryRow("made", htmlEscaped(page.createdUtc) + " by " + htmlEscaped(page.curetteVersion));
    h += "</table>\n";

    h += "<h2>Warnings</h2>\n";
    std::vector<std::string> warnings = r.warnings();
    if (warnings.empty()) h += "<p>none: no protected structure or bundle is touched</p>\n";
    for (const std::string& w : warnings) h += "<p class=\"warning\">" + htmlEscaped(w) + "</p>\n";

    if (!r.structures.empty()) {
        h += "<h2>Structures</h2>\n<table>\n<tr><th>label set</th><th>structure</th><th class=\"n\">volume mL</th><th class=\"n\">removed mL</th>"
             "<th class=\"n\">share</th><th class=\"n\">depth mm</th><th class=\"n\">margin mm</th></tr>\n";
        for (const StructureRow& s : r.structures) {
            std::string name = htmlEscaped(s.name) + (s.isProtected ? " <span class=\"protected\">(protected)</span>" : "");
            h += "<tr>" + cell(htmlEscaped(s.labelSet)) + cell(name) + cell(number(s.volumeMl, 2), true) +
                 cell(withUncertainty(s.removedMl, s.removedUncertaintyMl, 3), true) + cell(number(100.0 * s.share, 1) + " %", true) +
                 cell(withUncertainty(s.intrusionDepthMm, s.intrusionUncertaintyMm, 1), true) +
                 cell(s.touched ? "contact" : withUncertainty(s.marginMm, s.marginUncertaintyMm, s.marginUncertaintyMm < 0.1 ? 2 : 1), true) + "</tr>\n";
        }
        h += "</table>\n";
    }
    if (!r.bundles.empty()) {
        h += "<h2>Tract bundles</h2>\n<table>\n<tr><th>bundle</th><th class=\"n\">streamlines</th><th class=\"n\">cut</th><th class=\"n\">share</th>"
             "<th class=\"n\">removed length mm</th><th class=\"n\">margin mm</th></tr>\n";
        for (const BundleRow& b : r.bundles) {
            std::string name = htmlEscaped(b.name) + (b.isProtected ? " <span class=\"protected\">(protected)</span>" : "");
            h += "<tr>" + cell(name) + cell(std::to_string(b.streamlines), true) + cell(std::to_string(b.cut), true) +
                 cell(number(100.0 * b.share, 1) + " %", true) + cell(number(b.removedLengthMm, 1), true) +
                 cell(withUncertainty(b.marginMm, b.marginUncertaintyMm, 1), true) + "</tr>\n";
        }
        h += "</table>\n";
    }
    h += figures("3-D views", page.views);
    h += figures("Slices through the cavity", page.slices);
    if (page.removalOverTime.size() >= 2) {
        // Removed mL over the session's time: a polyline in a 600 x 220 box, axes labelled at their ends.
        double t0 = page.removalOverTime.front().timeS, t1 = page.removalOverTime.back().timeS, top = 0;
        for (const ReportPage::RemovalSample& s : page.removalOverTime) top = std::max(top, s.removedMl);
        if (t1 <= t0) t1 = t0 + 1;
        if (top <= 0) top = 1;
        const double x0 = 50, y0 = 190, w = 530, hgt = 170;
        std::string points;
        for (const ReportPage::RemovalSample& s : page.removalOverTime)
            points += number(x0 + w * (s.timeS - t0) / (t1 - t0), 1) + "," + number(y0 - hgt * s.removedMl / top, 1) + " ";
        h += "<h2>Removed over the session</h2>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"600\" height=\"220\" "
             "role=\"img\" aria-label=\"removed mL over the session\">\n";
        h += "<line x1=\"50\" y1=\"190\" x2=\"580\" y2=\"190\" stroke=\"#444\"/><line x1=\"50\" y1=\"20\" x2=\"50\" y2=\"190\" stroke=\"#444\"/>\n";
        h += "<polyline fill=\"none\" stroke=\"#b03030\" stroke-width=\"2\" points=\"" + points + "\"/>\n";
        h += "<text x=\"45\" y=\"25\" text-anchor=\"end\" font-size=\"11\">" + number(top, 2) + " mL</text>";
        h += "<text x=\"45\" y=\"190\" text-anchor=\"end\" font-size=\"11\">0</text>";
        h += "<text x=\"50\" y=\"208\" font-size=\"11\">" + number(t0, 1) + " s</text>";
        h += "<text x=\"580\" y=\"208\" text-anchor=\"end\" font-size=\"11\">" + number(t1, 1) + " s</text>\n</svg>\n";
        h += "<p>" + std::to_string(page.removalOverTime.size()) + " frames sampled; the last: " + number(page.removalOverTime.back().removedMl, 3) +
             " mL.</p>\n";
    }
    if (!page.notes.empty()) {
        h += "<h2>Notes</h2>\n";
        for (const std::string& n : page.notes) h += "<p>" + htmlEscaped(n) + "</p>\n";
    }
    return h + "</body>\n</html>\n";
}

}  // namespace curette::plan
