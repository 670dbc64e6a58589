#include "base/error.h"

namespace curette {

static std::string describe(const std::string& file, const std::string& field, const std::string& expected,
                            const std::string& got) {
    std::string text = file;
    if (!field.empty()) text += ": " + field;
    text += ": expected " + expected;
    if (!got.empty()) text += ", got " + got;
    return text;
}

InputError::InputError(std::string file, std::string field, std::string expected, std::string got)
    : std::runtime_error(describe(file, field, expected, got)),
      file_(std::move(file)),
      field_(std::move(field)),
      expected_(std::move(expected)),
      got_(std::move(got)) {}

}  // namespace curette
