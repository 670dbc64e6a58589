#pragma once
// Runs the real `curette` binary (CURETTE_BINARY) with arguments, as a user would from a shell.

#include <array>
#include <cstdio>
#include <string>
#include <sys/wait.h>

namespace curette::testing {

struct Invocation {
    int exitCode;
    std::string output;  // stdout and stderr
};

inline Invocation runCurette(const std::string& arguments) {
    std::string command = std::string(CURETTE_BINARY) + " " + arguments + " 2>&1";
    FILE* pipe = popen(command.c_str(), "r");
    std::string output;
    std::array<char, 4096> buffer;
    while (std::size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe)) output.append(buffer.data(), n);
    int status = pclose(pipe);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

}  // namespace curette::testing
