// Run folder files: names, atomic replacement, and the folder's safety checks (files.hpp).
#include "drapelab/run_folder/files.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "drapelab/run_folder/output_file.hpp"

namespace drapelab::run_folder {

namespace fs = std::filesystem;

void write_file_atomically(const fs::path& path, const std::string& text) {
  const fs::path temporary = path.string() + ".partial";
  write_whole_file(temporary, text);  // removes the temporary when it cannot be written whole
  std::error_code error;
  fs::rename(temporary, path, error);
  if (error) {
    fs::remove(temporary, error);
    throw WriteError(path, error);
  }
}

std::string read_file(const fs::path& path) { return read_file_bytes(path).value_or(""); }

std::optional<std::string> read_file_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

}  // namespace drapelab::run_folder
