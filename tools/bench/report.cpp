#include "tools/bench/report.h"

#include "base/atomic_file.h"

#include <algorithm>
#include <cstdio>

namespace curette::bench {

Table::Table(std::string title, std::vector<std::string> columns) : title_(std::move(title)), columns_(std::move(columns)) {}

void Table::add(std::vector<nlohmann::json> cells) {
    cells.resize(columns_.size());
    rows_.push_back(std::move(cells));
}

static std::string cellText(const nlohmann::json& cell, int precision) {
    if (cell.is_string()) return cell.get<std::string>();
    if (cell.is_null()) return "-";
    if (cell.is_boolean()) return cell.get<bool>() ? "yes" : "no";
    if (cell.is_number_integer()) return std::to_string(cell.get<long long>());
    char text[32];
    std::snprintf(text, sizeof text, "%.*g", precision, cell.get<double>());
    return text;
}

void Table::print(int precision) const {
    std::vector<std::size_t> width(columns_.size());
    for (std::size_t c = 0; c < columns_.size(); ++c) width[c] = columns_[c].size();
    for (const auto& row : rows_)
        for (std::size_t c = 0; c < row.size(); ++c) width[c] = std::max(width[c], cellText(row[c], precision).size());
    std::printf("\n%s\n", title_.c_str());
    auto line = [&](auto cell) {
        std::string text;
        for (std::size_t c = 0; c < columns_.size(); ++c) {
            std::string s = cell(c);
            text += (c ? " | " : "") + s + std::string(width[c] - s.size(), ' ');
        }
        std::printf("%s\n", text.c_str());
    };
    line([&](std::size_t c) { return columns_[c]; });
    line([&](std::size_t c) { return std::string(width[c], '-'); });
    for (const auto& row : rows_) line([&](std::size_t c) { return cellText(row[c], precision); });
}

nlohmann::json Table::toJson() const {
    nlohmann::json rows = nlohmann::json::array();
    for (const auto& row : rows_) {
        nlohmann::json object = nlohmann::json::object();
        for (std::size_t c = 0; c < columns_.size(); ++c) object[columns_[c]] = row[c];
        rows.push_back(object);
    }
    return {{"title", title_}, {"columns", columns_}, {"rows", rows}};
}

void writeJson(const std::filesystem::path& path, const nlohmann::json& document) {
    writeFileAtomically(path, document.dump(2) + "\n");
    std::printf("\nwrote %s\n", path.string().c_str());
}

double median(std::vector<double> values) {
    if (values.empty()) return 0;
    std::sort(values.begin(), values.end());
    std::size_t n = values.size();
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace curette::bench
