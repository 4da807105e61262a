// CSV as the run folder writes and reads it: tables written a row at a time and flushed per frame,
// and whole files read back into string cells with numbers parsed on demand.
#pragma once

#include <cstddef>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

namespace drapelab::run_folder {

// A CSV table written a row at a time. Each row is flushed when the frame ends, so a run stopped at
// any moment leaves a valid table (header + whole rows).
class CsvWriter {
 public:
  CsvWriter(const std::filesystem::path& path, const std::vector<std::string>& columns);
  void row(const std::vector<std::string>& cells);
  void flush();
  std::size_t column_count() const { return columns_; }

 private:
  std::ofstream out_;
  std::size_t columns_;
};

// A cell quoted when it must be (RFC 4180: commas, quotes, line breaks, edge spaces), or always.
std::string csv_cell(const std::string& text, bool always = false);

// A CSV file read whole into memory: a header row and string cells. An empty or unreadable cell
// reads as NaN, so a plot can leave a gap where a run wrote nothing.
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

// Reads and parses a file; nullopt when it cannot be opened.
std::optional<CsvTable> read_csv_file(const std::filesystem::path& path);

// Parses a whole cell as a double ("1e-3", "nan", "inf" included); nullopt for "" or anything else.
std::optional<double> parse_number(const std::string& cell);

}  // namespace drapelab::run_folder
