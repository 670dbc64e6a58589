#include "tools/movie.h"

#include "base/atomic_file.h"
#include "base/error.h"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <sys/wait.h>
#include <unistd.h>

namespace curette {

std::string movieFrameName(std::size_t index) {
    char name[64];
    std::snprintf(name, sizeof name, "frame_%06zu.png", index);
    return name;
}

double turntableAzimuthDeg(double startDeg, int i, int count) { return startDeg + 360.0 * i / count; }

std::optional<std::filesystem::path> findProgram(const std::string& program, const std::string& pathVariable) {
    std::size_t start = 0;
    while (start <= pathVariable.size()) {
        std::size_t colon = pathVariable.find(':', start);
        std::string dir = pathVariable.substr(start, colon == std::string::npos ? std::string::npos : colon - start);
        std::filesystem::path candidate = std::filesystem::path(dir.empty() ? "." : dir) / program;
        std::error_code ec;
        if (std::filesystem::is_regular_file(candidate, ec) && access(candidate.c_str(), X_OK) == 0) return candidate;
        if (colon == std::string::npos) break;
        start = colon + 1;
    }
    return std::nullopt;
}

std::string ffconcatList(const std::vector<std::string>& frames, double fps) {
    char duration[32];
    std::snprintf(duration, sizeof duration, "%.6f", 1.0 / fps);
    std::string list = "ffconcat version 1.0\n";
    auto quoted = [](const std::string& name) {
        std::string q = "'";
        for (char c : name) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
        return q + "'";
    };
    // Every entry with its duration, the last one too (ffmpeg 5 honours it; the fps filter then makes exactly
    // one output frame per entry).
    for (const std::string& f : frames) list += "file " + quoted(f) + "\nduration " + duration + "\n";
    return list;
}

std::vector<std::string> ffmpegArguments(const std::string& list, double fps, const std::filesystem::path& output) {
    char rate[32];
    std::snprintf(rate, sizeof rate, "%g", fps);
    return {"-hide_banner", "-loglevel", "error", "-nostdin", "-y", "-f", "concat", "-i", list,
            "-vf", std::string("fps=") + rate + ",pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v", "libx264", "-pix_fmt", "yuv420p",
            "-movflags", "+faststart", "-f", "mp4", output.string()};
}

namespace {

std::optional<std::filesystem::path> ffmpegOnPath() {
    const char* path = std::getenv("PATH");
    return findProgram("ffmpeg", path ? path : "");
}

}  // namespace

bool ffmpegAvailable() { return ffmpegOnPath().has_value(); }

bool encodeMovie(const std::filesystem::path& framesDir, const std::vector<std::string>& frames, double fps,
                 const std::filesystem::path& mp4) {
    std::optional<std::filesystem::path> ffmpeg = ffmpegOnPath();
    if (!ffmpeg) return false;
    std::filesystem::path target = std::filesystem::absolute(mp4);
    std::string partialName = ".";   // (appended, not "." + name: GCC 12 warns falsely about the latter)
    partialName += target.filename().string();
    partialName += ".partial";
    std::filesystem::path partial = target.parent_path() / partialName;
    const std::string listName = ".frames.ffconcat";
    writeFileAtomically(framesDir / listName, ffconcatList(frames, fps));
    std::vector<std::string> arguments = ffmpegArguments(listName, fps, partial);
    std::vector<char*> argv;
    std::string program = ffmpeg->string();
    argv.push_back(program.data());
    for (std::string& a : arguments) argv.push_back(a.data());
    argv.push_back(nullptr);
    std::fflush(stdout);
    std::fflush(stderr);
    pid_t child = fork();
    if (child < 0) throw SystemError("cannot start ffmpeg (fork failed)");
    if (child == 0) {
        // In the frames' folder the list names them plainly: no quoting of the folder's own name can go wrong.
        if (chdir(framesDir.c_str()) != 0) _exit(126);
        execv(argv[0], argv.data());
        _exit(127);
    }
    int status = 0;
    while (waitpid(child, &status, 0) < 0)
        if (errno != EINTR) throw SystemError("cannot wait for ffmpeg");
    std::error_code ec;
    std::filesystem::remove(framesDir / listName, ec);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || !std::filesystem::is_regular_file(partial, ec)) {
        std::filesystem::remove(partial, ec);
        throw SystemError(program + " failed (" + (WIFEXITED(status) ? "exit code " + std::to_string(WEXITSTATUS(status)) : std::string("killed")) +
                          ") making " + target.string() + "; the frames are in " + framesDir.string());
    }
    std::filesystem::rename(partial, target, ec);
    if (ec) {
        std::filesystem::remove(partial, ec);
        throw SystemError(target.string() + ": cannot rename the finished movie into place (" + ec.message() + ")");
    }
    return true;
}

}  // namespace curette
