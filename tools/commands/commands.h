#pragma once
// The sub-commands of the `curette` executable: one table of them (name, synopsis, summary, options, and the
// function that runs it). The parser, `curette COMMAND --help` and the top-level usage all read this table, so
// none of them can lag another. A command returns the process exit code and throws InputError/SystemError for
// main() to report.

#include "tools/command_line.h"

#include <string>
#include <vector>

namespace curette::commands {

using Arguments = std::vector<std::string>;

struct Command {
    CommandSpec spec;
    int (*run)(const CommandLine& cl) = nullptr;
};

// Each command file's entries (bench and tracts have several sub-commands).
Command infoCommand();                  // curette info FILE, curette info --gl
Command renderCommand();                // curette render --scene S --out F.png
Command viewCommand();                  // curette view --scene S
Command recordCommand();                // curette record --scene S --out F.jsonl --synthetic FAMILIES
Command replayCommand();                // curette replay F.jsonl
Command reportCommand();                // curette report --scene S --out DIR
std::vector<Command> benchCommands();   // curette bench raycast|cao|... (tools/bench/)
std::vector<Command> tractsCommands();  // curette tracts synth --from DIR --count N --out F.tck

// Every command, in the order of the top-level usage.
const std::vector<Command>& commandTable();

// The top-level usage, generated from commandTable().
std::string usage();
// "curette VERSION" (the CMake project version; with the git description at configure time when there was one):
// `curette --version`'s line, and the maker a report names (session/carve_report.h takes it as data).
std::string programVersion();
std::string versionText();   // programVersion() and a line feed

// Runs the command `args` names (args: everything after `curette`; a group such as bench takes the sub-command
// from args[1]). `--help` prints the command's help and returns 0.
int run(const Arguments& args);

}  // namespace curette::commands
