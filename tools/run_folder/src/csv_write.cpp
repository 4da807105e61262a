// Writing CSV tables row by row (csv.hpp).
#include "drapelab/run_folder/csv.hpp"

namespace drapelab::run_folder {

CsvWriter::CsvWriter(const std::filesystem::path& path, const std::vector<std::string>& columns)
    : file_(path), columns_(columns.size()) {
  row(columns);
  flush();
  commit();
}

void CsvWriter::row(const std::vector<std::string>& cells) {
  for (std::size_t k = 0; k < cells.size(); ++k) {
    if (k) pending_ += ',';
    pending_ += cells[k];
  }
  pending_ += '\n';
}

void CsvWriter::flush() {
  file_.append(pending_);
  pending_.clear();
}

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
