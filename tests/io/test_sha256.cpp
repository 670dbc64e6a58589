// base/sha256.h against the FIPS 180-2 / NIST example digests, fed whole and in pieces of every small size
// (so each padding case and the pending block are crossed), and a file's digest against its bytes'.
#include "base/sha256.h"

#include "base/atomic_file.h"
#include "base/error.h"

#include <gtest/gtest.h>

#include <string>
#include <unistd.h>

namespace curette {
namespace {

struct Vector {
    std::string message, digest;
};

const Vector kVectors[] = {
    {"", "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855"},
    {"abc", "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"},
    {"abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq", "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1"},
    {"abcdefghbcdefghicdefghijdefghijkefghijklfghijklmghijklmnhijklmnoijklmnopjklmnopqklmnopqrlmnopqrsmnopqrstnopqrstu",
     "cf5b16a778af8380036ce59e7b0492370b249b11e8f07a51afac45037afee9d1"},
    {std::string(1000000, 'a'), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0"},
};

TEST(Sha256, GivesTheStandardsExampleDigests) {
    for (const Vector& v : kVectors) EXPECT_EQ(sha256Hex(v.message), v.digest) << v.message.size() << " bytes";
}

TEST(Sha256, PiecesGiveTheDigestOfTheWhole) {
    for (const Vector& v : kVectors) {
        if (v.message.size() > 1000) continue;
        for (std::size_t piece = 1; piece <= 70; ++piece) {
            Sha256 h;
            for (std::size_t at = 0; at < v.message.size(); at += piece) h.update(std::string_view(v.message).substr(at, piece));
            EXPECT_EQ(h.hexDigest(), v.digest) << v.message.size() << " bytes in pieces of " << piece;
        }
    }
    // Every length around the padding's two cases (55, 56 and 64 bytes left in the last block).
    for (std::size_t n = 50; n <= 130; ++n) {
        std::string message(n, 'x');
        Sha256 h;
        h.update(std::string_view(message).substr(0, n / 3));
        h.update(std::string_view(message).substr(n / 3));
        EXPECT_EQ(h.hexDigest(), sha256Hex(message)) << n;
    }
}

TEST(Sha256, AFilesDigestIsItsBytesDigestAndAMissingFileIsAnInputError) {
    auto dir = std::filesystem::temp_directory_path() / ("curette-sha256-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    std::string bytes(3u << 20, '\0');   // more than one read piece
    for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<char>((i * 2654435761u) >> 13);
    writeFileAtomically(dir / "data.bin", bytes);
    EXPECT_EQ(sha256OfFile(dir / "data.bin"), sha256Hex(bytes));
    writeFileAtomically(dir / "abc.txt", std::string_view("abc"));
    EXPECT_EQ(sha256OfFile(dir / "abc.txt"), kVectors[1].digest);
    EXPECT_THROW(sha256OfFile(dir / "missing.bin"), InputError);
    EXPECT_THROW(sha256OfFile(dir), InputError);
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace curette
