// Files of a run folder (shared/outputs.md): CSV tables flushed row by row, files replaced
// atomically, and the run folder's own safety checks.
#pragma once

#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

namespace drapelab::runner {

// A CSV table written a row at a time. Each row is flushed when the frame ends, so a run stopped at
// any moment leaves a valid table (header + whole rows).
class CsvTable {
 public:
  CsvTable(const std::filesystem::path& path, const std::vector<std::string>& columns);
  void row(const std::vector<std::string>& cells);
  void flush();
  std::size_t column_count() const { return columns_; }

 private:
  std::ofstream out_;
  std::size_t columns_;
};

// Writes `text` to `path` through a temporary file and a rename, so readers never see half a file.
void write_file_atomically(const std::filesystem::path& path, const std::string& text);
std::string read_file(const std::filesystem::path& path);

// Every file and folder a run may write into its folder (and --force may replace).
const std::vector<std::string>& run_output_names();

// Checks the output folder before anything is written. Returns an error message (exit code 2) when
// it may not be used: it is a file, or holds a different run or other files and --force was not given.
// With `force`, removes the previous run's outputs (only drapelab's own files). Creates the folder.
std::optional<std::string> prepare_run_folder(const std::filesystem::path& folder,
                                              const std::string& resolved_scene, bool force);

}  // namespace drapelab::runner
