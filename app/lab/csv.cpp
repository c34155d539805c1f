#include "csv.h"

#include <cmath>
#include <cstdlib>
#include <fstream>

#include "text.h"

namespace lab {

std::string csvField(std::string_view text) {
  if (text.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(text);
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

std::string csvNumber(double value, int digits) {
  return std::isfinite(value) ? formatNumber(value, digits) : std::string();
}

std::string csvLine(const std::vector<std::string>& fields) {
  return join(fields, ",") + "\n";
}

std::vector<std::string> csvFields(std::string_view line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        fields.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        fields.back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  return fields;
}

CsvTable readCsv(const std::filesystem::path& file) {
  CsvTable csv;
  std::ifstream in(file);
  std::string line;
  if (!std::getline(in, line)) return csv;
  csv.header = csvFields(line);
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const std::vector<std::string> fields = csvFields(line);
    if (fields.size() != csv.header.size()) ++csv.raggedRows;
    CsvRow row;
    for (std::size_t i = 0; i < csv.header.size() && i < fields.size(); ++i) row[csv.header[i]] = fields[i];
    csv.rows.push_back(std::move(row));
  }
  return csv;
}

double fieldNumber(const CsvRow& row, const std::string& column) {
  const auto it = row.find(column);
  if (it == row.end() || it->second.empty()) return std::nan("");
  return std::strtod(it->second.c_str(), nullptr);
}

std::string fieldText(const CsvRow& row, const std::string& column) {
  const auto it = row.find(column);
  return it == row.end() ? std::string() : it->second;
}

}  // namespace lab
