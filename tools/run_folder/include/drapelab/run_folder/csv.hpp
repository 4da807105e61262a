// CSV as the run folder writes and reads it: tables written a row at a time and flushed per frame,
// and whole files read back into string cells with numbers parsed on demand.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "drapelab/run_folder/output_file.hpp"

namespace drapelab::run_folder {

// A CSV table written a row at a time. Rows wait in memory until flush(), which the run calls when
// a frame ends; commit() then marks the frame complete, and rollback() cuts the file back to the
// last complete frame after a write error, so the table always ends on a whole row.
class CsvWriter {
 public:
  CsvWriter(const std::filesystem::path& path, const std::vector<std::string>& columns);
  void row(const std::vector<std::string>& cells);
  void flush();  // throws WriteError (output_file.hpp)
  void commit() { file_.commit(); }
  bool rollback() noexcept {
    pending_.clear();
    return file_.rollback();
  }
  std::size_t column_count() const { return columns_; }

 private:
  OutputFile file_;
  std::string pending_;  // rows not yet written
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
