#pragma once
// A table of results with named columns: written as CSV (one per table or figure) and shown in
// the report as Markdown. Cells are text; numbers go through csvNumber so that every file
// prints them alike (infinity as "inf", e.g. the PSNR of identical images).
#include <string>
#include <vector>

namespace mfadvr::eval {

class CsvTable {
 public:
  explicit CsvTable(std::vector<std::string> columns);

  // Throws mfadvr::Error when the row's length differs from the column count.
  void addRow(std::vector<std::string> cells);

  const std::vector<std::string>& columns() const { return columns_; }
  const std::vector<std::vector<std::string>>& rows() const { return rows_; }
  std::size_t columnIndex(const std::string& name) const;  // throws for an unknown name

  // RFC 4180: fields with commas, quotes or line breaks are quoted.
  std::string toCsv() const;
  // Writes the CSV atomically.
  void write(const std::string& path) const;
  // A Markdown table of the named columns (all when empty), with optional header labels.
  std::string toMarkdown(const std::vector<std::string>& columns = {},
                         const std::vector<std::string>& headers = {}) const;

 private:
  std::vector<std::string> columns_;
  std::vector<std::vector<std::string>> rows_;
};

// The parameter studies' Markdown table: a row per degree, a column per control count, each
// cell cell(degree, controlCount).
template <class Cell>
std::string degreeByControlsTable(const std::vector<int>& degrees, const std::vector<int>& ctrls,
                                  Cell cell) {
  std::vector<std::string> columns = {"degree"};
  for (int c : ctrls) columns.push_back(std::to_string(c));
  CsvTable t(columns);
  for (int p : degrees) {
    std::vector<std::string> row = {std::to_string(p)};
    for (int c : ctrls) row.push_back(cell(p, c));
    t.addRow(row);
  }
  return t.toMarkdown();
}

// Shortest round-trip-ish text of a number: %.*g with `digits` significant digits, "inf",
// "-inf" or "nan".
std::string csvNumber(double value, int digits = 6);
// Fixed decimals, for the report's tables.
std::string fixed(double value, int decimals);

}  // namespace mfadvr::eval
