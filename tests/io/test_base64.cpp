// base/base64.h against the test vectors of RFC 4648 section 10.
#include "base/base64.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace curette {
namespace {

std::string encoded(const std::string& text) { return base64(std::vector<std::uint8_t>(text.begin(), text.end())); }

TEST(Base64, Rfc4648TestVectors) {
    EXPECT_EQ(encoded(""), "");
    EXPECT_EQ(encoded("f"), "Zg==");
    EXPECT_EQ(encoded("fo"), "Zm8=");
    EXPECT_EQ(encoded("foo"), "Zm9v");
    EXPECT_EQ(encoded("foob"), "Zm9vYg==");
    EXPECT_EQ(encoded("fooba"), "Zm9vYmE=");
    EXPECT_EQ(encoded("foobar"), "Zm9vYmFy");
}

TEST(Base64, EveryByteValue) {
    std::vector<std::uint8_t> bytes = {0x00, 0xff, 0xfe, 0x80, 0x7f};
    EXPECT_EQ(base64(bytes), "AP/+gH8=");
}

}  // namespace
}  // namespace curette
