#include "tools/command_line.h"

#include "base/error.h"

#include <algorithm>
#include <cctype>
#include <charconv>

namespace curette {

static const std::string kCommandLine = "<command line>";

CommandLine::CommandLine(std::vector<std::string> args, std::vector<OptionSpec> specs) : specs_(std::move(specs)) {
    for (const std::string& arg : args) {
        if (arg == "--") break;
        if (arg == "--help" || arg == "-h") {
            helpRequested_ = true;
            return;
        }
    }
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& arg = args[i];
        if (arg.rfind("--", 0) != 0 || arg == "--") {
            positional_.push_back(arg);
            continue;
        }
        std::string name = arg.substr(2), value;
        bool hasValue = false;
        if (auto eq = name.find('='); eq != std::string::npos) {
            value = name.substr(eq + 1);
            name = name.substr(0, eq);
            hasValue = true;
        }
        const OptionSpec* spec = nullptr;
        for (const OptionSpec& s : specs_)
            if (s.name == name) spec = &s;
        if (!spec) {
            std::string known;
            for (const OptionSpec& s : specs_) known += (known.empty() ? "--" : ", --") + s.name;
            throw InputError(kCommandLine, "--" + name, known.empty() ? "no options" : "one of " + known, "an unknown option");
        }
        if (!spec->takesValue) {
            if (hasValue) throw InputError(kCommandLine, "--" + name, "no value (it is a flag)", value);
            flags_.insert(name);
            continue;
        }
        if (!hasValue) {
            if (i + 1 >= args.size()) throw InputError(kCommandLine, "--" + name, "a value after it", "nothing");
            value = args[++i];
        }
        values_[name] = value;
    }
}

std::optional<std::string> CommandLine::value(const std::string& name) const {
    auto it = values_.find(name);
    if (it == values_.end()) return std::nullopt;
    return it->second;
}

std::string CommandLine::valueOr(const std::string& name, const std::string& fallback) const {
    return value(name).value_or(fallback);
}

std::string CommandLine::required(const std::string& name) const {
    auto v = value(name);
    if (!v) throw InputError(kCommandLine, "--" + name, "this option (it is required)", "nothing");
    return *v;
}

bool CommandLine::flag(const std::string& name) const { return flags_.count(name) > 0; }

int CommandLine::parseInt(const std::string& option, const std::string& text, int min, int max) {
    int v = 0;
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc() || end != text.data() + text.size() || v < min || v > max)
        throw InputError(kCommandLine, "--" + option,
                         "an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "]", "\"" + text + "\"");
    return v;
}

double CommandLine::parseDouble(const std::string& option, const std::string& text, double min, double max) {
    double v = 0;
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc() || end != text.data() + text.size() || !(v >= min && v <= max))
        throw InputError(kCommandLine, "--" + option, "a number in [" + std::to_string(min) + ", " + std::to_string(max) + "]",
                         "\"" + text + "\"");
    return v;
}

glm::ivec2 CommandLine::parseSize(const std::string& option, const std::string& text) {
    auto x = text.find('x');
    if (x == std::string::npos) throw InputError(kCommandLine, "--" + option, "WIDTHxHEIGHT, e.g. 512x512", "\"" + text + "\"");
    try {
        return {parseInt(option, text.substr(0, x), 1, 16384), parseInt(option, text.substr(x + 1), 1, 16384)};
    } catch (const InputError&) {
        throw InputError(kCommandLine, "--" + option, "WIDTHxHEIGHT with each in [1, 16384], e.g. 512x512", "\"" + text + "\"");
    }
}

std::vector<int> CommandLine::parseIntList(const std::string& option, const std::string& text, int min, int max) {
    std::vector<int> list;
    std::size_t start = 0;
    while (start <= text.size()) {
        std::size_t comma = text.find(',', start);
        std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        list.push_back(parseInt(option, item, min, max));
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    return list;
}

std::string optionForm(const OptionSpec& spec) {
    if (!spec.takesValue) return "--" + spec.name;
    std::string placeholder = spec.placeholder;
    if (placeholder.empty())
        for (char c : spec.name) placeholder += c == '-' ? '_' : static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return "--" + spec.name + " " + placeholder;
}

std::string CommandLine::optionUsage(const std::vector<OptionSpec>& specs) {
    std::string text;
    constexpr std::size_t kColumn = 30, kWidth = 110;   // the help's column, and the lines' width it wraps to
    for (const OptionSpec& s : specs) {
        std::string line = "  " + optionForm(s);
        line.resize(std::max<std::size_t>(line.size() + 2, kColumn), ' ');
        std::size_t lineStart = 0, start = 0;
        while (start < s.help.size()) {
            std::size_t end = std::min(s.help.find(' ', start), s.help.size());
            std::string word = s.help.substr(start, end - start);
            bool first = line.size() - lineStart <= kColumn;
            if (!first && line.size() - lineStart + 1 + word.size() > kWidth) {
                line += "\n";
                lineStart = line.size();
                line += std::string(kColumn, ' ') + word;
            } else {
                line += (first ? "" : " ") + word;
            }
            start = end + 1;
        }
        text += line + "\n";
    }
    return text;
}

std::string wrapText(const std::string& text, const std::string& indent, std::size_t width) {
    std::string out, line;
    std::size_t start = 0;
    while (start < text.size()) {
        std::size_t end = std::min(text.find(' ', start), text.size());
        std::string word = text.substr(start, end - start);
        start = end + 1;
        if (word.empty()) continue;
        if (!line.empty() && line.size() + 1 + word.size() > width) out += line + "\n", line.clear();
        line += line.empty() ? indent + word : " " + word;
    }
    return line.empty() ? out : out + line + "\n";
}

std::string commandHelp(const CommandSpec& command) {
    std::string text = "usage: curette " + command.name + (command.synopsis.empty() ? "" : " " + command.synopsis) +
                       (command.options.empty() ? "" : " [options]") + "\n\n" + wrapText(command.summary, "");
    std::vector<OptionSpec> options = command.options;
    options.push_back({"help", false, "this help"});
    return text + "\noptions:\n" + CommandLine::optionUsage(options);
}

OptionSpec gpuOption() {
    return {"gpu", true, "headless GL: an EGL device index (curette info --gl lists them), llvmpipe (software) or surfaceless "
                         "(default: the first hardware device, else surfaceless)", "N|llvmpipe|surfaceless"};
}

std::vector<OptionSpec> withGpuOption(std::vector<OptionSpec> specs) {
    specs.push_back(gpuOption());
    return specs;
}

gl::GpuChoice parseGpuChoice(const std::string& text, const gl::EglPlatforms& platforms) {
    if (text == "llvmpipe") return {gl::GpuChoice::Kind::Software, -1};
    if (text == "surfaceless") return {gl::GpuChoice::Kind::Surfaceless, -1};
    const int count = static_cast<int>(platforms.devices.size());
    std::string expected = "an EGL device index, llvmpipe or surfaceless; " + platforms.describeDevices();
    int index = -1;
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), index);
    if (ec != std::errc() || end != text.data() + text.size()) throw InputError(kCommandLine, "--gpu", expected, "\"" + text + "\"");
    if (index < 0 || index >= count)
        throw InputError(kCommandLine, "--gpu",
                         (count ? "a device index in [0, " + std::to_string(count - 1) + "], llvmpipe or surfaceless; "
                                : std::string("llvmpipe or surfaceless (there is no device to index); ")) +
                             platforms.describeDevices(),
                         "\"" + text + "\"");
    return {gl::GpuChoice::Kind::Device, index};
}

gl::GpuChoice gpuChoice(const CommandLine& cl) {
    std::optional<std::string> text = cl.value("gpu");
    if (!text) return {};
    if (*text == "llvmpipe" || *text == "surfaceless") return parseGpuChoice(*text, {});
    return parseGpuChoice(*text, gl::queryEglPlatforms());
}

}  // namespace curette
