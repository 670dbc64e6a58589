#pragma once
// Shader programs built from shaders/ with a small preprocessor: `#include "file.glsl"` is resolved from the
// embedded table (or from $CURETTE_SHADER_DIR for live editing), each file once, with #line directives so
// compiler errors name the real file and line. Defines are injected after #version.

#include "gl/objects.h"

#include <glm/glm.hpp>

#include <map>
#include <set>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace curette::gl {

using Defines = std::vector<std::pair<std::string, std::string>>;

// Expanded source of one shader (includes resolved) and the file names in #line order, for messages.
struct ExpandedSource {
    std::string text;
    std::vector<std::string> files;
};
ExpandedSource expandShaderSource(const std::string& name, const Defines& defines);

class Program {
public:
    Program() = default;
    static Program compute(const std::string& name, const Defines& defines = {});
    static Program graphics(const std::string& vertex, const std::string& fragment, const Defines& defines = {});

    GLuint name() const { return program_.name(); }
    explicit operator bool() const { return static_cast<bool>(program_); }
    void use() const;   // glUseProgram, recorded by a live ProgramUseLog

    // Uniform setters by name (glProgramUniform*). The name must be declared by the program's source (any of
    // its shader pieces), or set() throws: a typo or a stale name is an error, as an unknown scene key is. A
    // declared uniform the compiler removed (unused, or under a define that is off) is ignored, so a binder
    // may set every uniform of its piece whatever the variant.
    void set(const char* uniform, int v);
    void set(const char* uniform, unsigned v);
    void set(const char* uniform, float v);
    void set(const char* uniform, glm::vec2 v);
    void set(const char* uniform, glm::vec3 v);
    void set(const char* uniform, glm::vec4 v);
    void set(const char* uniform, glm::ivec2 v);
    void set(const char* uniform, glm::ivec3 v);
    void set(const char* uniform, glm::uvec2 v);
    void set(const char* uniform, glm::uvec3 v);
    void set(const char* uniform, const glm::mat3& v);
    void set(const char* uniform, const glm::mat4& v);
    GLint location(const char* uniform);
    // Whether the source declares `uniform` (plain uniforms, not block members).
    bool declares(const std::string& uniform) const { return declared_.count(uniform) != 0; }

    // The compute work-group size declared by the shader.
    glm::uvec3 workGroupSize() const;
    // Dispatches enough groups to cover `items` invocations.
    void dispatchCovering(glm::uvec3 items) const;

private:
    ProgramName program_;
    std::string label_;
    std::unordered_map<std::string, GLint> locations_;
    std::set<std::string> declared_;
};

// The names of the plain uniforms `source` declares (`uniform T name;`, arrays by their name; blocks are not
// plain uniforms). Preprocessor conditionals are not evaluated: a uniform under an #ifdef counts as declared.
std::set<std::string> declaredUniforms(const std::string& source);

// The variants of one compute shader, each compiled on first use for its set of defines (shading mode, TF
// features, bench counters). Passes compile features in or out rather than branch on uniforms: llvmpipe runs
// both sides of a branch under a lane mask, so a feature switched off by a uniform still costs its work.
class ComputeVariants {
public:
    explicit ComputeVariants(std::string shader) : shader_(std::move(shader)) {}
    Program& get(const Defines& defines);

private:
    std::string shader_;
    std::map<Defines, Program> programs_;
};

// Records every program made current (Program::use) on this thread while it lives: what a pass really ran, so
// the resources its programs bind can be held against what the pass declares (render/pass_bindings.h).
class ProgramUseLog {
public:
    ProgramUseLog();
    ~ProgramUseLog();
    ProgramUseLog(const ProgramUseLog&) = delete;
    ProgramUseLog& operator=(const ProgramUseLog&) = delete;
    const std::vector<GLuint>& programs() const { return programs_; }

private:
    friend class Program;
    std::vector<GLuint> programs_;
    ProgramUseLog* outer_ = nullptr;
};

// The units a linked program's active resources are bound to (the GL's introspection: what the compiled shaders
// really read or write, after dead code is gone).
struct ProgramBindings {
    std::set<unsigned> samplers, images, storageBlocks, uniformBlocks;
};
ProgramBindings activeBindings(GLuint program);

}  // namespace curette::gl
