#pragma once
// The lab's CSV, RFC 4180 as the commands write it (sweep's results.csv, stability.csv, the
// run's --dump): one writer's quoting and one reader, so what one command writes another
// (lab report) and the tests read back the same way.
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace lab {

/// A field as CSV: as it is, or quoted with its quotes doubled when it holds a comma, a quote
/// or a line break.
std::string csvField(std::string_view text);

/// A number as the lab's CSV files write it: %.{digits}g; an empty field, CSV's missing value,
/// for a figure that is not a finite number, never "inf" or "nan". A file whose figures can blow
/// up says so in a column of its own (`blew_up`), not through the number.
std::string csvNumber(double value, int digits);

/// One CSV line: the fields, each already written as CSV (csvField, csvNumber), with a comma
/// between each two and a newline after the last.
std::string csvLine(const std::vector<std::string>& fields);

/// One CSV line split into fields, undoing csvField's quoting (a quoted field may hold commas;
/// a doubled quote inside it is one quote). Always at least one field.
std::vector<std::string> csvFields(std::string_view line);

/// One row as column name -> field.
using CsvRow = std::map<std::string, std::string>;

/// A CSV file with a header line.
struct CsvTable {
  std::vector<std::string> header;
  std::vector<CsvRow> rows;  ///< blank lines skipped
  /// Rows whose field count differed from the header's: their extra fields are dropped and
  /// their missing columns absent, so a reader that cares (a test) can tell.
  std::size_t raggedRows = 0;
};

/// The file read as CsvTable; empty when it cannot be read or is empty.
CsvTable readCsv(const std::filesystem::path& file);

/// A row's field as a number: NaN when the column is missing or blank.
double fieldNumber(const CsvRow& row, const std::string& column);
/// A row's field as written ("" when the column is missing).
std::string fieldText(const CsvRow& row, const std::string& column);

}  // namespace lab
