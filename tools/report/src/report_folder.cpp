#include <system_error>
#include <vector>

#include "drapelab/report/report.hpp"

namespace drapelab::report {

namespace fs = std::filesystem;

FolderCheck inspect_folder(const fs::path& folder) {
  FolderCheck check;
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) {
    check.problem = folder.string() + " is not a folder";
    return check;
  }
  auto is_file = [&](const char* name) { return fs::is_regular_file(folder / name, ec); };
  if (is_file("sweep.csv")) {
    check.kind = FolderKind::sweep;
    return check;
  }
  // A run folder: the three files the page cannot do without. compare.csv and contacts.csv are
  // read when present: every run writes them, with their header alone for a scene with one solver
  // or without colliders (docs/outputs.md, "The run folder"), but the page does without them.
  std::vector<std::string> missing;
  for (const char* name : {"summary.json", "metrics.csv", "scene.yaml"})
    if (!is_file(name)) missing.emplace_back(name);
  if (missing.empty()) {
    check.kind = FolderKind::run;
    return check;
  }
  std::string list;
  for (std::size_t k = 0; k < missing.size(); ++k)
    list += (k == 0 ? "" : k + 1 == missing.size() ? " and " : ", ") + missing[k];
  check.problem =
      folder.string() + " is neither a run folder (missing " + list +
      "; make one with drapelab run SCENE --out DIR) nor a sweep folder (missing sweep.csv; make "
      "one with drapelab sweep SCENE --vary ... --out DIR)";
  return check;
}

}  // namespace drapelab::report
