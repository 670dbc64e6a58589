// base/atomic_file.h's AtomicFileWriter, which the large tract writers stream through: the parts become the
// file only at commit(); abandoned (an error while writing), the old file stays and no temporary is left.
#include "base/atomic_file.h"
#include "tests/io/io_test_support.h"

#include <gtest/gtest.h>

namespace curette {
namespace {

namespace fs = std::filesystem;

std::vector<std::uint8_t> bytesOf(std::string_view text) { return {text.begin(), text.end()}; }

std::size_t hiddenTemporaries(const fs::path& dir) {
    std::size_t n = 0;
    for (const fs::directory_entry& e : fs::directory_iterator(dir)) n += e.path().filename().string().starts_with(".parts");
    return n;
}

TEST(AtomicFileWriter, PartsBecomeTheFileAtCommitAndAnAbandonedWriteLeavesTheOldOne) {
    fs::path dir = test::scratchDirectory() / "atomic";
    fs::create_directories(dir);
    fs::path path = dir / "parts.bin";
    {
        AtomicFileWriter file(path);
        file.write(bytesOf("abc"));
        EXPECT_FALSE(fs::exists(path)) << "nothing at the target before commit()";
        file.write(bytesOf(""));
        file.write(bytesOf("defg"));
        EXPECT_EQ(file.size(), 7u);
        file.commit();
    }
    EXPECT_EQ(readFileBytes(path), bytesOf("abcdefg"));
    {
        AtomicFileWriter file(path);
        file.write(bytesOf("half"));
        EXPECT_EQ(hiddenTemporaries(dir), 1u);
    }  // destroyed without commit()
    EXPECT_EQ(readFileBytes(path), bytesOf("abcdefg"));
    EXPECT_EQ(hiddenTemporaries(dir), 0u);
    EXPECT_THROW(AtomicFileWriter(dir / "no-such-folder" / "x.bin"), SystemError);
}

}  // namespace
}  // namespace curette
