#pragma once
// One error type for every bad-input path: it names the file, the field and the expected form, so a user
// can fix the input without reading code. Programs catch it at the top, print what() and exit non-zero.

#include <stdexcept>
#include <string>

namespace curette {

class InputError : public std::runtime_error {
public:
    // file: the path the user gave (or "<scene>", "<command line>"); field: dotted key or header field;
    // expected: the form the field must take; got: what was found (may be empty).
    InputError(std::string file, std::string field, std::string expected, std::string got = {});

    const std::string& file() const { return file_; }
    const std::string& field() const { return field_; }
    const std::string& expected() const { return expected_; }
    const std::string& got() const { return got_; }

private:
    std::string file_, field_, expected_, got_;
};

// A failure of the machine or driver rather than of the input (no GL 4.5, out of memory, I/O failure).
class SystemError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

}  // namespace curette
