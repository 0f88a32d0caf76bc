#include "eval/CsvTable.h"

#include <cmath>
#include <cstdio>

#include "core/util/AtomicFile.h"
#include "core/util/Error.h"

namespace mfadvr::eval {

CsvTable::CsvTable(std::vector<std::string> columns) : columns_(std::move(columns)) {}

void CsvTable::addRow(std::vector<std::string> cells) {
  if (cells.size() != columns_.size())
    throw Error("table row has " + std::to_string(cells.size()) + " cells, expected " +
                std::to_string(columns_.size()));
  rows_.push_back(std::move(cells));
}

std::size_t CsvTable::columnIndex(const std::string& name) const {
  for (std::size_t i = 0; i < columns_.size(); ++i)
    if (columns_[i] == name) return i;
  throw Error("table has no column '" + name + "'");
}

namespace {

std::string quoted(const std::string& cell) {
  if (cell.find_first_of(",\"\r\n") == std::string::npos) return cell;
  std::string out = "\"";
  for (char c : cell) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

void appendLine(std::string& out, const std::vector<std::string>& cells) {
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (i) out += ',';
    out += quoted(cells[i]);
  }
  out += '\n';
}

}  // namespace

std::string CsvTable::toCsv() const {
  std::string out;
  appendLine(out, columns_);
  for (const auto& row : rows_) appendLine(out, row);
  return out;
}

void CsvTable::write(const std::string& path) const {
  writeFileAtomically(path, toCsv());
}

std::string CsvTable::toMarkdown(const std::vector<std::string>& columns,
                                 const std::vector<std::string>& headers) const {
  std::vector<std::size_t> index;
  for (const auto& c : columns.empty() ? columns_ : columns) index.push_back(columnIndex(c));
  if (!headers.empty() && headers.size() != index.size())
    throw Error("markdown headers do not match the columns");
  auto cellText = [](std::string s) {
    for (auto& ch : s)
      if (ch == '|') ch = '/';
    return s;
  };
  std::string out = "|";
  for (std::size_t i = 0; i < index.size(); ++i)
    out += " " + (headers.empty() ? columns_[index[i]] : headers[i]) + " |";
  out += "\n|";
  for (std::size_t i = 0; i < index.size(); ++i) out += "---|";
  out += "\n";
  for (const auto& row : rows_) {
    out += "|";
    for (std::size_t i : index) out += " " + cellText(row[i]) + " |";
    out += "\n";
  }
  return out;
}

std::string csvNumber(double value, int digits) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, value);
  return buf;
}

std::string fixed(double value, int decimals) {
  if (!std::isfinite(value)) return csvNumber(value);
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, value);
  return buf;
}

}  // namespace mfadvr::eval
