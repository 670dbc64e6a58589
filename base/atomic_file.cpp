#include "base/atomic_file.h"

#include "base/error.h"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <random>
#include <string>
#include <unistd.h>
#include <utility>

namespace curette {

namespace fs = std::filesystem;

AtomicFileWriter::AtomicFileWriter(fs::path path) : path_(std::move(path)) {
    fs::path directory = path_.has_parent_path() ? path_.parent_path() : fs::path(".");
    std::random_device entropy;
    // Hidden sibling in the same directory, so the final rename cannot cross file systems.
    std::string temporaryName = ".";
    temporaryName += path_.filename().string();
    temporaryName += ".tmp";
    temporaryName += std::to_string(entropy() % 1000000);
    temporary_ = directory / temporaryName;
    fd_ = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd_ < 0) throw SystemError(path_.string() + ": cannot create a file there (" + std::strerror(errno) + ")");
}

AtomicFileWriter::~AtomicFileWriter() {
    if (fd_ >= 0) ::close(fd_);
    if (!temporary_.empty()) ::unlink(temporary_.c_str());
}

void AtomicFileWriter::fail(const char* what, int error) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    ::unlink(temporary_.c_str());
    temporary_.clear();
    throw SystemError(path_.string() + ": " + what + " failed (" + std::strerror(error) + ")");
}

void AtomicFileWriter::write(std::span<const std::uint8_t> bytes) {
    if (fd_ < 0) throw SystemError(path_.string() + ": write after the file was committed or abandoned");
    std::size_t written = 0;
    while (written < bytes.size()) {
        ssize_t n = ::write(fd_, bytes.data() + written, bytes.size() - written);
        if (n < 0) {
            if (errno == EINTR) continue;
            fail("write", errno);
        }
        written += static_cast<std::size_t>(n);
    }
    size_ += bytes.size();
}

void AtomicFileWriter::commit() {
    if (fd_ < 0) throw SystemError(path_.string() + ": commit after the file was committed or abandoned");
    if (::fsync(fd_) != 0) fail("flush", errno);
    int closed = ::close(fd_);
    fd_ = -1;
    if (closed != 0) fail("flush", errno);
    if (::rename(temporary_.c_str(), path_.c_str()) != 0) fail("rename", errno);
    temporary_.clear();
}

void writeFileAtomically(const fs::path& path, std::span<const std::uint8_t> bytes) {
    AtomicFileWriter file(path);
    file.write(bytes);
    file.commit();
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
