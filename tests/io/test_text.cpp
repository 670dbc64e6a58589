// base/text.h: the one trim every reader uses, each naming the characters its format pads with.
#include "base/text.h"

#include <gtest/gtest.h>

#include <string>

namespace curette {
namespace {

TEST(Text, TrimDropsWhiteSpaceAtBothEndsOnly) {
    EXPECT_EQ(trim("  a b\t\r\n"), "a b");
    EXPECT_EQ(trim("\v\f x \f\v"), "x");   // all of std::isspace's "C" set (NRRD fields, label tables)
    EXPECT_EQ(trim("x"), "x");
    EXPECT_EQ(trim(""), "");
    EXPECT_EQ(trim(" \t \n"), "");
}

TEST(Text, TrimTakesTheFormatsBlanks) {
    using namespace std::string_view_literals;
    const std::string_view dicom = " \0\t\r\n"sv;   // PS3.5 6.2 padding (a NUL after a UI), stray line ends
    EXPECT_EQ(trim("1.2.840.10008.1.2.1\0"sv, dicom), "1.2.840.10008.1.2.1");
    EXPECT_EQ(trim(" CT "sv, dicom), "CT");
    EXPECT_EQ(trim("ElementSpacing = 1 1\r", " \t\r"), "ElementSpacing = 1 1");   // MetaImage, CRLF
    EXPECT_EQ(trim("\fkey\f", " \t\r"), "\fkey\f");   // a form feed is not MetaImage padding
}

TEST(Text, TrimReturnsAViewOfItsArgument) {
    std::string text = "  inner  ";
    std::string_view t = trim(text);
    EXPECT_EQ(t.data(), text.data() + 2);
    EXPECT_EQ(t.size(), 5u);
}

}  // namespace
}  // namespace curette
