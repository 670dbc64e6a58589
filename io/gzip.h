#pragma once
// gzip and raw deflate decompression (RFC 1952, 1951, through zlib), including files of several concatenated members, with a
// limit so a small file cannot claim gigabytes; and compression into one gzip member, for the writers.

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace curette::io {

bool isGzip(std::span<const std::uint8_t> bytes);

// Inflates all members. Throws InputError(source, "gzip stream", ...) when the stream is corrupt or
// truncated, or when the output would exceed maxBytes.
// With stopAfter > 0, returns as soon as that many bytes are out (to read a header before sizing the whole).
std::vector<std::uint8_t> gunzip(std::span<const std::uint8_t> bytes, const std::string& source, std::uint64_t maxBytes,
                                 std::uint64_t stopAfter = 0);

// Inflates one raw deflate stream (RFC 1951, no header: DICOM's deflated transfer syntax, PS3.5 A.5); bytes
// after its end are ignored. Throws InputError(source, "deflate stream", ...) as gunzip does.
std::vector<std::uint8_t> inflateRaw(std::span<const std::uint8_t> bytes, const std::string& source, std::uint64_t maxBytes);

// The inflation of gunzip or inflateRaw read in parts, for a reader whose file is too large to hold
// uncompressed: read() fills `out` and returns how many bytes it wrote, fewer only at the stream's end (0 after
// it). `bytes` must outlive the inflater. Throws as gunzip does, the limit counting every byte read.
class Inflater {
public:
    Inflater(std::span<const std::uint8_t> bytes, std::string source, std::uint64_t maxBytes, bool gzip = true);
    ~Inflater();
    Inflater(const Inflater&) = delete;
    Inflater& operator=(const Inflater&) = delete;
    std::size_t read(std::span<std::uint8_t> out);

private:
    [[noreturn]] void fail(const std::string& expected, const std::string& found);
    struct Stream;
    std::unique_ptr<Stream> stream_;
    std::span<const std::uint8_t> bytes_;
    std::string source_, what_;
    std::uint64_t maxBytes_, total_ = 0;
    bool gzip_, done_ = false;
};

// Deflates `bytes` into a single gzip member (zlib level 0..9; 6 is zlib's default). Throws SystemError
// when zlib fails (out of memory).
std::vector<std::uint8_t> gzipCompress(std::span<const std::uint8_t> bytes, int level = 6);

// The same member fed in parts, for a writer whose file is too large to hold uncompressed: add() each part in
// order, then finish() returns the member (gzipCompress of their concatenation).
class GzipCompressor {
public:
    explicit GzipCompressor(int level = 6);
    ~GzipCompressor();
    GzipCompressor(const GzipCompressor&) = delete;
    GzipCompressor& operator=(const GzipCompressor&) = delete;
    void add(std::span<const std::uint8_t> bytes);
    std::vector<std::uint8_t> finish();

private:
    void run(std::span<const std::uint8_t> bytes, bool last);
    struct Stream;
    std::unique_ptr<Stream> stream_;
    std::vector<std::uint8_t> out_;
};

}  // namespace curette::io
