// The values C++ and GLSL share, read from both sides' source text: every binding and shared constant is
// one name with one value, so changing either side alone fails here.
#include "gl/bindings.h"
#include "mesh/coverage.h"
#include "mesh/limits.h"
#include "render/model/brick_set.h"
#include "render/model/frame.h"
#include "render/model/shading_mode.h"
#include "render/passes/ambient_occlusion.h"
#include "render/passes/clip_mesh_gpu.h"

#include <gtest/gtest.h>

#include <cctype>
#include <cstddef>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace curette {
namespace {

std::string sourceText(const std::string& path) {
    std::ifstream in(std::string(CURETTE_SOURCE_DIR) + "/" + path);
    EXPECT_TRUE(in) << path;
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

// Every `#define NAME value` of a shader whose value is a number (decimal, hex, float; a u suffix).
std::map<std::string, double> glslDefines(const std::string& shader) {
    std::map<std::string, double> out;
    std::string s = sourceText("shaders/" + shader);
    std::regex define(R"(#define\s+(\w+)\s+(0x[0-9A-Fa-f]+|[0-9]+(?:\.[0-9]*)?)u?\b)");
    for (std::sregex_iterator it(s.begin(), s.end(), define), end; it != end; ++it)
        out[(*it)[1]] = std::stod((*it)[2].str());   // stod reads hex too
    return out;
}

// ssboTubeRings -> SSBO_TUBE_RINGS; names without a kind prefix are texture units: volume -> BINDING_VOLUME.
std::string glslName(const std::string& cpp) {
    std::string out;
    for (char c : cpp) {
        if (std::isupper(static_cast<unsigned char>(c))) out += '_';
        out += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    }
    for (const char* prefix : {"IMAGE_", "SSBO_", "UBO_", "SURFACE_", "CATEGORY_"})
        if (out.starts_with(prefix)) return out;
    return "BINDING_" + out;
}

TEST(ShaderConstants, EveryBindingHasOneValueOnBothSides) {
    std::map<std::string, double> cpp;
    std::string header = sourceText("gl/bindings.h");
    std::regex constant(R"(inline constexpr (?:unsigned|float) (\w+) = ([0-9.]+)f?;)");
    for (std::sregex_iterator it(header.begin(), header.end(), constant), end; it != end; ++it)
        cpp[glslName((*it)[1])] = std::stod((*it)[2].str());
    // Every constant the header declares is one the regex read.
    std::size_t declared = 0;
    for (std::size_t at = header.find("inline constexpr"); at != std::string::npos; at = header.find("inline constexpr", at + 1)) ++declared;
    EXPECT_EQ(cpp.size(), declared) << "a constant in gl/bindings.h not of the form `inline constexpr unsigned name = N;`";
    std::map<std::string, double> glsl = glslDefines("bindings.glsl");
    for (const auto& [name, value] : glsl) {
        if (!cpp.count(name)) ADD_FAILURE() << name << " is in shaders/bindings.glsl only";
        else EXPECT_EQ(cpp.at(name), value) << name;
    }
    for (const auto& [name, value] : cpp)
        if (!glsl.count(name)) ADD_FAILURE() << name << " is in gl/bindings.h only";
    // The header's text is what the compiler read.
    EXPECT_EQ(cpp.at("BINDING_VOLUME"), double(binding::volume));
    EXPECT_EQ(cpp.at("SSBO_ANTI_ALIASING"), double(binding::ssboAntiAliasing));
    EXPECT_EQ(cpp.at("SURFACE_LINE"), double(binding::surfaceLine));
}

TEST(ShaderConstants, LimitsMatchTheShaders) {
    EXPECT_EQ(glslDefines("phong.glsl").at("MAX_LIGHTS"), double(kMaxLights));
    EXPECT_EQ(glslDefines("ismos_occlusion.comp").at("MAX_ISMOS_LIGHTS"), double(kMaxLights));
    EXPECT_EQ(glslDefines("clip_test.glsl").at("MAX_CLIP_MESHES"), double(clip::kMaxClipMeshes));
    EXPECT_EQ(glslDefines("clip_coverage.glsl").at("CELL_SAMPLE_HALF_WIDTH"), clip::kCellSampleHalfWidth);
}

TEST(ShaderConstants, LaoGroupSizeMatchesTheShaders) {
    EXPECT_EQ(glslDefines("lao_common.glsl").at("LAO_GROUP_SIZE"), double(AmbientOcclusion::kLaoGroupSize));
    // linearInvocation() numbers invocations in groups of LAO_GROUP_SIZE: a shader calling it has that local size.
    std::smatch size;
    std::string lao = sourceText("shaders/lao.comp");
    ASSERT_TRUE(lao.find("linearInvocation()") != std::string::npos);
    ASSERT_TRUE(std::regex_search(lao, size, std::regex(R"(layout\s*\(\s*local_size_x\s*=\s*(\d+)\s*\)\s*in)")));
    EXPECT_EQ(std::stoul(size[1].str()), AmbientOcclusion::kLaoGroupSize);
}

TEST(ShaderConstants, VisitedBrickLayoutMatchesTheShaders) {
    std::map<std::string, double> glsl = glslDefines("visit_bricks.glsl");
    EXPECT_EQ(glsl.at("BRICK_SIZE"), double(kVisitBrickSize));
    EXPECT_EQ(glsl.at("BRICK_VOXELS"), double(kVisitBrickSize * kVisitBrickSize * kVisitBrickSize));
    EXPECT_EQ(glsl.at("VISIT_BRICK_NUMBER"), double(kVisitBrickNumber));
    EXPECT_EQ(glsl.at("VISIT_OPACITY_CHANGED"), double(kVisitOpacityChanged));
    EXPECT_EQ(glsl.at("VISIT_LAO_CAN_CHANGE"), double(kVisitLaoCanChange));
}

TEST(ShaderConstants, ShadingModesMatchTheShaders) {
    std::map<std::string, double> glsl = glslDefines("shading_modes.glsl");
    EXPECT_EQ(glsl.size(), allShadingModes().size());
    for (const ShadingModeTraits& t : allShadingModes()) {
        std::string name = "SHADING_";
        for (const char* c = t.name; *c; ++c) name += static_cast<char>(std::toupper(static_cast<unsigned char>(*c)));
        ASSERT_TRUE(glsl.count(name)) << name;
        EXPECT_EQ(glsl.at(name), double(static_cast<int>(t.mode))) << name;
    }
}

// The std140 offset of each member of a GLSL struct of vec4-sized and matrix members, in order.
struct Member {
    std::string name;
    std::size_t offset, size;
    bool operator==(const Member&) const = default;
};
std::ostream& operator<<(std::ostream& out, const Member& m) { return out << m.name << " @" << m.offset << " +" << m.size; }

std::vector<Member> std140Members(const std::string& shader, const std::string& structName, std::size_t& structSize) {
    std::string s = sourceText("shaders/" + shader);
    std::smatch body;
    EXPECT_TRUE(std::regex_search(s, body, std::regex("struct " + structName + R"(\s*\{([^}]*)\};)"))) << structName;
    // std140 (GLSL 4.50 sec. 7.6.2.2): base alignment and size of the member types a block here may hold.
    const std::map<std::string, std::pair<std::size_t, std::size_t>> types = {
        {"float", {4, 4}}, {"int", {4, 4}},    {"uint", {4, 4}},   {"vec2", {8, 8}},   {"vec3", {16, 12}},
        {"vec4", {16, 16}}, {"ivec4", {16, 16}}, {"uvec4", {16, 16}}, {"mat4", {16, 64}}};
    std::vector<Member> out;
    std::size_t offset = 0;
    std::string text = body[1];
    std::regex declaration(R"((\w+)\s+([\w\s,]+);)");
    std::string code = std::regex_replace(text, std::regex("//[^\n]*"), "");
    for (std::sregex_iterator it(code.begin(), code.end(), declaration), end; it != end; ++it) {
        auto type = types.find((*it)[1]);
        if (type == types.end()) {
            ADD_FAILURE() << "member type " << (*it)[1] << " not in the table";
            continue;
        }
        std::stringstream names((*it)[2]);
        for (std::string name; std::getline(names, name, ',');) {
            name = std::regex_replace(name, std::regex(R"(\s+)"), "");
            auto [align, size] = type->second;
            offset = (offset + align - 1) / align * align;
            out.push_back({name, offset, size});
            offset += size;
        }
    }
    structSize = (offset + 15) / 16 * 16;   // an array element rounds up to a vec4
    return out;
}

TEST(ShaderConstants, ClipMeshBlockMatchesTheCppStruct) {
    using clip::CameraGpu;
    std::size_t glslSize = 0;
    std::vector<Member> glsl = std140Members("clip_test.glsl", "ClipMeshGpu", glslSize);
    const std::vector<Member> cpp = {
        {"worldToMap", offsetof(CameraGpu, worldToMap), sizeof(CameraGpu::worldToMap)},
        {"info", offsetof(CameraGpu, info), sizeof(CameraGpu::info)},
        {"mapBox", offsetof(CameraGpu, mapBox), sizeof(CameraGpu::mapBox)},
        {"depthBoxLo", offsetof(CameraGpu, depthBoxLo), sizeof(CameraGpu::depthBoxLo)},
        {"depthBoxHi", offsetof(CameraGpu, depthBoxHi), sizeof(CameraGpu::depthBoxHi)},
        {"depthBall", offsetof(CameraGpu, depthBall), sizeof(CameraGpu::depthBall)},
        {"depthMap", offsetof(CameraGpu, depthMap), sizeof(CameraGpu::depthMap)},
    };
    EXPECT_EQ(glsl, cpp);
    EXPECT_EQ(glslSize, sizeof(CameraGpu));
}

}  // namespace
}  // namespace curette
