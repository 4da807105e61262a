// Writing CSV tables row by row (csv.hpp).
#include <stdexcept>

#include "drapelab/run_folder/csv.hpp"

namespace drapelab::run_folder {

CsvWriter::CsvWriter(const std::filesystem::path& path, const std::vector<std::string>& columns)
    : out_(path, std::ios::binary | std::ios::trunc), columns_(columns.size()) {
  if (!out_) throw std::runtime_error("cannot write " + path.string());
  row(columns);
  flush();
}

void CsvWriter::row(const std::vector<std::string>& cells) {
  for (std::size_t k = 0; k < cells.size(); ++k) out_ << (k ? "," : "") << cells[k];
  out_ << '\n';
}

void CsvWriter::flush() { out_.flush(); }

std::string csv_cell(const std::string& text, bool always) {
  const bool needs = always || text.find_first_of(",\"\n\r") != std::string::npos ||
                     (!text.empty() && (text.front() == ' ' || text.back() == ' '));
  if (!needs) return text;
  std::string quoted = "\"";
  for (const char c : text) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + "\"";
}

}  // namespace drapelab::run_folder
