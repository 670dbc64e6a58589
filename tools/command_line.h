#pragma once
// Command-line options of one sub-command: `--name value`, `--name=value` and flags. Unknown options and
// missing values are InputErrors naming the option (file "<command line>").

#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gl/context.h"

namespace curette {

struct OptionSpec {
    std::string name;        // without dashes
    bool takesValue = true;
    std::string help;        // one line for usage
};

class CommandLine {
public:
    // args: everything after the sub-command name.
    CommandLine(std::vector<std::string> args, std::vector<OptionSpec> specs);

    std::optional<std::string> value(const std::string& name) const;
    std::string valueOr(const std::string& name, const std::string& fallback) const;
    std::string required(const std::string& name) const;
    bool flag(const std::string& name) const;
    const std::vector<std::string>& positional() const { return positional_; }

    // Typed parsers with clear errors.
    static glm::ivec2 parseSize(const std::string& option, const std::string& text);     // "WxH"
    static int parseInt(const std::string& option, const std::string& text, int min, int max);
    static double parseDouble(const std::string& option, const std::string& text, double min, double max);
    static std::vector<int> parseIntList(const std::string& option, const std::string& text, int min, int max);

    std::string usage() const;

private:
    std::vector<OptionSpec> specs_;
    std::map<std::string, std::string> values_;
    std::set<std::string> flags_;
    std::vector<std::string> positional_;
};

// --gpu N|llvmpipe|surfaceless: the one option of every command that makes a headless GL context (render,
// replay, report, bench, info --gl); gl/context.h says what each choice opens.
OptionSpec gpuOption();
// `specs` with gpuOption() appended.
std::vector<OptionSpec> withGpuOption(std::vector<OptionSpec> specs);
// The --gpu of `cl` (absent: automatic). An index is checked against the EGL devices found here: a wrong one
// is an InputError that lists them.
gl::GpuChoice gpuChoice(const CommandLine& cl);
// The same on a given device list (tests use made-up ones).
gl::GpuChoice parseGpuChoice(const std::string& text, const gl::EglPlatforms& platforms);

}  // namespace curette
