// The layers of DESIGN.md / docs/architecture.md, checked on the source tree: every `#include "folder/..."`
// in a folder names a folder at or below it in the dependency order, and app/ issues no GL call of its own.
// The checker is tested on made-up files first, so a broken checker cannot pass the tree by finding nothing.
#include "layer_check.h"

#include <gtest/gtest.h>

namespace curette::layers {
namespace {

TEST(Layers, CheckerFlagsAnUpwardInclude) {
    std::vector<Violation> v = checkFile("clip/example.cpp", "#include \"clip/rigid_pose.h\"\n#include \"render/renderer.h\"\n");
    ASSERT_EQ(v.size(), 1u);
    EXPECT_EQ(v[0].line, 2);
    EXPECT_NE(v[0].message.find("render"), std::string::npos) << v[0].message;
}

TEST(Layers, CheckerAllowsIncludesFromLowerLayers) {
    EXPECT_TRUE(checkFile("render/x.cpp", "#include \"base/error.h\"\n#include \"gl/program.h\"\n#include \"clip/clip_mesh_set.h\"\n"
                                          "#include \"render/frame.h\"\n#include <glm/glm.hpp>\n").empty());
    EXPECT_TRUE(checkFile("app/x.cpp", "#include \"render/renderer.h\"\n#include \"input/actions.h\"\n").empty());
}

TEST(Layers, InputSeesOnlyBase) {
    EXPECT_EQ(checkFile("input/x.cpp", "#include \"gl/context.h\"\n").size(), 1u);
    EXPECT_EQ(checkFile("render/x.cpp", "#include \"input/actions.h\"\n").size(), 1u);
    EXPECT_TRUE(checkFile("input/x.cpp", "#include \"base/error.h\"\n").empty());
}

TEST(Layers, CheckerFlagsGlCallsInApp) {
    std::vector<Violation> v = checkFile("app/commands/x.cpp", "void f() {\n    glFinish();\n}\n// glFinish() in a comment is fine\n");
    ASSERT_EQ(v.size(), 1u);
    EXPECT_EQ(v[0].line, 2);
    EXPECT_TRUE(checkFile("render/x.cpp", "void f() { glFinish(); }\n").empty());
    EXPECT_EQ(checkFile("app/x.cpp", "#include <epoxy/gl.h>\n").size(), 1u);
}

TEST(Layers, UnknownFolderInAnIncludeIsAViolation) {
    // A folder the table does not know cannot be placed in the order: say so instead of passing it.
    EXPECT_EQ(checkFile("render/x.cpp", "#include \"misc/thing.h\"\n").size(), 1u);
}

TEST(Layers, SourceTreeRespectsTheLayers) {
    std::vector<Violation> all = checkTree(CURETTE_SOURCE_DIR);
    std::string report;
    for (const Violation& v : all) report += v.file + ":" + std::to_string(v.line) + ": " + v.message + "\n";
    EXPECT_TRUE(all.empty()) << report;
    EXPECT_GT(filesChecked(CURETTE_SOURCE_DIR), 100) << "the checker found too few source files to be looking at the tree";
}

}  // namespace
}  // namespace curette::layers
