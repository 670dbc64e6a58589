#include "base/transfer_function.h"

#include "base/error.h"

#include <algorithm>
#include <cmath>

namespace curette {

namespace {

template <typename Point, typename Get>
auto interpolate(const std::vector<Point>& points, double x, Get get) {
    if (x <= points.front().value) return get(points.front());
    if (x >= points.back().value) return get(points.back());
    auto upper = std::upper_bound(points.begin(), points.end(), x,
                                  [](double v, const Point& p) { return v < p.value; });
    const Point& b = *upper;
    const Point& a = *(upper - 1);
    double span = b.value - a.value;
    double t = span > 0 ? (x - a.value) / span : 1.0;
    return get(a) + (get(b) - get(a)) * t;
}

}  // namespace

glm::dvec3 TransferFunction::evaluateColor(double value) const {
    return interpolate(color, value, [](const ColorPoint& p) { return p.rgb; });
}

double TransferFunction::evaluateOpacity(double value) const {
    return interpolate(opacity, value, [](const ScalarPoint& p) { return p.y; });
}

double TransferFunction::evaluateGradientOpacity(double g) const {
    if (gradientOpacity.empty()) return 1.0;
    return interpolate(gradientOpacity, g, [](const ScalarPoint& p) { return p.y; });
}

bool TransferFunction::hasGradientOpacity() const {
    return std::any_of(gradientOpacity.begin(), gradientOpacity.end(), [](const ScalarPoint& p) { return p.y != 1.0; });
}

double TransferFunction::domainMin() const { return std::min(color.front().value, opacity.front().value); }
double TransferFunction::domainMax() const { return std::max(color.back().value, opacity.back().value); }

void TransferFunction::validate(const std::string& file) const {
    auto checkSorted = [&](const auto& points, const char* field) {
        for (std::size_t i = 0; i < points.size(); ++i) {
            std::string where = std::string(field) + "[" + std::to_string(i) + "]";
            if (!std::isfinite(points[i].value)) throw InputError(file, where, "a finite data value");
            if (i > 0 && points[i].value < points[i - 1].value)
                throw InputError(file, where, "points sorted by increasing value",
                                 std::to_string(points[i].value) + " after " + std::to_string(points[i - 1].value));
        }
    };
    if (color.empty()) throw InputError(file, "color", "at least one colour point", "none");
    if (opacity.empty()) throw InputError(file, "opacity", "at least one opacity point", "none");
    checkSorted(color, "color");
    checkSorted(opacity, "opacity");
    checkSorted(gradientOpacity, "gradient_opacity");
    for (std::size_t i = 0; i < color.size(); ++i)
        for (int c = 0; c < 3; ++c)
            if (!(color[i].rgb[c] >= 0.0 && color[i].rgb[c] <= 1.0))
                throw InputError(file, "color[" + std::to_string(i) + "]", "r, g, b in [0, 1]",
                                 std::to_string(color[i].rgb[c]));
    auto checkUnit = [&](const std::vector<ScalarPoint>& points, const char* field) {
        for (std::size_t i = 0; i < points.size(); ++i)
            if (!(points[i].y >= 0.0 && points[i].y <= 1.0))
                throw InputError(file, std::string(field) + "[" + std::to_string(i) + "]", "an opacity in [0, 1]",
                                 std::to_string(points[i].y));
    };
    checkUnit(opacity, "opacity");
    checkUnit(gradientOpacity, "gradient_opacity");
    if (!(unitLengthMm > 0.0 && std::isfinite(unitLengthMm)))
        throw InputError(file, "unit_length_mm", "a positive length in millimetres", std::to_string(unitLengthMm));
}

}  // namespace curette
