#include "gl/program.h"

#include "base/error.h"
#include "base/log.h"
#include "gl/embedded_shaders.h"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>

namespace curette::gl {

namespace {

std::string readShaderFile(const std::string& name) {
    if (const char* dir = std::getenv("CURETTE_SHADER_DIR"); dir && *dir) {
        std::ifstream in(std::string(dir) + "/" + name);
        if (!in) throw SystemError("shader " + name + " not found in CURETTE_SHADER_DIR=" + dir);
        std::stringstream text;
        text << in.rdbuf();
        return text.str();
    }
    for (const EmbeddedShader& shader : embeddedShaders())
        if (shader.name == name) return std::string(shader.source);
    throw SystemError("shader " + name + " is not embedded (shaders/CMakeLists.txt embeds every *.glsl, *.comp, *.vert and "
                      "*.frag in shaders/: is the name right, and was CMake re-run?)");
}

struct Expander {
    std::vector<std::string> files;
    std::set<std::string> included;

    void expand(const std::string& name, std::string& out, int depth) {
        if (depth > 16) throw SystemError("shader include depth exceeds 16 at " + name);
        if (!included.insert(name).second) return;  // each file once: includes are their own guards
        int fileIndex = static_cast<int>(files.size());
        files.push_back(name);
        std::istringstream in(readShaderFile(name));
        std::string line;
        int number = 0;
        out += "#line 1 " + std::to_string(fileIndex) + "\n";
        while (std::getline(in, line)) {
            ++number;
            auto first = line.find_first_not_of(" \t");
            if (first != std::string::npos && line.compare(first, 8, "#include") == 0) {
                auto open = line.find('"', first), close = line.rfind('"');
                if (open == std::string::npos || close <= open)
                    throw SystemError(name + ":" + std::to_string(number) + ": malformed #include");
                expand(line.substr(open + 1, close - open - 1), out, depth + 1);
                out += "#line " + std::to_string(number + 1) + " " + std::to_string(fileIndex) + "\n";
                continue;
            }
            out += line;
            out += '\n';
        }
    }
};

// Replaces the driver's "SOURCE:LINE(COLUMN)" (Mesa) or "SOURCE(LINE)" (others) locations with
// "file.glsl:LINE", using the #line source numbers expandShaderSource assigned.
std::string annotateLog(const std::string& log, const std::vector<std::string>& files) {
    std::string result;
    std::istringstream in(log);
    std::string line;
    while (std::getline(in, line)) {
        std::size_t end = line.find_first_not_of("0123456789");
        if (end != std::string::npos && end > 0 && (line[end] == ':' || line[end] == '(')) {
            std::size_t index = std::stoul(line.substr(0, end));
            std::size_t numberStart = end + 1;
            std::size_t numberEnd = line.find_first_not_of("0123456789", numberStart);
            if (index < files.size() && numberEnd != std::string::npos && numberEnd > numberStart) {
                std::string number = line.substr(numberStart, numberEnd - numberStart);
                std::size_t rest = line.find(':', numberEnd);
                line = files[index] + ":" + number + (rest == std::string::npos ? "" : line.substr(rest));
            }
        }
        result += "  " + line + "\n";
    }
    return result;
}

ShaderName compileStage(GLenum stage, const std::string& name, const Defines& defines, std::set<std::string>& declared) {
    ExpandedSource source = expandShaderSource(name, defines);
    declared.merge(declaredUniforms(source.text));
    ShaderName shader(glCreateShader(stage));
    const char* text = source.text.c_str();
    glShaderSource(shader.name(), 1, &text, nullptr);
    glCompileShader(shader.name());
    GLint ok = 0;
    glGetShaderiv(shader.name(), GL_COMPILE_STATUS, &ok);
    if (!ok) {
        GLint length = 0;
        glGetShaderiv(shader.name(), GL_INFO_LOG_LENGTH, &length);
        std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
        glGetShaderInfoLog(shader.name(), length, nullptr, log.data());
        throw SystemError("shader " + name + " failed to compile:\n" + annotateLog(log, source.files));
    }
    return shader;
}

ProgramName link(const std::vector<GLuint>& shaders, const std::string& label) {
    ProgramName program(glCreateProgram());
    for (GLuint s : shaders) glAttachShader(program.name(), s);
    glLinkProgram(program.name());
    GLint ok = 0;
    glGetProgramiv(program.name(), GL_LINK_STATUS, &ok);
    if (!ok) {
        GLint length = 0;
        glGetProgramiv(program.name(), GL_INFO_LOG_LENGTH, &length);
        std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
        glGetProgramInfoLog(program.name(), length, nullptr, log.data());
        throw SystemError("shader program " + label + " failed to link:\n" + log);
    }
    for (GLuint s : shaders) glDetachShader(program.name(), s);
    glObjectLabel(GL_PROGRAM, program.name(), static_cast<GLsizei>(label.size()), label.c_str());
    return program;
}

}  // namespace

std::set<std::string> declaredUniforms(const std::string& source) {
    // Statements are split at ';' and '{' after comments are dropped; a statement whose first word after
    // any layout(...) and qualifiers is "uniform" declares the identifiers before each '[' , ',' or its end.
    std::string text;
    text.reserve(source.size());
    for (std::size_t i = 0; i < source.size(); ++i) {
        if (source.compare(i, 2, "//") == 0) {
            i = source.find('\n', i);
            if (i == std::string::npos) break;
        } else if (source.compare(i, 2, "/*") == 0) {
            i = source.find("*/", i);
            if (i == std::string::npos) break;
            ++i;
            continue;
        }
        if (source[i] == '#') {  // preprocessor lines are not declarations
            i = source.find('\n', i);
            if (i == std::string::npos) break;
        }
        text += source[i];
    }
    std::set<std::string> names;
    auto isIdentifier = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
    std::size_t start = 0;
    while (start < text.size()) {
        std::size_t end = text.find_first_of(";{}", start);
        if (end == std::string::npos) end = text.size();
        std::string statement = text.substr(start, end - start);
        bool block = end < text.size() && text[end] == '{';
        start = end + 1;
        // Drop layout(...) qualifiers.
        for (std::size_t l = statement.find("layout"); l != std::string::npos; l = statement.find("layout")) {
            std::size_t close = statement.find(')', l);
            if (close == std::string::npos) break;
            statement.erase(l, close + 1 - l);
        }
        std::istringstream words(statement);
        std::vector<std::string> tokens;
        for (std::string w; words >> w;) tokens.push_back(w);
        auto u = std::find(tokens.begin(), tokens.end(), "uniform");
        if (u == tokens.end() || block) continue;
        // What follows "uniform": qualifiers and a type, then declarators "name", "name[N]" separated by commas.
        std::string rest;
        for (auto t = u + 1; t != tokens.end(); ++t) rest += *t + " ";
        std::vector<std::string> declarators;
        std::size_t from = 0;
        while (from <= rest.size()) {
            std::size_t comma = rest.find(',', from);
            if (comma == std::string::npos) comma = rest.size();
            declarators.push_back(rest.substr(from, comma - from));
            from = comma + 1;
        }
        for (std::string& d : declarators) {
            std::size_t bracket = d.find('[');
            if (bracket != std::string::npos) d.erase(bracket);
            std::size_t last = d.find_last_not_of(' ');
            if (last == std::string::npos) continue;
            std::size_t first = last;
            while (first > 0 && isIdentifier(d[first - 1])) --first;
            names.insert(d.substr(first, last + 1 - first));
        }
    }
    return names;
}

ExpandedSource expandShaderSource(const std::string& name, const Defines& defines) {
    Expander expander;
    std::string body;
    expander.expand(name, body, 0);
    // Every shader starts with "#version 450"; defines go right after it.
    auto versionEnd = body.find("#version");
    if (versionEnd == std::string::npos) throw SystemError("shader " + name + " has no #version line");
    versionEnd = body.find('\n', versionEnd) + 1;
    std::string prelude;
    for (const auto& [key, value] : defines) prelude += "#define " + key + " " + value + "\n";
    prelude += "#line 2 0\n";
    body.insert(versionEnd, prelude);
    // The expander's first #line precedes #version, which GLSL forbids; drop it.
    if (body.rfind("#line 1 0\n", 0) == 0) body.erase(0, 10);
    return {std::move(body), std::move(expander.files)};
}

Program Program::compute(const std::string& name, const Defines& defines) {
    Program p;
    ShaderName shader = compileStage(GL_COMPUTE_SHADER, name, defines, p.declared_);
    p.program_ = link({shader.name()}, name);
    p.label_ = name;
    return p;
}

Program& ComputeVariants::get(const Defines& defines) {
    auto found = programs_.find(defines);
    if (found != programs_.end()) return found->second;
    return programs_.emplace(defines, Program::compute(shader_, defines)).first->second;
}

Program Program::graphics(const std::string& vertex, const std::string& fragment, const Defines& defines) {
    Program p;
    ShaderName vs = compileStage(GL_VERTEX_SHADER, vertex, defines, p.declared_);
    ShaderName fs = compileStage(GL_FRAGMENT_SHADER, fragment, defines, p.declared_);
    p.label_ = vertex + "+" + fragment;
    p.program_ = link({vs.name(), fs.name()}, p.label_);
    return p;
}

GLint Program::location(const char* uniform) {
    auto found = locations_.find(uniform);
    if (found != locations_.end()) return found->second;
    if (!declared_.count(uniform))
        throw SystemError("shader program " + label_ + " declares no uniform \"" + uniform +
                          "\" (a binder or pass sets a name its shader pieces do not have)");
    GLint location = glGetUniformLocation(program_.name(), uniform);
    locations_.emplace(uniform, location);
    return location;
}

void Program::set(const char* u, int v) { glProgramUniform1i(program_.name(), location(u), v); }
void Program::set(const char* u, unsigned v) { glProgramUniform1ui(program_.name(), location(u), v); }
void Program::set(const char* u, float v) { glProgramUniform1f(program_.name(), location(u), v); }
void Program::set(const char* u, glm::vec2 v) { glProgramUniform2fv(program_.name(), location(u), 1, glm::value_ptr(v)); }
void Program::set(const char* u, glm::vec3 v) { glProgramUniform3fv(program_.name(), location(u), 1, glm::value_ptr(v)); }
void Program::set(const char* u, glm::vec4 v) { glProgramUniform4fv(program_.name(), location(u), 1, glm::value_ptr(v)); }
void Program::set(const char* u, glm::ivec2 v) { glProgramUniform2iv(program_.name(), location(u), 1, glm::value_ptr(v)); }
void Program::set(const char* u, glm::ivec3 v) { glProgramUniform3iv(program_.name(), location(u), 1, glm::value_ptr(v)); }
void Program::set(const char* u, glm::uvec2 v) { glProgramUniform2uiv(program_.name(), location(u), 1, glm::value_ptr(v)); }
void Program::set(const char* u, glm::uvec3 v) { glProgramUniform3uiv(program_.name(), location(u), 1, glm::value_ptr(v)); }
void Program::set(const char* u, const glm::mat3& v) {
    glProgramUniformMatrix3fv(program_.name(), location(u), 1, GL_FALSE, glm::value_ptr(v));
}
void Program::set(const char* u, const glm::mat4& v) {
    glProgramUniformMatrix4fv(program_.name(), location(u), 1, GL_FALSE, glm::value_ptr(v));
}

glm::uvec3 Program::workGroupSize() const {
    GLint size[3] = {1, 1, 1};
    glGetProgramiv(program_.name(), GL_COMPUTE_WORK_GROUP_SIZE, size);
    return {static_cast<unsigned>(size[0]), static_cast<unsigned>(size[1]), static_cast<unsigned>(size[2])};
}

void Program::dispatchCovering(glm::uvec3 items) const {
    glm::uvec3 group = workGroupSize();
    glm::uvec3 groups = (items + group - 1u) / group;
    use();
    glDispatchCompute(groups.x, groups.y, groups.z);
}

namespace {
thread_local ProgramUseLog* currentUseLog = nullptr;

bool isSamplerType(GLenum t) {
    switch (t) {
        case GL_SAMPLER_1D: case GL_SAMPLER_2D: case GL_SAMPLER_3D: case GL_SAMPLER_2D_ARRAY: case GL_SAMPLER_1D_ARRAY:
        case GL_SAMPLER_CUBE: case GL_SAMPLER_2D_SHADOW: case GL_SAMPLER_BUFFER:
        case GL_INT_SAMPLER_1D: case GL_INT_SAMPLER_2D: case GL_INT_SAMPLER_3D: case GL_INT_SAMPLER_2D_ARRAY:
        case GL_UNSIGNED_INT_SAMPLER_1D: case GL_UNSIGNED_INT_SAMPLER_2D: case GL_UNSIGNED_INT_SAMPLER_3D:
        case GL_UNSIGNED_INT_SAMPLER_2D_ARRAY: case GL_UNSIGNED_INT_SAMPLER_BUFFER: return true;
        default: return false;
    }
}

bool isImageType(GLenum t) {
    switch (t) {
        case GL_IMAGE_1D: case GL_IMAGE_2D: case GL_IMAGE_3D: case GL_IMAGE_2D_ARRAY: case GL_IMAGE_BUFFER:
        case GL_INT_IMAGE_2D: case GL_INT_IMAGE_3D: case GL_INT_IMAGE_2D_ARRAY:
        case GL_UNSIGNED_INT_IMAGE_1D: case GL_UNSIGNED_INT_IMAGE_2D: case GL_UNSIGNED_INT_IMAGE_3D:
        case GL_UNSIGNED_INT_IMAGE_2D_ARRAY: case GL_UNSIGNED_INT_IMAGE_BUFFER: return true;
        default: return false;
    }
}

void blockBindings(GLuint program, GLenum interface, std::set<unsigned>& out) {
    GLint count = 0;
    glGetProgramInterfaceiv(program, interface, GL_ACTIVE_RESOURCES, &count);
    for (GLint i = 0; i < count; ++i) {
        const GLenum property = GL_BUFFER_BINDING;
        GLint binding = 0;
        glGetProgramResourceiv(program, interface, static_cast<GLuint>(i), 1, &property, 1, nullptr, &binding);
        out.insert(static_cast<unsigned>(binding));
    }
}
}  // namespace

void Program::use() const {
    glUseProgram(program_.name());
    if (currentUseLog) currentUseLog->programs_.push_back(program_.name());
}

ProgramUseLog::ProgramUseLog() : outer_(currentUseLog) { currentUseLog = this; }
ProgramUseLog::~ProgramUseLog() {
    if (outer_) outer_->programs_.insert(outer_->programs_.end(), programs_.begin(), programs_.end());
    currentUseLog = outer_;
}

ProgramBindings activeBindings(GLuint program) {
    ProgramBindings b;
    GLint count = 0;
    glGetProgramInterfaceiv(program, GL_UNIFORM, GL_ACTIVE_RESOURCES, &count);
    for (GLint i = 0; i < count; ++i) {
        const GLenum properties[2] = {GL_TYPE, GL_LOCATION};
        GLint values[2] = {0, -1};
        glGetProgramResourceiv(program, GL_UNIFORM, static_cast<GLuint>(i), 2, properties, 2, nullptr, values);
        auto type = static_cast<GLenum>(values[0]);
        if (values[1] < 0 || !(isSamplerType(type) || isImageType(type))) continue;
        GLint unit = 0;
        glGetUniformiv(program, values[1], &unit);
        (isSamplerType(type) ? b.samplers : b.images).insert(static_cast<unsigned>(unit));
    }
    blockBindings(program, GL_SHADER_STORAGE_BLOCK, b.storageBlocks);
    blockBindings(program, GL_UNIFORM_BLOCK, b.uniformBlocks);
    return b;
}

}  // namespace curette::gl
