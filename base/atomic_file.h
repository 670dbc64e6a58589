#pragma once
// Files are written atomically: the content goes to a temporary file beside the target, is flushed to disk,
// then renamed over the target. A crash or an error leaves either the old file or none, never a partial one.

#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>
#include <string_view>

namespace curette {

// A file written in parts, atomically (for a writer whose output is too large to assemble in memory): the
// temporary file is created at construction, write() appends, commit() flushes and renames it over the target.
// Destroyed without commit() (an error while writing), the temporary file is removed and the target untouched.
// Throws SystemError (naming the path) when the directory is not writable or the disk is full.
class AtomicFileWriter {
public:
    explicit AtomicFileWriter(std::filesystem::path path);
    ~AtomicFileWriter();
    AtomicFileWriter(const AtomicFileWriter&) = delete;
    AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;
    void write(std::span<const std::uint8_t> bytes);
    void commit();
    // Bytes written so far.
    std::uint64_t size() const { return size_; }

private:
    [[noreturn]] void fail(const char* what, int error);
    std::filesystem::path path_, temporary_;
    int fd_ = -1;
    std::uint64_t size_ = 0;
};

// Throws SystemError (naming the path) when the directory is not writable or the disk is full.
void writeFileAtomically(const std::filesystem::path& path, std::span<const std::uint8_t> bytes);
void writeFileAtomically(const std::filesystem::path& path, std::string_view text);

// Reads a whole file; throws InputError(path, "", "a readable file") when it cannot be opened.
std::vector<std::uint8_t> readFileBytes(const std::filesystem::path& path);

}  // namespace curette
