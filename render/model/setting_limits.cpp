#include "render/model/setting_limits.h"

#include "base/error.h"

namespace curette {

namespace {
// As the scene reader has always printed numbers: no trailing zeros.
std::string shortText(double v) {
    std::string s = std::to_string(v);
    s.erase(s.find_last_not_of('0') + 1);
    if (!s.empty() && s.back() == '.') s.pop_back();
    return s;
}
}  // namespace

std::string IntLimit::expected() const { return "an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "]"; }

std::string NumberLimit::expected() const {
    return "a number in [" + shortText(min) + ", " + shortText(max) + (maxOpen ? ")" : "]");
}

void requireWithin(const IntLimit& limit, int value, const std::string& source, const std::string& key) {
    if (!limit.contains(value)) throw InputError(source, key, limit.expected(), std::to_string(value));
}

void requireWithin(const NumberLimit& limit, double value, const std::string& source, const std::string& key) {
    if (!limit.contains(value)) throw InputError(source, key, limit.expected(), std::to_string(value));
}

}  // namespace curette
