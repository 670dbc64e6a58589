#include "layer_check.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

namespace curette::layers {

const std::vector<Layer>& layerTable() {
    // Each layer lists what it may include, besides itself. GL-free layers are linked without GL as well.
    static const std::vector<Layer> table{
        {"base", {}, true, false},
        {"mesh", {"base"}, true, false},
        {"io", {"base", "mesh"}, true, false},
        {"gl", {"base"}, false, true},
        {"plan", {"base", "mesh"}, true, false},
        {"render/model", {"base", "mesh", "plan"}, true, false},
        {"render/reference", {"base", "mesh", "plan", "render/model"}, true, false},
        {"render", {"base", "mesh", "gl", "plan", "render/model"}, false, true},
        {"xr", {"base", "mesh", "gl", "plan", "render/model", "render"}, false, true},
        {"input", {"base"}, true, false},
        {"scene", {"base", "mesh", "io", "plan", "render/model"}, true, false},
        {"session", {"base", "mesh", "io", "gl", "plan", "render/model", "render", "input", "scene"}, false, false},
        {"viewer", {"base", "mesh", "io", "gl", "plan", "render/model", "render", "input", "scene", "session"}, false, false},
        {"tools",
         {"base", "mesh", "io", "gl", "plan", "render/model", "render/reference", "render", "xr", "input", "scene", "session", "viewer"},
         false, false},
        {"tests",
         {"base", "mesh", "io", "gl", "plan", "render/model", "render/reference", "render", "xr", "input", "scene", "session", "viewer",
          "tools"},
         false, true},
    };
    return table;
}

namespace {

const Layer* find(const std::string& folder) {
    for (const Layer& l : layerTable())
        if (l.folder == folder) return &l;
    return nullptr;
}

std::string withoutLineComment(const std::string& line) {
    std::size_t comment = line.find("//");
    return comment == std::string::npos ? line : line.substr(0, comment);
}

}  // namespace

std::string layerOf(const std::string& path) {
    std::string best;
    for (const Layer& l : layerTable())
        if (path.size() > l.folder.size() && path.compare(0, l.folder.size(), l.folder) == 0 && path[l.folder.size()] == '/' &&
            l.folder.size() > best.size())
            best = l.folder;
    return best;
}

std::vector<Violation> checkFile(const std::string& path, const std::string& text) {
    std::vector<Violation> out;
    const Layer* rule = find(layerOf(path));
    if (!rule) return {{path, 0, "\"" + path + "\" lies in no folder of the layer table"}};
    static const std::regex quoted(R"re(^\s*#\s*include\s*"([^"]+)")re");
    static const std::regex angled(R"(^\s*#\s*include\s*<(epoxy/|GL/|EGL/)[^>]*>)");
    static const std::regex window(R"(^\s*#\s*include\s*<GLFW/[^>]*>)");   // a window: GL-free layers have none
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
            if (target.find('/') == std::string::npos) continue;  // a file beside this one
            std::string targetLayer = layerOf(target);
            if (targetLayer.empty()) {
                out.push_back({path, number, "includes \"" + target + "\", which lies in no folder of the layer table"});
            } else if (targetLayer != rule->folder &&
                       std::find(rule->includes.begin(), rule->includes.end(), targetLayer) == rule->includes.end()) {
                out.push_back({path, number, rule->folder + "/ may not include " + targetLayer + "/ (\"" + target +
                                                 "\"): it is not below " + rule->folder + "/ in the layer order (docs/architecture.md, Layers)"});
            }
            continue;
        }
        if (rule->glCalls) continue;
        if (std::regex_search(line, angled) || (rule->glFree && std::regex_search(line, window)))
            out.push_back({path, number, rule->folder + "/ includes a GL or window header; GL calls belong to gl/ and render/"});
        // Block comments: skip their lines (good enough for this tree's style of /* */-free code).
        if (line.find("/*") != std::string::npos) inBlockComment = true;
        if (inBlockComment) {
            if (line.find("*/") != std::string::npos) inBlockComment = false;
            continue;
        }
        std::string code = withoutLineComment(line);
        if (std::regex_search(code, m, glCall))
            out.push_back({path, number, rule->folder + "/ calls GL directly (" + std::string(m[0]).substr(m[1].length()) +
                                             "...); GL calls belong to gl/ and render/"});
    }
    return out;
}

namespace {

bool isSource(const std::filesystem::path& p) {
    std::string ext = p.extension().string();
    return ext == ".h" || ext == ".cpp" || ext == ".in";
}

template <typename F>
void forEachSource(const std::string& root, F&& f) {
    namespace fs = std::filesystem;
    std::set<std::string> tops;
    for (const Layer& l : layerTable()) tops.insert(l.folder.substr(0, l.folder.find('/')));
    for (const std::string& top : tops) {
        fs::path dir = fs::path(root) / top;
        if (!fs::is_directory(dir)) continue;
        for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir)) {
            if (!e.is_regular_file() || !isSource(e.path())) continue;
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

std::vector<std::string> foldersOutsideTheTable(const std::string& root) {
    namespace fs = std::filesystem;
    std::set<std::string> outside;
    for (const fs::directory_entry& top : fs::directory_iterator(root)) {
        std::string name = top.path().filename().string();
        if (!top.is_directory() || name.starts_with(".") || name.starts_with("build")) continue;
        for (const fs::directory_entry& e : fs::recursive_directory_iterator(top.path())) {
            if (!e.is_regular_file() || !isSource(e.path())) continue;
            std::string relative = fs::relative(e.path(), root).generic_string();
            if (layerOf(relative).empty()) outside.insert(fs::relative(e.path().parent_path(), root).generic_string());
        }
    }
    return {outside.begin(), outside.end()};
}

}  // namespace curette::layers
