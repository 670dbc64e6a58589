#pragma once
// Strict reading of JSON files (scenes, transfer functions, sessions, input mappings): every access names
// its dotted key path, so errors say exactly which key is wrong and what form it must take. Objects are
// closed with finish(), which rejects keys nobody read (typos must not be silently ignored).

#include <nlohmann/json.hpp>

#include <glm/glm.hpp>

#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace curette {

// Parses JSON text; a syntax error becomes InputError(file, "line L, column C", "valid JSON", reason).
nlohmann::json parseJson(std::string_view text, const std::string& file);

class JsonReader {
public:
    JsonReader(const nlohmann::json& value, std::string file, std::string path = {});

    const std::string& file() const { return file_; }
    const std::string& path() const { return path_; }   // e.g. "camera.target[1]"
    const nlohmann::json& json() const { return *value_; }

    bool isObject() const { return value_->is_object(); }
    bool isArray() const { return value_->is_array(); }
    bool isString() const { return value_->is_string(); }
    bool isNumber() const { return value_->is_number(); }

    // Object members. `at` requires the key; `find` returns nullopt when absent. Both mark it as read.
    JsonReader at(const std::string& key) const;
    std::optional<JsonReader> find(const std::string& key) const;
    bool has(const std::string& key) const;
    // Throws for any key of this object that no at/find asked for.
    void finish() const;

    // Arrays.
    std::size_t size() const;   // requires an array
    JsonReader operator[](std::size_t index) const;
    std::vector<JsonReader> elements(std::size_t minCount = 0, std::size_t maxCount = SIZE_MAX) const;

    // Scalars, with the expected form in the error.
    double number(double min = -1e300, double max = 1e300) const;
    int integer(int min = INT32_MIN, int max = INT32_MAX) const;
    std::uint64_t unsignedInteger(std::uint64_t max = UINT64_MAX) const;
    bool boolean() const;
    std::string string() const;
    std::string oneOf(const std::vector<std::string>& choices) const;
    glm::dvec2 vec2(double min = -1e300, double max = 1e300) const;
    glm::dvec3 vec3(double min = -1e300, double max = 1e300) const;
    glm::dvec4 vec4(double min = -1e300, double max = 1e300) const;
    std::vector<double> numbers(std::size_t count, double min = -1e300, double max = 1e300) const;

    [[noreturn]] void fail(const std::string& expected) const;  // names path_, shows the value found

private:
    JsonReader child(const nlohmann::json& value, std::string path) const;
    const nlohmann::json* value_;
    std::string file_, path_;
    std::shared_ptr<std::set<std::string>> read_;  // keys read from this object
};

// A short rendering of a JSON value for messages ("\"abc\"", "[1,2,...]", "an object").
std::string describeJson(const nlohmann::json& value);

}  // namespace curette
