// curette: carve CT and MRI volumes with exact ambient occlusion. See README.md.
#include "tools/commands/commands.h"
#include "base/error.h"

#include <cstdio>
#include <cstring>
#include <exception>
#include <string>

int main(int argc, char** argv) {
    if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h") || !std::strcmp(argv[1], "help")) {
        std::fputs(curette::commands::usage().c_str(), argc < 2 ? stderr : stdout);
        return argc < 2 ? 2 : 0;
    }
    if (!std::strcmp(argv[1], "--version")) {
        std::fputs(curette::commands::versionText().c_str(), stdout);
        return 0;
    }
    std::string command = argv[1];
    try {
        return curette::commands::run(curette::commands::Arguments(argv + 1, argv + argc));
    } catch (const curette::InputError& e) {
        std::fprintf(stderr, "curette %s: error: %s\n", command.c_str(), e.what());
        return 2;
    } catch (const curette::SystemError& e) {
        std::fprintf(stderr, "curette %s: error: %s\n", command.c_str(), e.what());
        return 3;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "curette %s: internal error: %s\n", command.c_str(), e.what());
        return 1;
    }
}
