#include "base/error.h"

namespace curette {

static std::string describe(const std::string& file, const std::string& field, const std::string& expected,
                            const std::string& got) {
    // Appended piece by piece: g++ 12 warns falsely (-Wrestrict, GCC bug 105329) on `"literal" + string`.
    std::string text = file;
    if (!field.empty()) text.append(": ").append(field);
    text.append(": expected ").append(expected);
    if (!got.empty()) text.append(", got ").append(got);
    return text;
}

InputError::InputError(std::string file, std::string field, std::string expected, std::string got)
    : std::runtime_error(describe(file, field, expected, got)),
      file_(std::move(file)),
      field_(std::move(field)),
      expected_(std::move(expected)),
      got_(std::move(got)) {}

}  // namespace curette
