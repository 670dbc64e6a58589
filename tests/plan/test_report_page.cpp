// plan/report_page.h: the page's text is escaped, its tables hold the report's rows with their
// uncertainties, and a protected structure the carve touches is a warning.
#include "plan/report_page.h"

#include <gtest/gtest.h>

#include <algorithm>

#include <limits>

namespace curette::plan {
namespace {

TEST(ReportPage, TextIsEscaped) {
    EXPECT_EQ(htmlEscaped("a<b>&\"c'"), "a&lt;b&gt;&amp;&quot;c&#39;");
}

// A session's removed mL over time: a chart whose polyline has one point per sample, from the first time to
// the last, and no chart for fewer than two samples.
TEST(ReportPage, ASessionChartsItsRemovalOverTime) {
    Report r;
    ReportPage page;
    EXPECT_EQ(reportPageHtml(r, page).find("<svg"), std::string::npos);
    page.removalOverTime = {{0.0, 0.0}, {0.5, 0.2}, {1.0, 0.7}, {1.5, 0.65}};
    std::string html = reportPageHtml(r, page);
    ASSERT_NE(html.find("Removed over the session"), std::string::npos);
    std::size_t at = html.find("points=\"");
    ASSERT_NE(at, std::string::npos);
    std::string points = html.substr(at + 8, html.find('"', at + 8) - at - 8);
    EXPECT_EQ(std::count(points.begin(), points.end(), ','), 4);
    EXPECT_NE(points.find("50.0,190.0"), std::string::npos) << "the first sample at the origin: " << points;
    EXPECT_NE(points.find("403.3,20.0"), std::string::npos) << "the largest at the top: " << points;
    EXPECT_NE(points.find("580.0,32.1"), std::string::npos) << "the last at the right: " << points;
    EXPECT_NE(html.find("0.70 mL"), std::string::npos);
}

TEST(ReportPage, TablesCarryTheRowsAndTheWarnings) {
    Report r;
    r.volumeSource = "/data/scans/head.nii.gz";
    r.removedMl = 3.14159;
    r.removedUncertaintyMl = 0.02;
    StructureRow s;
    s.labelSet = "aal";
    s.name = "Precentral_L <motor>";
    s.isProtected = true;
    s.touched = true;
    s.touchedVoxels = 5;
    s.removedMl = 0.25;
    s.removedUncertaintyMl = 0.004;
    s.intrusionDepthMm = 2.5;
    s.intrusionUncertaintyMm = 1.7;
    r.structures.push_back(s);
    BundleRow b;
    b.name = "arcuate";
    b.streamlines = 10;
    b.marginMm = std::numeric_limits<double>::infinity();
    r.bundles.push_back(b);
    ReportPage page;
    page.views.push_back({"a view", {0x89, 'P', 'N', 'G'}});
    std::string html = reportPageHtml(r, page);
    EXPECT_NE(html.find("3.14 &plusmn; 0.02 mL"), std::string::npos);
    EXPECT_NE(html.find("Precentral_L &lt;motor&gt;"), std::string::npos);
    EXPECT_EQ(html.find("<motor>"), std::string::npos);
    EXPECT_NE(html.find("0.250 &plusmn; 0.004"), std::string::npos);
    EXPECT_NE(html.find("2.5 &plusmn; 1.7"), std::string::npos);
    EXPECT_NE(html.find("contact"), std::string::npos);
    EXPECT_NE(html.find("<td class=\"n\">&ndash;</td></tr>"), std::string::npos) << "an infinite margin";
    EXPECT_NE(html.find("class=\"warning\""), std::string::npos);
    EXPECT_NE(html.find("src=\"data:image/png;base64,iVBORw==\""), std::string::npos);
    EXPECT_NE(html.find("<td>head.nii.gz</td>"), std::string::npos);
    EXPECT_EQ(html.find("/data/scans"), std::string::npos) << "the file name only";
}

}  // namespace
}  // namespace curette::plan
