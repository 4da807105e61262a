// Run folder files: names, atomic replacement, and the folder's safety checks (files.hpp).
#include "drapelab/run_folder/files.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>

namespace drapelab::run_folder {

namespace fs = std::filesystem;

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

std::string read_file(const fs::path& path) { return read_file_bytes(path).value_or(""); }

std::optional<std::string> read_file_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

const std::vector<std::string>& run_output_names() {
  // render/: drapelab render's default folder, stale after a re-run.
  static const std::vector<std::string> names = {kSceneYaml,
                                                 kResolvedYaml,
                                                 kMetricsCsv,
                                                 kCompareCsv,
                                                 kContactsCsv,
                                                 kSummaryJson,
                                                 std::string(kSummaryJson) + ".partial",
                                                 kMeshesFolder,
                                                 kRenderFolder};
  return names;
}

std::optional<std::string> prepare_run_folder(const fs::path& folder,
                                              const std::string& resolved_scene, bool force) {
  std::error_code ec;
  if (fs::exists(folder, ec) && !fs::is_directory(folder, ec))
    return folder.string() + " exists and is not a folder; choose another --out";
  if (fs::is_directory(folder, ec) && !fs::is_empty(folder, ec) && !force) {
    const fs::path previous = folder / kResolvedYaml;
    if (!fs::exists(previous))
      return folder.string() +
             " is not empty and holds no drapelab run; choose an empty or new --out "
             "folder, or add --force to write the run beside its files";
    // A folder holding this very run (same resolved scene) may be refreshed without --force.
    if (read_file(previous) != resolved_scene)
      return folder.string() +
             " holds a different run (its resolved.yaml differs); add --force to "
             "replace it, or choose another --out";
  }
  for (const auto& name : run_output_names()) fs::remove_all(folder / name, ec);
  fs::create_directories(folder, ec);
  if (ec || !fs::is_directory(folder))
    return "cannot create the output folder " + folder.string() + ": " + ec.message();
  return std::nullopt;
}

}  // namespace drapelab::run_folder
