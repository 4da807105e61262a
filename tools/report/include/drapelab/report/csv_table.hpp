// A CSV file read whole into memory: a header row and string cells. Numbers are parsed on demand, and
// an empty or unreadable cell reads as NaN, so a plot can leave a gap where a run wrote nothing.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace drapelab::report {

struct CsvTable {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;  // each padded or cut to header.size() cells

  // Index of the column named `name`, or nullopt.
  std::optional<std::size_t> column(const std::string& name) const;
  // The cell as text ("" when the column is missing).
  const std::string& text(std::size_t row, const std::optional<std::size_t>& column) const;
  // The cell as a number: NaN when the column is missing, the cell empty or not a number.
  double number(std::size_t row, const std::optional<std::size_t>& column) const;
};

// Splits CSV text into rows of cells (RFC 4180: quoted cells may hold commas, quotes ("") and
// newlines; CR before LF is dropped). The first row is the header; blank lines are skipped.
CsvTable parse_csv(const std::string& text);

// A whole file as bytes; nullopt when it cannot be opened.
std::optional<std::string> read_file_bytes(const std::filesystem::path& path);

// Reads and parses a file; nullopt when it cannot be opened.
std::optional<CsvTable> read_csv_file(const std::filesystem::path& path);

// Parses a whole cell as a double ("1e-3", "nan", "inf" included); nullopt for "" or anything else.
std::optional<double> parse_number(const std::string& cell);

}  // namespace drapelab::report
