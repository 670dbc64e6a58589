#include "io/gzip.h"

#include "base/error.h"
#include "base/progress.h"

#include <zlib.h>

#include <algorithm>
#include <climits>

namespace curette::io {

bool isGzip(std::span<const std::uint8_t> bytes) { return bytes.size() >= 2 && bytes[0] == 0x1f && bytes[1] == 0x8b; }

struct Inflater::Stream {
    Stream(const std::string& source, double total) : progress("decompressing " + source, total) {}
    z_stream z{};
    Progress progress;
};

// gzip members (16 + MAX_WBITS, restarting for each further member) or one raw deflate stream (-MAX_WBITS,
// whatever follows its end ignored).
Inflater::Inflater(std::span<const std::uint8_t> bytes, std::string source, std::uint64_t maxBytes, bool gzip)
    : stream_(std::make_unique<Stream>(source, static_cast<double>(bytes.size()))),
      bytes_(bytes), source_(std::move(source)), what_(gzip ? "gzip stream" : "deflate stream"), maxBytes_(maxBytes), gzip_(gzip) {
    if (inflateInit2(&stream_->z, gzip ? 16 + MAX_WBITS : -MAX_WBITS) != Z_OK) {
        stream_.reset();
        throw SystemError(source_ + ": zlib could not initialise");
    }
    stream_->z.next_in = const_cast<Bytef*>(bytes_.data());
    stream_->z.avail_in = static_cast<uInt>(std::min<std::size_t>(bytes_.size(), UINT_MAX));
}

Inflater::~Inflater() {
    if (stream_) inflateEnd(&stream_->z);
}

void Inflater::fail(const std::string& expected, const std::string& found) {
    done_ = true;
    throw InputError(source_, what_, expected, found);
}

std::size_t Inflater::read(std::span<std::uint8_t> out) {
    z_stream& z = stream_->z;
    std::size_t written = 0;
    while (written < out.size() && !done_) {
        const std::size_t room = std::min<std::size_t>(out.size() - written, std::size_t(1) << 30);
        z.next_out = out.data() + written;
        z.avail_out = static_cast<uInt>(room);
        int status = inflate(&z, Z_NO_FLUSH);
        if (status == Z_NEED_DICT || status == Z_DATA_ERROR || status == Z_MEM_ERROR)
            fail(gzip_ ? "valid gzip-compressed data" : "valid deflate-compressed data (RFC 1951)", z.msg ? z.msg : "corrupt data");
        const std::size_t produced = room - z.avail_out;
        written += produced;
        total_ += produced;
        if (total_ > maxBytes_) fail("at most " + std::to_string(maxBytes_) + " bytes once decompressed", "more");
        const std::size_t consumed = static_cast<std::size_t>(reinterpret_cast<const std::uint8_t*>(z.next_in) - bytes_.data());
        stream_->progress.update(static_cast<double>(consumed));
        if (status == Z_STREAM_END) {
            std::span<const std::uint8_t> rest = bytes_.subspan(consumed);
            // Trailing zero padding after the last member is tolerated (some tools pad); anything else that is
            // not another member is ignored.
            if (!gzip_ || std::all_of(rest.begin(), rest.end(), [](std::uint8_t b) { return b == 0; }) || !isGzip(rest)) {
                done_ = true;
                break;
            }
            inflateReset(&z);
            continue;
        }
        if (z.avail_in == 0 && consumed < bytes_.size()) {   // zlib counts in uInt: the next part of a > 4 GiB input
            z.avail_in = static_cast<uInt>(std::min<std::size_t>(bytes_.size() - consumed, UINT_MAX));
            continue;
        }
        if (status == Z_BUF_ERROR || (status == Z_OK && z.avail_in == 0 && produced == 0)) fail("a complete " + what_, "a truncated one");
    }
    return written;
}

namespace {
// gunzip and inflateRaw: the inflater read to its end (or to stopAfter bytes) in chunks.
std::vector<std::uint8_t> inflateStream(std::span<const std::uint8_t> bytes, const std::string& source, std::uint64_t maxBytes,
                                        std::uint64_t stopAfter, bool gzip) {
    Inflater inflater(bytes, source, maxBytes, gzip);
    std::vector<std::uint8_t> out;
    std::uint8_t chunk[1 << 16];
    while (std::size_t n = inflater.read(chunk)) {
        out.insert(out.end(), chunk, chunk + n);
        if (stopAfter > 0 && out.size() >= stopAfter) break;
        if (n < sizeof chunk) break;
    }
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
