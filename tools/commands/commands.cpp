// The command table, the usage generated from it, and the dispatch: one place that knows every command.
#include "tools/commands/commands.h"

#include "base/error.h"
#include "render/model/shading_mode.h"

#include <algorithm>
#include <cstdio>

#ifndef CURETTE_VERSION
#define CURETTE_VERSION "unknown"
#endif
#ifndef CURETTE_GIT_DESCRIPTION
#define CURETTE_GIT_DESCRIPTION ""
#endif

namespace curette::commands {

namespace {

std::string firstWord(const std::string& name) { return name.substr(0, name.find(' ')); }
bool isHelp(const std::string& arg) { return arg == "--help" || arg == "-h"; }

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
    std::string text = "  " + spec.name + (spec.synopsis.empty() ? "" : " " + spec.synopsis) + "\n" + wrapText(spec.summary, "      ");
    std::string options;
    for (const OptionSpec& o : spec.options) {
        if (o.name == "gpu" || names(spec.synopsis, o.name)) continue;
        // Non-breaking inside a bracket: the wrap splits at spaces, so the form's space is put back after.
        std::string form = optionForm(o);
        std::replace(form.begin(), form.end(), ' ', '\x1f');
        options += (options.empty() ? "[" : " [") + form + "]";
    }
    std::string wrapped = wrapText(options, "      ");
    std::replace(wrapped.begin(), wrapped.end(), '\x1f', ' ');
    return text + wrapped;
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
    std::string footnote = "--gpu N|llvmpipe|surfaceless chooses the headless GL context of:";
    for (std::string g : gpu) footnote += " " + (std::replace(g.begin(), g.end(), ' ', '\x1f'), g);
    std::string wrapped = wrapText(footnote, "");
    std::replace(wrapped.begin(), wrapped.end(), '\x1f', ' ');
    text += wrapped;
    text += "exit codes: 0 success, 2 bad input (the message names file, field and expected form),\n"
            "            3 system problem (GL driver, disk), 1 a failed check or anything else\n";
    return text;
}

std::string programVersion() {
    std::string git = CURETTE_GIT_DESCRIPTION;
    return std::string("curette ") + CURETTE_VERSION + (git.empty() ? "" : " (git " + git + ")");
}

std::string versionText() { return programVersion() + "\n"; }

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
