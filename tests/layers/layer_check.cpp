#include "layer_check.h"

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

namespace curette::layers {

namespace {

// Lowest first. A folder may include itself and the folders listed for it; input sits beside gl, clip and
// render and sees only base; plan (the carve as a surgical plan, CPU only) sees base and clip's CPU geometry,
// never gl or render, and render sees plan (its removal probe produces plan's removal field); tests see
// everything.
const std::map<std::string, std::set<std::string>>& allowed() {
    static const std::map<std::string, std::set<std::string>> table{
        {"base", {"base"}},
        {"gl", {"base", "gl"}},
        {"clip", {"base", "gl", "clip"}},
        {"plan", {"base", "clip", "plan"}},
        {"render", {"base", "gl", "clip", "plan", "render"}},
        {"input", {"base", "input"}},
        {"app", {"base", "gl", "clip", "plan", "render", "input", "app"}},
        {"tests", {"base", "gl", "clip", "plan", "render", "input", "app", "tests"}},
    };
    return table;
}

std::string folderOf(const std::string& path) { return path.substr(0, path.find('/')); }

std::string withoutLineComment(const std::string& line) {
    std::size_t comment = line.find("//");
    return comment == std::string::npos ? line : line.substr(0, comment);
}

}  // namespace

std::vector<Violation> checkFile(const std::string& path, const std::string& text) {
    std::vector<Violation> out;
    const std::string folder = folderOf(path);
    auto rule = allowed().find(folder);
    if (rule == allowed().end()) return {{path, 0, "folder \"" + folder + "\" is not in the layer table"}};
    static const std::regex quoted(R"re(^\s*#\s*include\s*"([^"]+)")re");
    static const std::regex angled(R"(^\s*#\s*include\s*<(epoxy/|GL/|EGL/)[^>]*>)");
    static const std::regex glCall(R"re((^|[^A-Za-z0-9_.>])gl[A-Z][A-Za-z0-9_]*\s*\()re");
    std::istringstream in(text);
    std::string line;
    int number = 0;
    bool inBlockComment = false;
    while (std::getline(in, line)) {
        ++number;
        std::smatch m;
        if (std::regex_search(line, m, quoted)) {
            std::string target = m[1];
            std::size_t slash = target.find('/');
            if (slash == std::string::npos) continue;  // a file beside this one
            std::string targetFolder = target.substr(0, slash);
            if (!allowed().count(targetFolder)) {
                out.push_back({path, number, "includes \"" + target + "\" from folder \"" + targetFolder + "\", which is not in the layer table"});
            } else if (!rule->second.count(targetFolder)) {
                out.push_back({path, number, folder + "/ may not include " + targetFolder + "/ (\"" + target + "\"): it is above " + folder +
                                                 "/ in the layer order (docs/architecture.md, Layers)"});
            }
            continue;
        }
        if (folder != "app") continue;
        if (std::regex_search(line, angled))
            out.push_back({path, number, "app/ includes a GL header; GL calls belong to gl/ and render/"});
        // Block comments: skip their lines (good enough for this tree's style of /* */-free code).
        if (line.find("/*") != std::string::npos) inBlockComment = true;
        if (inBlockComment) {
            if (line.find("*/") != std::string::npos) inBlockComment = false;
            continue;
        }
        std::string code = withoutLineComment(line);
        if (std::regex_search(code, m, glCall))
            out.push_back({path, number, "app/ calls GL directly (" + std::string(m[0]).substr(m[1].length()) +
                                             "...); GL calls belong to gl/ and render/"});
    }
    return out;
}

namespace {
template <typename F>
void forEachSource(const std::string& root, F&& f) {
    namespace fs = std::filesystem;
    for (const auto& [folder, unused] : allowed()) {
        fs::path dir = fs::path(root) / folder;
        if (!fs::is_directory(dir)) continue;
        for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir)) {
            if (!e.is_regular_file()) continue;
            std::string ext = e.path().extension().string();
            if (ext != ".h" && ext != ".cpp" && ext != ".in") continue;
            if (e.path().string().find("/fuzz/corpus/") != std::string::npos) continue;
            f(e.path(), fs::relative(e.path(), root).generic_string());
        }
    }
}
}  // namespace

std::vector<Violation> checkTree(const std::string& root) {
    std::vector<Violation> all;
    forEachSource(root, [&](const std::filesystem::path& file, const std::string& relative) {
        std::ifstream in(file);
        std::stringstream text;
        text << in.rdbuf();
        for (Violation& v : checkFile(relative, text.str())) all.push_back(std::move(v));
    });
    return all;
}

int filesChecked(const std::string& root) {
    int n = 0;
    forEachSource(root, [&](const std::filesystem::path&, const std::string&) { ++n; });
    return n;
}

}  // namespace curette::layers
