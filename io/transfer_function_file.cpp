#include "io/transfer_function_file.h"

#include "base/atomic_file.h"
#include "base/error.h"
#include "base/json_reader.h"

#include <charconv>
#include <cstdio>
#include <cmath>
#include <sstream>

namespace curette::io {

TransferFunction parseTransferFunctionJson(const nlohmann::json& json, const std::string& source, const std::string& keyPrefix) {
    JsonReader r(json, source, keyPrefix);
    if (!r.isObject()) r.fail("a transfer function object with \"color\" and \"opacity\"");
    TransferFunction tf;
    if (auto n = r.find("name")) tf.name = n->string();
    if (auto u = r.find("unit_length_mm")) tf.unitLengthMm = u->number(1e-6, 1e6);
    for (const JsonReader& p : r.at("color").elements(1)) {
        std::vector<double> v = p.numbers(4);
        for (int c = 1; c < 4; ++c)
            if (v[static_cast<std::size_t>(c)] < 0 || v[static_cast<std::size_t>(c)] > 1) p.fail("[value, r, g, b] with r, g, b in [0, 1]");
        tf.color.push_back({v[0], {v[1], v[2], v[3]}});
    }
    for (const JsonReader& p : r.at("opacity").elements(1)) {
        std::vector<double> v = p.numbers(2);
        if (v[1] < 0 || v[1] > 1) p.fail("[value, alpha] with alpha in [0, 1]");
        tf.opacity.push_back({v[0], v[1]});
    }
    if (auto g = r.find("gradient_opacity"))
        for (const JsonReader& p : g->elements(0)) {
            std::vector<double> v = p.numbers(2);
            if (v[0] < 0 || v[1] < 0 || v[1] > 1) p.fail("[gradient magnitude >= 0, factor in [0, 1]]");
            tf.gradientOpacity.push_back({v[0], v[1]});
        }
    if (auto m = r.find("material")) readMaterial(*m, tf.material);
    r.finish();
    tf.validate(source);
    return tf;
}

TransferFunction parseTransferFunctionJsonText(std::string_view text, const std::string& source) {
    nlohmann::json json = parseJson(text, source);
    return parseTransferFunctionJson(json, source);
}

namespace {

std::vector<double> parseNumbers(const std::string& line, const std::string& source, const std::string& field) {
    std::vector<double> values;
    std::istringstream in(line);
    for (std::string token; in >> token;) {
        double v = 0;
        auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
        if (ec != std::errc() || end != token.data() + token.size() || !std::isfinite(v))
            throw InputError(source, field, "numbers", "\"" + token + "\"");
        values.push_back(v);
    }
    return values;
}

// "N v1 v2 ... vN" grouped `stride` numbers per point.
std::vector<std::vector<double>> parseFunction(const std::string& line, int stride, const std::string& source, const std::string& field) {
    std::vector<double> v = parseNumbers(line, source, field);
    if (v.empty()) throw InputError(source, field, "a count followed by that many numbers", "an empty line");
    double count = v[0];
    // Compared as doubles: the count is untrusted and may be far outside any integer type.
    if (count != static_cast<double>(v.size() - 1))
        throw InputError(source, field, "a count equal to the numbers that follow it",
                         std::to_string(count) + " announced, " + std::to_string(v.size() - 1) + " present");
    if ((v.size() - 1) % static_cast<std::size_t>(stride) != 0)
        throw InputError(source, field, "a multiple of " + std::to_string(stride) + " numbers", std::to_string(v.size() - 1));
    std::vector<std::vector<double>> points;
    for (std::size_t i = 1; i + static_cast<std::size_t>(stride) <= v.size(); i += static_cast<std::size_t>(stride))
        points.emplace_back(v.begin() + static_cast<std::ptrdiff_t>(i), v.begin() + static_cast<std::ptrdiff_t>(i) + stride);
    return points;
}

}  // namespace

TransferFunction parseSlicerVolumeProperty(std::string_view text, const std::string& source) {
    std::vector<std::string> lines;
    std::istringstream in{std::string(text)};
    for (std::string line; std::getline(in, line);) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.find_first_not_of(" \t") == std::string::npos) continue;
        lines.push_back(line);
    }
    if (lines.size() < 9)
        throw InputError(source, "lines", "9 lines (interpolation, shade, diffuse, ambient, specular, power, scalar opacity, "
                                          "gradient opacity, colour)", std::to_string(lines.size()));
    TransferFunction tf;
    tf.name = std::filesystem::path(source).stem().string();
    auto scalar = [&](int line, const char* what) {
        std::vector<double> v = parseNumbers(lines[static_cast<std::size_t>(line)], source, "line " + std::to_string(line + 1) + " (" + what + ")");
        if (v.size() != 1) throw InputError(source, "line " + std::to_string(line + 1) + " (" + what + ")", "one number", std::to_string(v.size()) + " numbers");
        return v[0];
    };
    scalar(0, "interpolation");
    scalar(1, "shade");
    // The same ranges as the JSON material (readMaterial); a specular power of 0 would make the shader's
    // pow(0, 0) undefined.
    auto inRange = [&](int line, const char* what, double lo, double hi, bool positive) {
        double v = scalar(line, what);
        if (!(v >= lo && v <= hi) || (positive && !(v > 0.0)))
            throw InputError(source, "line " + std::to_string(line + 1) + " (" + what + ")",
                             std::string(positive ? "a positive number up to " : "a number in [0, ") + std::to_string(static_cast<int>(hi)) + (positive ? "" : "]"),
                             std::to_string(v));
        return v;
    };
    tf.material.diffuse = inRange(2, "diffuse", 0, 10, false);
    tf.material.ambient = inRange(3, "ambient", 0, 10, false);
    tf.material.specular = inRange(4, "specular", 0, 10, false);
    tf.material.specularPower = inRange(5, "specular power", 0, 1000, true);
    for (const auto& p : parseFunction(lines[6], 2, source, "line 7 (scalar opacity)")) tf.opacity.push_back({p[0], p[1]});
    for (const auto& p : parseFunction(lines[7], 2, source, "line 8 (gradient opacity)")) tf.gradientOpacity.push_back({p[0], p[1]});
    for (const auto& p : parseFunction(lines[8], 4, source, "line 9 (colour)")) tf.color.push_back({p[0], {p[1], p[2], p[3]}});
    tf.validate(source);
    return tf;
}

TransferFunction readTransferFunction(const std::filesystem::path& path) {
    std::vector<std::uint8_t> bytes = readFileBytes(path);
    std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    std::string extension = path.extension().string();
    if (extension == ".json") return parseTransferFunctionJsonText(text, path.string());
    if (extension == ".vp") return parseSlicerVolumeProperty(text, path.string());
    throw InputError(path.string(), "extension", ".json (curette) or .vp (3D Slicer volume property)", "\"" + extension + "\"");
}

void readMaterial(const JsonReader& object, TransferFunction::Material& material) {
    if (auto a = object.find("ambient")) material.ambient = a->number(0, 10);
    if (auto d = object.find("diffuse")) material.diffuse = d->number(0, 10);
    if (auto s = object.find("specular")) material.specular = s->number(0, 10);
    if (auto p = object.find("specular_power")) {
        material.specularPower = p->number(0, 1000);
        if (!(material.specularPower > 0.0)) p->fail("a positive number up to 1000 (a power of 0 makes pow(0, 0) undefined)");
    }
    object.finish();
}

std::string writeTransferFunctionJson(const TransferFunction& tf) {
    nlohmann::ordered_json j;
    j["name"] = tf.name;
    j["unit_length_mm"] = tf.unitLengthMm;
    for (const auto& p : tf.color) j["color"].push_back({p.value, p.rgb.r, p.rgb.g, p.rgb.b});
    for (const auto& p : tf.opacity) j["opacity"].push_back({p.value, p.y});
    for (const auto& p : tf.gradientOpacity) j["gradient_opacity"].push_back({p.value, p.y});
    j["material"] = {{"ambient", tf.material.ambient}, {"diffuse", tf.material.diffuse}, {"specular", tf.material.specular},
                     {"specular_power", tf.material.specularPower}};
    return j.dump(2) + "\n";
}

namespace {

std::string exact(double v) {
    char text[40];
    std::snprintf(text, sizeof text, "%.17g", v);
    return text;
}

}  // namespace

std::string writeSlicerVolumeProperty(const TransferFunction& tf) {
    std::string out = "1\n1\n" + exact(tf.material.diffuse) + "\n" + exact(tf.material.ambient) + "\n" + exact(tf.material.specular) + "\n" +
                      exact(tf.material.specularPower) + "\n";
    auto function = [&](const std::vector<TransferFunction::ScalarPoint>& points) {
        std::string line = std::to_string(2 * points.size());
        for (const auto& p : points) line += " " + exact(p.value) + " " + exact(p.y);
        return line + "\n";
    };
    out += function(tf.opacity);
    out += function(tf.gradientOpacity);
    std::string color = std::to_string(4 * tf.color.size());
    for (const auto& p : tf.color) color += " " + exact(p.value) + " " + exact(p.rgb.r) + " " + exact(p.rgb.g) + " " + exact(p.rgb.b);
    return out + color + "\n";
}

void writeTransferFunction(const std::filesystem::path& path, const TransferFunction& tf) {
    std::string extension = path.extension().string();
    if (extension == ".json") writeFileAtomically(path, writeTransferFunctionJson(tf));
    else if (extension == ".vp") writeFileAtomically(path, writeSlicerVolumeProperty(tf));
    else throw InputError(path.string(), "extension", ".json (curette) or .vp (3D Slicer volume property)", "\"" + extension + "\"");
}

}  // namespace curette::io
