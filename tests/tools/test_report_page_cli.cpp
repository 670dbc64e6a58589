// `curette report --html --pdf`: report.html is one self-contained page (every image a data URI, nothing
// fetched), and headless Chromium, which no one here wrote, opens it: a screenshot is taken, the console stays
// silent (the page has no script, so any line is an error), every image decodes, and --pdf prints a PDF.
// The Chromium checks skip, saying so, only when chromium is not installed (scripts/setup installs it).
#include "tests/tools/run_curette.h"
#include "tests/tools/tool_test_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>

namespace curette {
namespace {

namespace fs = std::filesystem;
using testing::Invocation;

Invocation shell(const std::string& command) {
    FILE* pipe = popen((command + " 2>&1").c_str(), "r");
    std::string output;
    char buffer[4096];
    while (std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) output.append(buffer, n);
    int status = pclose(pipe);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

std::size_t count(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

const std::string kChromium = "chromium --headless --no-sandbox --disable-gpu ";

struct Page {
    fs::path dir;
    Invocation report;
    std::string html;
};

// The noisy ball with a 9 mm sphere carved into its side.
const Page& page() {
    static Page p = [] {
        Page made;
        made.dir = testing::freshScratchFolder("curette-report-page", "ball");
        fs::path scene = testing::writeNoisyBallScene(made.dir, nlohmann::json::parse(R"({"shading": "phong", "clip_meshes": [
            {"name": "ball", "mesh": {"shape": "sphere", "radius_mm": 9}, "position_mm": [44, 30, 33]}]})"));
        made.report = testing::runCurette("report --html --pdf --scene " + scene.string() + " --out " + (made.dir / "plan").string());
        made.html = testing::readTextFile(made.dir / "plan" / "report.html");
        return made;
    }();
    return p;
}

TEST(ReportPageCli, OneSelfContainedFileWithTheReportsFigures) {
    const Page& p = page();
    ASSERT_EQ(p.report.exitCode, 0) << p.report.output;
    EXPECT_NE(p.report.output.find("page: report.html"), std::string::npos) << p.report.output;
    ASSERT_FALSE(p.html.empty());
    EXPECT_EQ(count(p.html, "<img "), 7u) << "four 3-D views and three slices";
    EXPECT_EQ(count(p.html, "src=\"data:image/png;base64,"), 7u);
    EXPECT_EQ(count(p.html, "src=\""), 7u) << "nothing but the data URIs is loaded";
    for (const char* outside : {"http:", "https:", "file:", "<link", "<script"}) EXPECT_EQ(p.html.find(outside), std::string::npos) << outside;
    nlohmann::json json = nlohmann::json::parse(testing::readTextFile(p.dir / "plan" / "report.json"));
    char removed[32];
    std::snprintf(removed, sizeof removed, "%.2f &plusmn;", json.at("removed_ml").get<double>());
    EXPECT_NE(p.html.find(removed), std::string::npos) << "the summary's removed mL, " << removed;
}

TEST(ReportPageCli, HeadlessChromiumShowsItWithoutErrorsAndPrintsIt) {
    if (shell("command -v chromium").exitCode != 0) GTEST_SKIP() << "chromium (Debian package chromium) is not installed";
    const Page& p = page();
    ASSERT_EQ(p.report.exitCode, 0) << p.report.output;
    const fs::path html = p.dir / "plan" / "report.html";

    // The screenshot, with Chromium's console on stderr: the page has no script, so any console line is an error.
    fs::path shot = p.dir / "screenshot.png";
    Invocation screenshot = shell(kChromium + "--enable-logging=stderr --v=0 --hide-scrollbars --window-size=900,1600 --screenshot='" +
                                  shot.string() + "' 'file://" + html.string() + "'");
    ASSERT_EQ(screenshot.exitCode, 0) << screenshot.output;
    EXPECT_EQ(screenshot.output.find(":CONSOLE"), std::string::npos) << screenshot.output;
    testing::Png png = testing::readPng(shot);
    EXPECT_EQ(png.width, 900);
    EXPECT_EQ(png.height, 1600);

    // Every image decoded: a copy of the page with a check that runs after load, read back from the DOM.
    std::string checked = p.html;
    checked.insert(checked.rfind("</body>"),
                   "<script>window.addEventListener('load', () => { const images = [...document.images]; document.body.setAttribute("
                   "'data-images', images.length + ' ' + images.filter(i => i.complete && i.naturalWidth > 0).length); });</script>");
    std::ofstream(p.dir / "checked.html") << checked;
    Invocation dom = shell(kChromium + "--virtual-time-budget=5000 --dump-dom 'file://" + (p.dir / "checked.html").string() + "'");
    ASSERT_EQ(dom.exitCode, 0) << dom.output;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(dom.output, m, std::regex("data-images=\"(\\d+) (\\d+)\""))) << dom.output.substr(0, 2000);
    EXPECT_EQ(m[1], "7");
    EXPECT_EQ(m[2], "7") << "images that loaded";

    // --pdf: printed by Chromium.
    EXPECT_NE(p.report.output.find("report.pdf (headless Chromium)"), std::string::npos) << p.report.output;
    std::string pdf = testing::readTextFile(p.dir / "plan" / "report.pdf");
    EXPECT_EQ(pdf.substr(0, 5), "%PDF-");
    EXPECT_FALSE(fs::exists(p.dir / "plan" / "report.pdf.partial"));
}

TEST(ReportPageCli, PdfNeedsTheHtmlPage) {
    const Page& p = page();
    Invocation r = testing::runCurette("report --pdf --scene " + (p.dir / "scene.json").string() + " --out " + (p.dir / "other").string());
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("--pdf"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace curette
