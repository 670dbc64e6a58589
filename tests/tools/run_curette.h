#pragma once
// Runs the real `curette` binary (CURETTE_BINARY) with arguments, as a user would from a shell.

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

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

// An empty folder `name` in this test process's own folder `<prefix>-<pid>` under the system's temporary
// directory (emptied if an earlier test of the process left it).
inline std::filesystem::path freshScratchFolder(const std::string& prefix, const std::string& name) {
    auto dir = std::filesystem::temp_directory_path() / (prefix + "-" + std::to_string(::getpid())) / name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

// A whole file as bytes ("" when it cannot be read).
inline std::string readTextFile(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace curette::testing
