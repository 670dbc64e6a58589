#include "base/json_reader.h"

#include "base/error.h"

#include <cmath>

namespace curette {

namespace {

// "camera" + "target" -> "camera.target"; a root path ending in ':' ("line 3:") reads as a prefix.
std::string joinKey(const std::string& path, const std::string& key) {
    if (path.empty()) return key;
    return path.back() == ':' ? path + " " + key : path + "." + key;
}

}  // namespace

namespace {

// The JSON parser (and whatever later walks the value) recurses once per nesting level, so a hostile file
// nested a few hundred thousand levels deep would overflow the stack. Every file curette reads nests a handful
// of levels; refuse anything deeper than kMaxJsonDepth before parsing, naming where it got too deep.
constexpr int kMaxJsonDepth = 64;

void checkNestingDepth(std::string_view text, const std::string& file) {
    int depth = 0;
    bool inString = false, escaped = false;
    std::size_t line = 1, column = 0;
    for (char c : text) {
        ++column;
        if (c == '\n') ++line, column = 0;
        if (inString) {
            if (escaped) escaped = false;
            else if (c == '\\') escaped = true;
            else if (c == '"') inString = false;
            continue;
        }
        if (c == '"') inString = true;
        else if (c == '[' || c == '{') {
            if (++depth > kMaxJsonDepth)
                throw InputError(file, "line " + std::to_string(line) + ", column " + std::to_string(column),
                                 "JSON nested at most " + std::to_string(kMaxJsonDepth) + " levels deep", "deeper nesting");
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
}

}  // namespace

nlohmann::json parseJson(std::string_view text, const std::string& file) {
    checkNestingDepth(text, file);
    try {
        return nlohmann::json::parse(text.begin(), text.end());
    } catch (const nlohmann::json::parse_error& e) {
        // Convert the byte offset into a line and column a user can find.
        std::size_t offset = std::min<std::size_t>(e.byte > 0 ? e.byte - 1 : 0, text.size());
        std::size_t line = 1, column = 1;
        for (std::size_t i = 0; i < offset; ++i) {
            if (text[i] == '\n') ++line, column = 1;
            else ++column;
        }
        std::string reason = e.what();
        if (auto colon = reason.rfind(": "); colon != std::string::npos) reason = reason.substr(colon + 2);
        throw InputError(file, "line " + std::to_string(line) + ", column " + std::to_string(column), "valid JSON",
                         reason);
    } catch (const nlohmann::json::exception& e) {
        // Other parser failures (e.g. a number too large for any numeric type) carry no position.
        std::string reason = e.what();
        if (auto colon = reason.rfind(": "); colon != std::string::npos) reason = reason.substr(colon + 2);
        throw InputError(file, "(document)", "valid JSON", reason);
    }
}

std::string describeJson(const nlohmann::json& value) {
    if (value.is_object()) return "an object";
    if (value.is_null()) return "null";
    std::string text = value.dump();
    if (text.size() > 40) text = text.substr(0, 37) + "...";
    if (value.is_array()) return "the array " + text;
    if (value.is_string()) return "the string " + text;
    if (value.is_boolean()) return text;
    return text;
}

JsonReader::JsonReader(const nlohmann::json& value, std::string file, std::string path)
    : value_(&value), file_(std::move(file)), path_(std::move(path)), read_(std::make_shared<std::set<std::string>>()) {}

JsonReader JsonReader::child(const nlohmann::json& value, std::string path) const { return JsonReader(value, file_, std::move(path)); }

void JsonReader::fail(const std::string& expected) const {
    throw InputError(file_, path_.empty() ? "(top level)" : path_, expected, describeJson(*value_));
}

JsonReader JsonReader::at(const std::string& key) const {
    if (!value_->is_object()) fail("an object");
    auto it = value_->find(key);
    if (it == value_->end())
        throw InputError(file_, joinKey(path_, key), "a value (this key is required)", "nothing");
    read_->insert(key);
    return child(*it, joinKey(path_, key));
}

std::optional<JsonReader> JsonReader::find(const std::string& key) const {
    if (!value_->is_object()) fail("an object");
    read_->insert(key);
    auto it = value_->find(key);
    if (it == value_->end()) return std::nullopt;
    return child(*it, joinKey(path_, key));
}

bool JsonReader::has(const std::string& key) const { return value_->is_object() && value_->contains(key); }

void JsonReader::finish() const {
    if (!value_->is_object()) return;
    for (auto it = value_->begin(); it != value_->end(); ++it)
        if (!read_->count(it.key())) {
            std::string known;
            for (const std::string& k : *read_) known += (known.empty() ? "" : ", ") + k;
            throw InputError(file_, joinKey(path_, it.key()),
                             "one of the known keys (" + known + ")", "an unknown key");
        }
}

std::size_t JsonReader::size() const {
    if (!value_->is_array()) fail("an array");
    return value_->size();
}

JsonReader JsonReader::operator[](std::size_t index) const {
    if (!value_->is_array()) fail("an array");
    return child((*value_)[index], path_ + "[" + std::to_string(index) + "]");
}

std::vector<JsonReader> JsonReader::elements(std::size_t minCount, std::size_t maxCount) const {
    std::size_t n = size();
    if (n < minCount || n > maxCount) {
        std::string expected = minCount == maxCount ? "an array of " + std::to_string(minCount) + " elements"
                               : maxCount == SIZE_MAX ? "an array of at least " + std::to_string(minCount) + " elements"
                                                      : "an array of " + std::to_string(minCount) + " to " +
                                                            std::to_string(maxCount) + " elements";
        fail(expected);
    }
    std::vector<JsonReader> list;
    for (std::size_t i = 0; i < n; ++i) list.push_back((*this)[i]);
    return list;
}

static std::string rangeText(double min, double max) {
    auto text = [](double v) {
        std::string s = std::to_string(v);
        s.erase(s.find_last_not_of('0') + 1);
        if (!s.empty() && s.back() == '.') s.pop_back();
        return s;
    };
    if (min <= -1e300 && max >= 1e300) return "";
    if (min <= -1e300) return " <= " + text(max);
    if (max >= 1e300) return " >= " + text(min);
    return " in [" + text(min) + ", " + text(max) + "]";
}

double JsonReader::number(double min, double max) const {
    if (!value_->is_number()) fail("a number" + rangeText(min, max));
    double v = value_->get<double>();
    if (!std::isfinite(v) || v < min || v > max) fail("a number" + rangeText(min, max));
    return v;
}

int JsonReader::integer(int min, int max) const {
    if (!value_->is_number_integer()) fail("an integer" + rangeText(min, max));
    auto v = value_->get<std::int64_t>();
    if (v < min || v > max) fail("an integer" + rangeText(min, max));
    return static_cast<int>(v);
}

std::uint64_t JsonReader::unsignedInteger(std::uint64_t max) const {
    if (!value_->is_number_integer() || (value_->is_number_integer() && !value_->is_number_unsigned() && value_->get<std::int64_t>() < 0))
        fail("a non-negative integer");
    auto v = value_->get<std::uint64_t>();
    if (v > max) fail("a non-negative integer <= " + std::to_string(max));
    return v;
}

bool JsonReader::boolean() const {
    if (!value_->is_boolean()) fail("true or false");
    return value_->get<bool>();
}

std::string JsonReader::string() const {
    if (!value_->is_string()) fail("a string");
    return value_->get<std::string>();
}

std::string JsonReader::oneOf(const std::vector<std::string>& choices) const {
    std::string list;
    for (const std::string& c : choices) list += (list.empty() ? "" : ", ") + ("\"" + c + "\"");
    if (!value_->is_string()) fail("one of " + list);
    std::string v = value_->get<std::string>();
    for (const std::string& c : choices)
        if (v == c) return v;
    fail("one of " + list);
}

std::vector<double> JsonReader::numbers(std::size_t count, double min, double max) const {
    if (!value_->is_array() || value_->size() != count)
        fail("an array of " + std::to_string(count) + " numbers" + rangeText(min, max));
    std::vector<double> values;
    for (std::size_t i = 0; i < count; ++i) values.push_back((*this)[i].number(min, max));
    return values;
}

glm::dvec2 JsonReader::vec2(double min, double max) const {
    auto v = numbers(2, min, max);
    return {v[0], v[1]};
}
glm::dvec3 JsonReader::vec3(double min, double max) const {
    auto v = numbers(3, min, max);
    return {v[0], v[1], v[2]};
}
glm::dvec4 JsonReader::vec4(double min, double max) const {
    auto v = numbers(4, min, max);
    return {v[0], v[1], v[2], v[3]};
}

}  // namespace curette
