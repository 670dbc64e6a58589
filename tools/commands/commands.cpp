// The command table, the usage generated from it, and the dispatch: one place that knows every command.
#include "tools/commands/commands.h"

#include "base/error.h"
#include "render/model/shading_mode.h"

#include <cstdio>

#ifndef CURETTE_VERSION
#define CURETTE_VERSION "unknown"
#endif
#ifndef CURETTE_GIT_DESCRIPTION
#define CURETTE_GIT_DESCRIPTION ""
#endif

namespace curette::commands {

namespace {

constexpr std::size_t kWidth = 110;

std::string firstWord(const std::string& name) { return name.substr(0, name.find(' ')); }
bool isHelp(const std::string& arg) { return arg == "--help" || arg == "-h"; }

// `words` filled into lines of at most kWidth characters, each starting with `indent`.
std::string wrap(const std::vector<std::string>& words, const std::string& indent) {
    std::string text, line;
    for (const std::string& w : words) {
        if (!line.empty() && line.size() + 1 + w.size() > kWidth) text += line + "\n", line.clear();
        line += line.empty() ? indent + w : " " + w;
    }
    return line.empty() ? text : text + line + "\n";
}

std::vector<std::string> splitWords(const std::string& text) {
    std::vector<std::string> words;
    std::size_t start = 0;
    while (start < text.size()) {
        std::size_t end = std::min(text.find(' ', start), text.size());
        if (end > start) words.push_back(text.substr(start, end - start));
        start = end + 1;
    }
    return words;
}

// Whether `synopsis` names --`name` (followed by a space, a bracket or its end, so --size is not --size-x).
bool names(const std::string& synopsis, const std::string& name) {
    const std::string dashed = "--" + name;
    for (std::size_t at = synopsis.find(dashed); at != std::string::npos; at = synopsis.find(dashed, at + 1)) {
        std::size_t after = at + dashed.size();
        if (after == synopsis.size() || synopsis[after] == ' ' || synopsis[after] == ']') return true;
    }
    return false;
}

bool hasGpuOption(const CommandSpec& spec) {
    for (const OptionSpec& o : spec.options)
        if (o.name == "gpu") return true;
    return false;
}

// A command in the top-level usage: its synopsis, what it does, and every option but --gpu (a footnote) in
// brackets (the ones the synopsis names are left out).
std::string usageBlock(const CommandSpec& spec) {
    std::string text = "  " + spec.name + (spec.synopsis.empty() ? "" : " " + spec.synopsis) + "\n" + wrap(splitWords(spec.summary), "      ");
    std::vector<std::string> options;
    for (const OptionSpec& o : spec.options) {
        if (o.name == "gpu" || names(spec.synopsis, o.name)) continue;
        options.push_back("[" + optionForm(o) + "]");
    }
    return text + wrap(options, "      ");
}

std::vector<const Command*> group(const std::string& name) {
    std::vector<const Command*> found;
    for (const Command& c : commandTable())
        if (firstWord(c.spec.name) == name) found.push_back(&c);
    return found;
}

std::string subCommandList(const std::vector<const Command*>& commands) {
    std::string list;
    for (const Command* c : commands) list += (list.empty() ? "" : ", ") + c->spec.name.substr(c->spec.name.find(' ') + 1);
    return list;
}

}  // namespace

const std::vector<Command>& commandTable() {
    static const std::vector<Command> table = [] {
        std::vector<Command> t{infoCommand(), renderCommand(), viewCommand(), recordCommand(), replayCommand(), reportCommand()};
        for (Command& c : benchCommands()) t.push_back(std::move(c));
        for (Command& c : tractsCommands()) t.push_back(std::move(c));
        return t;
    }();
    return table;
}

std::string usage() {
    std::string text =
        "usage: curette COMMAND [options]\n"
        "       curette COMMAND --help      the command's options, one a line\n"
        "       curette --version\n"
        "\ncommands:\n";
    std::vector<std::string> gpu;
    for (const Command& c : commandTable()) {
        text += usageBlock(c.spec);
        if (hasGpuOption(c.spec)) gpu.push_back(c.spec.name + ",");
    }
    if (!gpu.empty()) gpu.back().pop_back();
    text += "\nshading modes: " + shadingModeList() + "\n";
    std::vector<std::string> footnote = splitWords("--gpu N|llvmpipe|surfaceless chooses the headless GL context of:");
    footnote.insert(footnote.end(), gpu.begin(), gpu.end());
    text += wrap(footnote, "");
    text += "exit codes: 0 success, 2 bad input (the message names file, field and expected form),\n"
            "            3 system problem (GL driver, disk), 1 a failed check or anything else\n";
    return text;
}

std::string versionText() {
    std::string git = CURETTE_GIT_DESCRIPTION;
    return std::string("curette ") + CURETTE_VERSION + (git.empty() ? "" : " (git " + git + ")") + "\n";
}

int run(const Arguments& args) {
    const std::string& name = args.at(0);
    std::vector<const Command*> commands = group(name);
    if (commands.empty()) {
        std::fprintf(stderr, "curette: unknown command \"%s\"\n\n%s", name.c_str(), usage().c_str());
        return 2;
    }
    const Command* command = commands.front();
    Arguments rest(args.begin() + 1, args.end());
    if (command->spec.name != name) {   // a group: the sub-command is the next word
        if (!rest.empty() && isHelp(rest[0])) {
            std::string text = "usage: curette " + name + " SUB-COMMAND [options]   (curette " + name + " SUB-COMMAND --help: its options)\n\n";
            for (const Command* c : commands) text += usageBlock(c->spec);
            std::fputs(text.c_str(), stdout);
            return 0;
        }
        std::string expected = "a sub-command: " + subCommandList(commands) + " (curette " + name + " --help lists them)";
        if (rest.empty()) throw InputError("<command line>", name, expected, "nothing");
        command = nullptr;
        for (const Command* c : commands)
            if (c->spec.name == name + " " + rest[0]) command = c;
        if (!command) throw InputError("<command line>", name, expected, "\"" + rest[0] + "\"");
        rest.erase(rest.begin());
    }
    CommandLine cl(rest, command->spec);
    if (cl.helpRequested()) {
        std::fputs(commandHelp(command->spec).c_str(), stdout);
        return 0;
    }
    return command->run(cl);
}

}  // namespace curette::commands
