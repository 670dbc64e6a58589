// The layers of docs/architecture.md, checked on the source tree: every `#include "folder/..."` names a layer
// at or below its own, GL-free layers include no GL header and call no GL function, and only gl/ and render/
// call GL. The checker is tested on made-up files first, so a broken checker cannot pass the tree by finding
// nothing.
#include "layer_check.h"

#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>

namespace curette::layers {
namespace {

TEST(Layers, CheckerFlagsAnUpwardInclude) {
    std::vector<Violation> v = checkFile("mesh/example.cpp", "#include \"mesh/rigid_pose.h\"\n#include \"render/renderer.h\"\n");
    ASSERT_EQ(v.size(), 1u);
    EXPECT_EQ(v[0].line, 2);
    EXPECT_NE(v[0].message.find("render"), std::string::npos) << v[0].message;
    // A subfolder layer is its own: render/model may not reach up into the GL part of render/.
    EXPECT_EQ(checkFile("render/model/x.h", "#include \"render/passes/tube_set.h\"\n").size(), 1u);
    EXPECT_EQ(checkFile("scene/x.h", "#include \"session/session.h\"\n").size(), 1u);
    EXPECT_EQ(checkFile("session/x.h", "#include \"viewer/view_panels.h\"\n").size(), 1u);
}

TEST(Layers, CheckerAllowsIncludesFromLowerLayers) {
    EXPECT_TRUE(checkFile("render/x.cpp", "#include \"base/error.h\"\n#include \"gl/program.h\"\n#include \"render/passes/clip_mesh_set.h\"\n"
                                          "#include \"render/model/frame.h\"\n#include <glm/glm.hpp>\n").empty());
    EXPECT_TRUE(checkFile("tools/x.cpp", "#include \"render/renderer.h\"\n#include \"input/actions.h\"\n").empty());
    EXPECT_TRUE(checkFile("scene/x.cpp", "#include \"render/model/frame.h\"\n#include \"io/volume_file.h\"\n").empty());
}

TEST(Layers, InputSeesOnlyBase) {
    EXPECT_EQ(checkFile("input/x.cpp", "#include \"gl/context.h\"\n").size(), 1u);
    EXPECT_EQ(checkFile("render/x.cpp", "#include \"input/actions.h\"\n").size(), 1u);
    EXPECT_TRUE(checkFile("input/x.cpp", "#include \"base/error.h\"\n").empty());
}

TEST(Layers, CheckerFlagsGlInGlFreeFolders) {
    for (const char* folder : {"base", "mesh", "io", "plan", "render/model", "render/reference", "scene"}) {
        std::string path = std::string(folder) + "/x.cpp";
        EXPECT_EQ(checkFile(path, "#include <epoxy/gl.h>\n").size(), 1u) << path;
        EXPECT_EQ(checkFile(path, "void f() { glFinish(); }\n").size(), 1u) << path;
        EXPECT_EQ(checkFile(path, "#include \"gl/program.h\"\n").size(), 1u) << path;
        EXPECT_EQ(checkFile(path, "#include <GLFW/glfw3.h>\n").size(), 1u) << path;
    }
}

TEST(Layers, CheckerFlagsGlCallsAboveRender) {
    std::vector<Violation> v = checkFile("tools/commands/x.cpp", "void f() {\n    glFinish();\n}\n// glFinish() in a comment is fine\n");
    ASSERT_EQ(v.size(), 1u);
    EXPECT_EQ(v[0].line, 2);
    EXPECT_TRUE(checkFile("render/x.cpp", "void f() { glFinish(); }\n").empty());
    EXPECT_TRUE(checkFile("render/passes/x.cpp", "void f() { glFinish(); }\n").empty());
    EXPECT_EQ(checkFile("viewer/x.cpp", "#include <epoxy/gl.h>\n").size(), 1u);
    EXPECT_TRUE(checkFile("tools/commands/x.cpp", "#include <GLFW/glfw3.h>\n").empty()) << "the window's keys and events";
    EXPECT_EQ(checkFile("session/x.cpp", "void f() { glFinish(); }\n").size(), 1u);
}

TEST(Layers, UnknownFolderInAnIncludeIsAViolation) {
    // A folder the table does not know cannot be placed in the order: say so instead of passing it.
    EXPECT_EQ(checkFile("render/x.cpp", "#include \"misc/thing.h\"\n").size(), 1u);
    EXPECT_EQ(checkFile("misc/x.cpp", "").size(), 1u);
}

TEST(Layers, SubfolderLayersWinOverTheirParent) {
    EXPECT_EQ(layerOf("render/model/frame.h"), "render/model");
    EXPECT_EQ(layerOf("render/passes/tube_set.h"), "render");
    EXPECT_EQ(layerOf("render/renderer.h"), "render");
    EXPECT_EQ(layerOf("renderer/x.h"), "");
}

TEST(Layers, SourceTreeRespectsTheLayers) {
    std::vector<Violation> all = checkTree(CURETTE_SOURCE_DIR);
    std::string report;
    for (const Violation& v : all) report += v.file + ":" + std::to_string(v.line) + ": " + v.message + "\n";
    EXPECT_TRUE(all.empty()) << report;
    EXPECT_GT(filesChecked(CURETTE_SOURCE_DIR), 200) << "the checker found too few source files to be looking at the tree";
}

TEST(Layers, EveryFolderWithSourcesIsALayer) {
    std::vector<std::string> outside = foldersOutsideTheTable(CURETTE_SOURCE_DIR);
    std::string list;
    for (const std::string& f : outside) list += f + " ";
    EXPECT_TRUE(outside.empty()) << "folders with C++ sources outside the layer table: " << list;
}

// The architecture page's layer table is this one: the same folders in the same order.
TEST(Layers, TheArchitecturePageListsTheLayerTable) {
    std::ifstream in(std::string(CURETTE_SOURCE_DIR) + "/docs/architecture.md");
    ASSERT_TRUE(in) << "docs/architecture.md";
    std::stringstream text;
    text << in.rdbuf();
    std::string page = text.str();
    std::size_t start = page.find("## Layers");
    ASSERT_NE(start, std::string::npos);
    std::size_t end = page.find("\n## ", start + 1);
    std::istringstream section(page.substr(start, end - start));
    static const std::regex row(R"(^\| `([a-z/]+)/` \|)");
    std::vector<std::string> documented;
    std::string line;
    while (std::getline(section, line)) {
        std::smatch m;
        if (std::regex_search(line, m, row)) documented.push_back(m[1]);
    }
    std::vector<std::string> table;
    for (const Layer& l : layerTable()) table.push_back(l.folder);
    EXPECT_EQ(documented, table);
}

}  // namespace
}  // namespace curette::layers
