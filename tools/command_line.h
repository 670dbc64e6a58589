#pragma once
// Command-line options of one sub-command: `--name value`, `--name=value` and flags. Unknown options and
// missing values are InputErrors naming the option (file "<command line>"). The same tables give `--help`
// and the top-level usage (tools/commands/commands.h), so the help cannot lag the parser.

#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gl/context.h"

namespace curette {

struct OptionSpec {
    // A constructor, not an aggregate, so tables may leave the placeholder out without a warning.
    OptionSpec(std::string name_, bool takesValue_, std::string help_, std::string placeholder_ = {})
        : name(std::move(name_)), takesValue(takesValue_), help(std::move(help_)), placeholder(std::move(placeholder_)) {}

    std::string name;        // without dashes
    bool takesValue = true;
    std::string help;        // one line for usage
    std::string placeholder; // the value in usage (default: the name in capitals)
};

// One command or sub-command as the user types it: its name ("render", "bench raycast"), what follows the name
// in a synopsis (positional arguments and required options), what it does, and its options.
struct CommandSpec {
    std::string name;
    std::string synopsis;
    std::string summary;
    std::vector<OptionSpec> options;
};

class CommandLine {
public:
    // args: everything after the sub-command name. With --help or -h among them (before a `--`) nothing else
    // is parsed: helpRequested() says so and the caller prints the command's help.
    CommandLine(std::vector<std::string> args, std::vector<OptionSpec> specs);
    CommandLine(std::vector<std::string> args, const CommandSpec& command) : CommandLine(std::move(args), command.options) {}

    bool helpRequested() const { return helpRequested_; }

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

    std::string usage() const { return optionUsage(specs_); }
    // One line per option: `--name VALUE` and its help.
    static std::string optionUsage(const std::vector<OptionSpec>& specs);

private:
    bool helpRequested_ = false;
    std::vector<OptionSpec> specs_;
    std::map<std::string, std::string> values_;
    std::set<std::string> flags_;
    std::vector<std::string> positional_;
};

// `--name PLACEHOLDER` (or `--name` for a flag), as usage writes it.
std::string optionForm(const OptionSpec& spec);
// `text` (words split at spaces) in lines of at most `width` characters, each starting with `indent`.
std::string wrapText(const std::string& text, const std::string& indent, std::size_t width = 110);
// `curette NAME --help`: the synopsis, the summary and every option.
std::string commandHelp(const CommandSpec& command);

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
