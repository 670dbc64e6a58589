#include "io/label_table.h"

#include "base/atomic_file.h"
#include "base/error.h"
#include "base/text.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <optional>
#include <set>

namespace curette::io {

namespace {

constexpr std::size_t kLutBytes = 768;

struct Line {
    int number = 0;  // 1-based
    std::string text;
};

bool isBlank(std::string_view s) {
    return std::all_of(s.begin(), s.end(), [](char c) { return std::isspace(static_cast<unsigned char>(c)); });
}

std::string lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

// Every line with its number, CR stripped, a UTF-8 byte-order mark dropped.
std::vector<Line> splitLines(std::string_view text) {
    if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
    std::vector<Line> lines;
    int number = 0;
    std::size_t pos = 0;
    while (pos <= text.size()) {
        std::size_t end = text.find('\n', pos);
        if (end == std::string_view::npos) end = text.size();
        std::string line(text.substr(pos, end - pos));
        if (!line.empty() && line.back() == '\r') line.pop_back();
        lines.push_back({++number, std::move(line)});
        if (end == text.size()) break;
        pos = end + 1;
    }
    return lines;
}

bool isComment(const std::string& line) { return !line.empty() && trim(line).starts_with('#'); }

std::vector<std::string> words(std::string_view s) {
    std::vector<std::string> list;
    std::size_t i = 0;
    while (i < s.size()) {
        while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
        std::size_t j = i;
        while (j < s.size() && !std::isspace(static_cast<unsigned char>(s[j]))) ++j;
        if (j > i) list.emplace_back(s.substr(i, j - i));
        i = j;
    }
    return list;
}

std::optional<long> asInteger(std::string_view s) {
    long v = 0;
    auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || end != s.data() + s.size()) return std::nullopt;
    return v;
}

std::optional<double> asNumber(std::string_view s) {
    double v = 0;
    auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v)) return std::nullopt;
    return v;
}

std::string lineField(const Line& line) { return "line " + std::to_string(line.number); }

std::string quoted(const std::string& s) { return "\"" + (s.size() > 120 ? s.substr(0, 120) + "..." : s) + "\""; }

int parseId(std::string_view word, const Line& line, const std::string& source) {
    std::optional<long> id = asInteger(word);
    if (!id || *id < 0 || *id > 65535)
        throw InputError(source, lineField(line), "a label index: an integer in 0..65535 first", quoted(line.text));
    return static_cast<int>(*id);
}

// A colour component 0..255 (any number, clamped, as Slicer does), as 0..1.
double parseComponent(std::string_view word, const Line& line, const std::string& source, const char* what) {
    std::optional<double> v = asNumber(word);
    if (!v) throw InputError(source, lineField(line), std::string("a number 0..255 for ") + what, quoted(line.text));
    return std::clamp(*v, 0.0, 255.0) / 255.0;
}

std::string extensionOf(const std::string& source) { return lower(std::filesystem::path(source).extension().string()); }

// Data lines: not blank, not a `#` comment.
std::vector<const Line*> dataLines(const std::vector<Line>& lines) {
    std::vector<const Line*> data;
    for (const Line& l : lines)
        if (!isBlank(l.text) && !isComment(l.text)) data.push_back(&l);
    return data;
}

// Fields of one CSV record (RFC 4180 quoting: "" inside quotes is a quote).
std::vector<std::string> csvFields(const Line& line, const std::string& source) {
    std::vector<std::string> fields;
    std::string field;
    bool inQuotes = false, wasQuoted = false;
    const std::string& s = line.text;
    for (std::size_t i = 0; i < s.size(); ++i) {
        char c = s[i];
        if (inQuotes) {
            if (c == '"' && i + 1 < s.size() && s[i + 1] == '"') field += '"', ++i;
            else if (c == '"') inQuotes = false;
            else field += c;
        } else if (c == '"') {
            inQuotes = wasQuoted = true;
        } else if (c == ',') {
            fields.push_back(wasQuoted ? field : std::string(trim(field)));
            field.clear();
            wasQuoted = false;
        } else {
            field += c;
        }
    }
    if (inQuotes) throw InputError(source, lineField(line), "CSV fields with balanced double quotes", quoted(s));
    fields.push_back(wasQuoted ? field : std::string(trim(field)));
    return fields;
}

bool isCsvHeader(const std::string& line) {
    std::size_t comma = line.find(',');
    return comma != std::string::npos && lower(std::string(trim(std::string_view(line).substr(0, comma)))) == "labelvalue";
}

void addEntry(LabelTable& table, std::set<int>& seen, LabelEntry entry, const Line& line) {
    if (!seen.insert(entry.id).second)
        throw InputError(table.source, lineField(line), "each label index once", "index " + std::to_string(entry.id) + " again");
    table.entries.push_back(std::move(entry));
}

LabelTable parseSlicerCsv(const std::vector<Line>& lines, const std::string& source) {
    LabelTable table;
    table.source = source;
    std::vector<const Line*> data;
    for (const Line& l : lines)
        if (!isBlank(l.text)) data.push_back(&l);
    const Line& header = *data.front();
    std::vector<std::string> names = csvFields(header, source);
    auto column = [&](const char* name) -> std::optional<std::size_t> {
        for (std::size_t c = 0; c < names.size(); ++c)
            if (lower(names[c]) == lower(name)) return c;
        return std::nullopt;
    };
    std::optional<std::size_t> value = column("LabelValue"), name = column("Name"), r = column("Color_R"), g = column("Color_G"),
                               b = column("Color_B"), a = column("Color_A");
    if (!value || !name || !r || !g || !b)
        throw InputError(source, lineField(header), "a CSV header with the columns LabelValue, Name, Color_R, Color_G, Color_B",
                         quoted(header.text));
    std::set<int> seen;
    for (std::size_t n = 1; n < data.size(); ++n) {
        const Line& line = *data[n];
        std::vector<std::string> f = csvFields(line, source);
        if (f.size() != names.size())
            throw InputError(source, lineField(line), std::to_string(names.size()) + " comma-separated fields, as the header",
                             std::to_string(f.size()) + " in " + quoted(line.text));
        LabelEntry e;
        e.id = parseId(f[*value], line, source);
        e.name = f[*name];
        e.rgba = {parseComponent(f[*r], line, source, "Color_R"), parseComponent(f[*g], line, source, "Color_G"),
                  parseComponent(f[*b], line, source, "Color_B"), a ? parseComponent(f[*a], line, source, "Color_A") : 1.0};
        addEntry(table, seen, std::move(e), line);
    }
    return table;
}

// ColorTable and SlicerTable: `index name r g b [a]`.
LabelTable parseColorLines(const std::vector<Line>& lines, const std::string& source, bool slicer) {
    LabelTable table;
    table.source = source;
    std::set<int> seen;
    for (const Line* line : dataLines(lines)) {
        std::vector<std::string> w = words(line->text);
        if (w.size() != 5 && w.size() != 6)
            throw InputError(source, lineField(*line),
                             slicer ? "\"index name r g b a\" (a Slicer colour table line; spaces in names are written as _)"
                                    : "\"index name r g b [a]\" (one word for the name, colours 0..255)",
                             quoted(line->text));
        LabelEntry e;
        e.id = parseId(w[0], *line, source);
        e.name = w[1];
        if (slicer) std::replace(e.name.begin(), e.name.end(), '_', ' ');
        e.rgba = {parseComponent(w[2], *line, source, "red"), parseComponent(w[3], *line, source, "green"),
                  parseComponent(w[4], *line, source, "blue"),
                  w.size() == 6 ? parseComponent(w[5], *line, source, "alpha") : (slicer ? 0.0 : 1.0)};
        addEntry(table, seen, std::move(e), *line);
    }
    return table;
}

// Whether the last word is a code column on every data line (the rule in the header).
bool hasCodeColumn(const std::vector<const Line*>& data) {
    if (data.empty()) return false;
    for (const Line* line : data) {
        if (line->text.find('\t') != std::string::npos) return false;
        std::vector<std::string> w = words(line->text);
        if (w.size() < 3 || !asInteger(w.back())) return false;
    }
    return true;
}

LabelTable parseMricronNames(const std::vector<Line>& lines, const std::string& source) {
    LabelTable table;
    table.source = source;
    std::vector<const Line*> data = dataLines(lines);
    const bool codes = hasCodeColumn(data);
    std::set<int> seen;
    for (const Line* line : data) {
        std::string text(trim(line->text));
        std::size_t end = 0;
        while (end < text.size() && !std::isspace(static_cast<unsigned char>(text[end]))) ++end;
        LabelEntry e;
        e.id = parseId(std::string_view(text).substr(0, end), *line, source);
        std::string rest(trim(std::string_view(text).substr(end)));
        if (codes) rest = std::string(trim(std::string_view(rest).substr(0, rest.find_last_of(" \t"))));
        if (rest.empty())
            throw InputError(source, lineField(*line), "\"index name\" (a name after the index)", quoted(line->text));
        e.name = rest;
        e.rgba = generatedLabelColor(e.id);
        addEntry(table, seen, std::move(e), *line);
    }
    return table;
}

std::array<glm::dvec3, 256> readLutColors(const std::filesystem::path& path) {
    std::vector<std::uint8_t> bytes = readFileBytes(path);
    if (bytes.size() != kLutBytes)
        throw InputError(path.string(), "size", "768 bytes (a planar LUT: 256 red, then 256 green, then 256 blue)",
                         std::to_string(bytes.size()) + " bytes");
    std::array<glm::dvec3, 256> colors;
    for (std::size_t i = 0; i < 256; ++i) colors[i] = glm::dvec3(bytes[i], bytes[256 + i], bytes[512 + i]) / 255.0;
    return colors;
}

double lutAlpha(int id) { return id == 0 ? 0.0 : 1.0; }

}  // namespace

LabelTableFormat detectLabelTableFormat(std::string_view text, const std::string& source) {
    std::vector<Line> lines = splitLines(text);
    for (const Line& l : lines)
        if (!isBlank(l.text)) {
            if (isCsvHeader(l.text)) return LabelTableFormat::SlicerCsv;
            break;
        }
    bool slicerComment = false;
    for (const Line& l : lines) {
        std::string t = lower(std::string(trim(l.text)));
        if (t.starts_with("# color procedural file"))
            throw InputError(source, lineField(l), "a colour table (a Slicer procedural colour file holds a function, not a table)",
                             quoted(l.text));
        if (t.starts_with("# color table file")) slicerComment = true;
    }
    if (slicerComment || extensionOf(source) == ".ctbl") return LabelTableFormat::SlicerTable;
    std::vector<const Line*> data = dataLines(lines);
    bool colorLines = !data.empty();
    for (const Line* line : data) {
        std::vector<std::string> w = words(line->text);
        if ((w.size() != 5 && w.size() != 6) || !asInteger(w[0])) {
            colorLines = false;
            break;
        }
        for (std::size_t c = 2; c < w.size(); ++c) {
            std::optional<long> v = asInteger(w[c]);
            if (!v || *v < 0 || *v > 255) colorLines = false;
        }
        if (!colorLines) break;
    }
    return colorLines ? LabelTableFormat::ColorTable : LabelTableFormat::MricronNames;
}

namespace {

LabelTable parseAs(LabelTableFormat format, std::string_view text, const std::string& source) {
    std::vector<Line> lines = splitLines(text);
    if (dataLines(lines).empty()) throw InputError(source, "labels", "at least one label line", "none");
    switch (format) {
        case LabelTableFormat::SlicerCsv: return parseSlicerCsv(lines, source);
        case LabelTableFormat::SlicerTable: return parseColorLines(lines, source, true);
        case LabelTableFormat::ColorTable: return parseColorLines(lines, source, false);
        case LabelTableFormat::MricronNames: break;
    }
    return parseMricronNames(lines, source);
}

}  // namespace

LabelTable readLabelTableText(std::string_view text, const std::string& source) {
    return parseAs(detectLabelTableFormat(text, source), text, source);
}

LabelTable readLabelTable(const std::filesystem::path& path) {
    std::string source = path.string();
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) throw InputError(source, "", "an existing label table file", "no such file");
    if (extensionOf(source) == ".lut") return readLut(path);
    std::vector<std::uint8_t> bytes = readFileBytes(path);
    std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    const LabelTableFormat format = detectLabelTableFormat(text, source);
    LabelTable table = parseAs(format, text, source);
    if (format != LabelTableFormat::MricronNames) return table;
    std::filesystem::path lut = path;
    lut.replace_extension(".lut");
    if (!std::filesystem::is_regular_file(lut, ec)) return table;
    std::array<glm::dvec3, 256> colors = readLutColors(lut);
    for (LabelEntry& e : table.entries)
        if (e.id < 256) e.rgba = glm::dvec4(colors[static_cast<std::size_t>(e.id)], lutAlpha(e.id));
    table.source = source + " (colours: " + lut.string() + ")";
    return table;
}

LabelTable readLut(const std::filesystem::path& path) {
    std::array<glm::dvec3, 256> colors = readLutColors(path);
    LabelTable table;
    table.source = path.string();
    for (int id = 0; id < 256; ++id)
        table.entries.push_back({id, "label " + std::to_string(id), glm::dvec4(colors[static_cast<std::size_t>(id)], lutAlpha(id))});
    return table;
}

glm::dvec4 generatedLabelColor(int id) {
    if (id == 0) return {0.0, 0.0, 0.0, 0.0};
    // Hue by the golden angle (0.381966 turns), saturation and value in three steps so hues that come round
    // again differ; HSV -> RGB.
    double hue = std::fmod(static_cast<double>(id) * 0.3819660112501051, 1.0) * 6.0;
    double saturation = 0.55 + 0.15 * static_cast<double>(id % 3), value = 0.95 - 0.1 * static_cast<double>((id / 3) % 3);
    int sector = static_cast<int>(hue);
    double f = hue - sector;
    double p = value * (1 - saturation), q = value * (1 - saturation * f), t = value * (1 - saturation * (1 - f));
    glm::dvec3 rgb;
    switch (sector % 6) {
        case 0: rgb = {value, t, p}; break;
        case 1: rgb = {q, value, p}; break;
        case 2: rgb = {p, value, t}; break;
        case 3: rgb = {p, q, value}; break;
        case 4: rgb = {t, p, value}; break;
        default: rgb = {value, p, q}; break;
    }
    return glm::dvec4(rgb, 1.0);
}

LabelEntry generatedLabel(int id) { return {id, "label " + std::to_string(id), generatedLabelColor(id)}; }

LabelEntry labelEntryFor(const LabelTable& table, int id) {
    const LabelEntry* e = table.find(id);
    return e ? *e : generatedLabel(id);
}

void addMissingLabels(LabelTable& table, const LabelMap& map) {
    std::vector<bool> present(65536, false);
    for (std::uint16_t id : map.ids) present[id] = true;
    for (int id = 1; id < 65536; ++id)
        if (present[static_cast<std::size_t>(id)] && !table.find(id)) table.entries.push_back(generatedLabel(id));
}

}  // namespace curette::io
