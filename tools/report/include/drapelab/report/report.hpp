// drapelab report: one self-contained HTML page for a run folder (drapelab run) or a sweep folder
// (drapelab sweep), with inline SVG plots and, for a run, the last rendered frame embedded.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace drapelab::report {

enum class FolderKind { run, sweep };

struct FolderCheck {
  std::optional<FolderKind> kind;  // empty when the folder is neither
  std::string problem;             // when empty kind: what is missing, for the user
};

// A sweep folder holds sweep.csv; a run folder holds summary.json, metrics.csv and scene.yaml.
FolderCheck inspect_folder(const std::filesystem::path& folder);

// The page for a run folder. `report_file` is where the page will be written: the video's src is
// relative to it. Throws std::runtime_error naming the file when one cannot be read or parsed.
std::string run_report_html(const std::filesystem::path& folder,
                            const std::filesystem::path& report_file);

// The page for a sweep folder. Throws std::runtime_error like run_report_html.
std::string sweep_report_html(const std::filesystem::path& folder);

}  // namespace drapelab::report
