#include "tools/page_pdf.h"

#include "tools/movie.h"
#include "base/error.h"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <fcntl.h>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace curette {

bool printPageToPdf(const std::filesystem::path& html, const std::filesystem::path& pdf) {
    const char* path = std::getenv("PATH");
    std::optional<std::filesystem::path> chromium = findProgram("chromium", path ? path : "");
    if (!chromium) return false;
    const std::filesystem::path target = std::filesystem::absolute(pdf);
    std::filesystem::path partial = target;
    partial += ".partial";
    // --no-sandbox: Chromium's sandbox needs user namespaces, which containers and CI runners often lack; the
    // page is our own file and has no script.
    std::vector<std::string> arguments = {chromium->string(), "--headless", "--no-sandbox", "--disable-gpu", "--no-pdf-header-footer",
                                          "--print-to-pdf=" + partial.string(), "file://" + std::filesystem::absolute(html).string()};
    std::vector<char*> argv;
    for (std::string& a : arguments) argv.push_back(a.data());
    argv.push_back(nullptr);
    std::fflush(stdout);
    std::fflush(stderr);
    pid_t child = fork();
    if (child < 0) throw SystemError("cannot start chromium (fork failed)");
    if (child == 0) {
        int quiet = open("/dev/null", O_WRONLY);   // Chromium's own log lines are not ours to print
        if (quiet >= 0) dup2(quiet, 1), dup2(quiet, 2);
        execv(argv[0], argv.data());
        _exit(127);
    }
    int status = 0;
    while (waitpid(child, &status, 0) < 0)
        if (errno != EINTR) throw SystemError("cannot wait for chromium");
    std::error_code ec;
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || !std::filesystem::is_regular_file(partial, ec)) {
        std::filesystem::remove(partial, ec);
        throw SystemError(arguments[0] + " failed (" + (WIFEXITED(status) ? "exit code " + std::to_string(WEXITSTATUS(status)) : std::string("killed")) +
                          ") printing " + html.string() + " to PDF");
    }
    std::filesystem::rename(partial, target, ec);
    if (ec) {
        std::filesystem::remove(partial, ec);
        throw SystemError(target.string() + ": cannot rename the printed PDF into place (" + ec.message() + ")");
    }
    return true;
}

}  // namespace curette
