#include "io/gzip.h"

#include "base/error.h"
#include "base/progress.h"

#include <zlib.h>

#include <algorithm>
#include <climits>

namespace curette::io {

bool isGzip(std::span<const std::uint8_t> bytes) { return bytes.size() >= 2 && bytes[0] == 0x1f && bytes[1] == 0x8b; }

namespace {
// The one inflate loop: gzip members (16 + MAX_WBITS, restarting for each further member) or one raw deflate
// stream (-MAX_WBITS, whatever follows its end ignored); `what` names the stream in errors.
std::vector<std::uint8_t> inflateStream(std::span<const std::uint8_t> bytes, const std::string& source, std::uint64_t maxBytes,
                                        std::uint64_t stopAfter, bool gzip) {
    const std::string what = gzip ? "gzip stream" : "deflate stream";
    std::vector<std::uint8_t> out;
    Progress progress("decompressing " + source, static_cast<double>(bytes.size()));
    z_stream stream{};
    if (inflateInit2(&stream, gzip ? 16 + MAX_WBITS : -MAX_WBITS) != Z_OK) throw SystemError(source + ": zlib could not initialise");
    std::size_t consumed = 0;
    std::uint8_t chunk[1 << 16];
    while (consumed < bytes.size()) {
        stream.next_in = const_cast<Bytef*>(bytes.data() + consumed);
        stream.avail_in = static_cast<uInt>(std::min<std::size_t>(bytes.size() - consumed, UINT_MAX));
        int status = Z_OK;
        while (status != Z_STREAM_END) {
            stream.next_out = chunk;
            stream.avail_out = sizeof chunk;
            status = inflate(&stream, Z_NO_FLUSH);
            if (status == Z_NEED_DICT || status == Z_DATA_ERROR || status == Z_MEM_ERROR) {
                std::string reason = stream.msg ? stream.msg : "corrupt data";
                inflateEnd(&stream);
                throw InputError(source, what, gzip ? "valid gzip-compressed data" : "valid deflate-compressed data (RFC 1951)", reason);
            }
            std::size_t produced = sizeof chunk - stream.avail_out;
            if (out.size() + produced > maxBytes) {
                inflateEnd(&stream);
                throw InputError(source, what, "at most " + std::to_string(maxBytes) + " bytes once decompressed", "more");
            }
            out.insert(out.end(), chunk, chunk + produced);
            progress.update(static_cast<double>(bytes.size() - stream.avail_in));
            if (stopAfter > 0 && out.size() >= stopAfter) {
                inflateEnd(&stream);
                return out;
            }
            if (status == Z_BUF_ERROR || (status == Z_OK && stream.avail_in == 0 && produced == 0)) {
                inflateEnd(&stream);
                throw InputError(source, what, "a complete " + what, "a truncated one");
            }
        }
        consumed = bytes.size() - stream.avail_in;
        if (!gzip) break;
        // Trailing zero padding after the last member is tolerated (some tools pad).
        if (std::all_of(bytes.begin() + static_cast<std::ptrdiff_t>(consumed), bytes.end(), [](std::uint8_t b) { return b == 0; })) break;
        if (!isGzip(bytes.subspan(consumed))) break;  // not another member: trailing garbage is ignored
        inflateReset(&stream);
    }
    inflateEnd(&stream);
    return out;
}
}  // namespace

std::vector<std::uint8_t> gunzip(std::span<const std::uint8_t> bytes, const std::string& source, std::uint64_t maxBytes,
                                 std::uint64_t stopAfter) {
    return inflateStream(bytes, source, maxBytes, stopAfter, true);
}

std::vector<std::uint8_t> inflateRaw(std::span<const std::uint8_t> bytes, const std::string& source, std::uint64_t maxBytes) {
    return inflateStream(bytes, source, maxBytes, 0, false);
}

struct GzipCompressor::Stream {
    z_stream z{};
};

GzipCompressor::GzipCompressor(int level) : stream_(std::make_unique<Stream>()) {
    // 16 + MAX_WBITS: write a gzip header and trailer rather than zlib's.
    if (deflateInit2(&stream_->z, std::clamp(level, 0, 9), Z_DEFLATED, 16 + MAX_WBITS, 8, Z_DEFAULT_STRATEGY) != Z_OK) {
        stream_.reset();
        throw SystemError("zlib could not initialise compression");
    }
}

GzipCompressor::~GzipCompressor() {
    if (stream_) deflateEnd(&stream_->z);
}

void GzipCompressor::run(std::span<const std::uint8_t> bytes, bool last) {
    z_stream& z = stream_->z;
    std::uint8_t chunk[1 << 16];
    std::size_t consumed = 0;
    int status = Z_OK;
    do {
        // zlib counts in uInt: feed at most 1 GiB at a time.
        std::size_t feed = std::min<std::size_t>(bytes.size() - consumed, std::size_t(1) << 30);
        z.next_in = const_cast<Bytef*>(bytes.data() + consumed);
        z.avail_in = static_cast<uInt>(feed);
        const bool finishing = last && consumed + feed == bytes.size();
        do {
            z.next_out = chunk;
            z.avail_out = sizeof chunk;
            status = deflate(&z, finishing ? Z_FINISH : Z_NO_FLUSH);
            if (status == Z_STREAM_ERROR) throw SystemError("zlib failed while compressing");
            out_.insert(out_.end(), chunk, chunk + (sizeof chunk - z.avail_out));
        } while (z.avail_out == 0);
        consumed += feed - z.avail_in;
    } while (consumed < bytes.size() || (last && status != Z_STREAM_END));
}

void GzipCompressor::add(std::span<const std::uint8_t> bytes) { run(bytes, false); }

std::vector<std::uint8_t> GzipCompressor::finish() {
    run({}, true);
    return std::move(out_);
}

std::vector<std::uint8_t> gzipCompress(std::span<const std::uint8_t> bytes, int level) {
    GzipCompressor gz(level);
    gz.add(bytes);
    return gz.finish();
}

}  // namespace curette::io
