// Reading CSV files back (csv.hpp).
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "drapelab/run_folder/csv.hpp"
#include "drapelab/run_folder/files.hpp"

namespace drapelab::run_folder {

std::optional<std::size_t> CsvTable::column(const std::string& name) const {
  for (std::size_t k = 0; k < header.size(); ++k)
    if (header[k] == name) return k;
  return std::nullopt;
}

const std::string& CsvTable::text(std::size_t row, const std::optional<std::size_t>& column) const {
  static const std::string empty;
  if (!column || row >= rows.size() || *column >= rows[row].size()) return empty;
  return rows[row][*column];
}

double CsvTable::number(std::size_t row, const std::optional<std::size_t>& column) const {
  return parse_number(text(row, column)).value_or(std::numeric_limits<double>::quiet_NaN());
}

std::optional<double> parse_number(const std::string& cell) {
  std::size_t begin = cell.find_first_not_of(" \t");
  if (begin == std::string::npos) return std::nullopt;
  std::size_t end = cell.find_last_not_of(" \t") + 1;
  if (cell[begin] == '+') ++begin;  // from_chars refuses a leading '+'
  double value = 0.0;
  const char* first = cell.data() + begin;
  const char* last = cell.data() + end;
  const auto [stop, error] = std::from_chars(first, last, value);
  if (error != std::errc() || stop != last) return std::nullopt;
  return value;
}

CsvTable parse_csv(const std::string& text) {
  std::vector<std::vector<std::string>> records;
  std::vector<std::string> record;
  std::string cell;
  bool quoted = false;          // inside a quoted cell
  bool record_started = false;  // the current line has any character (a blank line is no record)
  auto end_record = [&] {
    if (record_started) {
      record.push_back(cell);
      records.push_back(std::move(record));
    }
    record = {};
    cell.clear();
    record_started = false;
  };
  for (std::size_t k = 0; k < text.size(); ++k) {
    const char c = text[k];
    if (quoted) {
      if (c == '"') {
        if (k + 1 < text.size() && text[k + 1] == '"') {
          cell += '"';
          ++k;
        } else {
          quoted = false;
        }
      } else {
        cell += c;
      }
      continue;
    }
    if (c == '"') {
      quoted = true;
      record_started = true;
    } else if (c == ',') {
      record.push_back(cell);
      cell.clear();
      record_started = true;
    } else if (c == '\n') {
      end_record();
    } else if (c != '\r') {
      cell += c;
      record_started = true;
    }
  }
  end_record();

  CsvTable table;
  if (records.empty()) return table;
  table.header = std::move(records.front());
  for (std::size_t r = 1; r < records.size(); ++r) {
    records[r].resize(table.header.size());
    table.rows.push_back(std::move(records[r]));
  }
  return table;
}

std::optional<CsvTable> read_csv_file(const std::filesystem::path& path) {
  const auto text = read_file_bytes(path);
  if (!text) return std::nullopt;
  return parse_csv(*text);
}

}  // namespace drapelab::run_folder
