#pragma once
// Benchmark output: every bench prints a table a person can read and writes JSON a script can read, from
// the same rows.

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace curette::bench {

class Table {
public:
    Table(std::string title, std::vector<std::string> columns);
    // Cells are JSON values: numbers are printed with `precision` significant digits, strings as is.
    void add(std::vector<nlohmann::json> cells);
    void print(int precision = 4) const;
    nlohmann::json toJson() const;   // {"title":..., "columns":[...], "rows":[{column: value}, ...]}
    const std::string& title() const { return title_; }

private:
    std::string title_;
    std::vector<std::string> columns_;
    std::vector<std::vector<nlohmann::json>> rows_;
};

// Writes `document` atomically and says where.
void writeJson(const std::filesystem::path& path, const nlohmann::json& document);

// Median of a list of values (copied).
double median(std::vector<double> values);

}  // namespace curette::bench
