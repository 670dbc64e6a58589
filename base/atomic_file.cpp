#include "base/atomic_file.h"

#include "base/error.h"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <random>
#include <string>
#include <unistd.h>

namespace curette {

namespace fs = std::filesystem;

void writeFileAtomically(const fs::path& path, std::span<const std::uint8_t> bytes) {
    fs::path directory = path.has_parent_path() ? path.parent_path() : fs::path(".");
    std::random_device entropy;
    // Hidden sibling in the same directory, so the final rename cannot cross file systems.
    std::string temporaryName = ".";
    temporaryName += path.filename().string();
    temporaryName += ".tmp";
    temporaryName += std::to_string(entropy() % 1000000);
    fs::path temporary = directory / temporaryName;
    int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd < 0) throw SystemError(path.string() + ": cannot create a file there (" + std::strerror(errno) + ")");
    std::size_t written = 0;
    while (written < bytes.size()) {
        ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
        if (n < 0) {
            if (errno == EINTR) continue;
            int error = errno;
            ::close(fd);
            ::unlink(temporary.c_str());
            throw SystemError(path.string() + ": write failed (" + std::strerror(error) + ")");
        }
        written += static_cast<std::size_t>(n);
    }
    if (::fsync(fd) != 0 || ::close(fd) != 0) {
        int error = errno;
        ::unlink(temporary.c_str());
        throw SystemError(path.string() + ": flush failed (" + std::strerror(error) + ")");
    }
    if (::rename(temporary.c_str(), path.c_str()) != 0) {
        int error = errno;
        ::unlink(temporary.c_str());
        throw SystemError(path.string() + ": rename failed (" + std::strerror(error) + ")");
    }
}

void writeFileAtomically(const fs::path& path, std::string_view text) {
    writeFileAtomically(path, std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

std::vector<std::uint8_t> readFileBytes(const fs::path& path) {
    std::error_code ec;
    if (fs::is_directory(path, ec)) throw InputError(path.string(), "", "a file", "a directory");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path.string(), "", "a readable file", std::strerror(errno));
    in.seekg(0, std::ios::end);
    auto size = static_cast<std::size_t>(in.tellg());
    in.seekg(0);
    std::vector<std::uint8_t> bytes(size);
    if (size && !in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size)))
        throw InputError(path.string(), "", "a readable file", "a read error");
    return bytes;
}

}  // namespace curette
