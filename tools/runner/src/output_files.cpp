// Run folder files: CSV tables, atomic replacement, and the folder's safety checks.
#include "drapelab/runner/output_files.hpp"

#include <sstream>
#include <stdexcept>
#include <system_error>

namespace drapelab::runner {

namespace fs = std::filesystem;

CsvTable::CsvTable(const fs::path& path, const std::vector<std::string>& columns)
    : out_(path, std::ios::binary | std::ios::trunc), columns_(columns.size()) {
  if (!out_) throw std::runtime_error("cannot write " + path.string());
  row(columns);
  flush();
}

void CsvTable::row(const std::vector<std::string>& cells) {
  for (std::size_t k = 0; k < cells.size(); ++k) out_ << (k ? "," : "") << cells[k];
  out_ << '\n';
}

void CsvTable::flush() { out_.flush(); }

void write_file_atomically(const fs::path& path, const std::string& text) {
  const fs::path temporary = path.string() + ".partial";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out << text;
    out.flush();
    if (!out) throw std::runtime_error("cannot write " + temporary.string());
  }
  fs::rename(temporary, path);
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

const std::vector<std::string>& run_output_names() {
  static const std::vector<std::string> names = {"scene.yaml",   "resolved.yaml", "metrics.csv",
                                                 "compare.csv",  "contacts.csv",  "summary.json",
                                                 "summary.json.partial", "meshes",
                                                 "render"};  // drapelab render's default folder: stale after a re-run
  return names;
}

std::optional<std::string> prepare_run_folder(const fs::path& folder, const std::string& resolved_scene,
                                              bool force) {
  std::error_code ec;
  if (fs::exists(folder, ec) && !fs::is_directory(folder, ec))
    return folder.string() + " exists and is not a folder; choose another --out";
  if (fs::is_directory(folder, ec) && !fs::is_empty(folder, ec) && !force) {
    const fs::path previous = folder / "resolved.yaml";
    if (!fs::exists(previous))
      return folder.string() + " is not empty and holds no drapelab run; choose an empty or new --out "
                               "folder, or add --force to write the run beside its files";
    // A folder holding this very run (same resolved scene) may be refreshed without --force.
    if (read_file(previous) != resolved_scene)
      return folder.string() + " holds a different run (its resolved.yaml differs); add --force to "
                               "replace it, or choose another --out";
  }
  for (const auto& name : run_output_names()) fs::remove_all(folder / name, ec);
  fs::create_directories(folder, ec);
  if (ec || !fs::is_directory(folder)) return "cannot create the output folder " + folder.string() + ": " + ec.message();
  return std::nullopt;
}

}  // namespace drapelab::runner
