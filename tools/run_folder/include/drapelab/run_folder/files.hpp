// The run folder's files (docs/outputs.md, "The run folder"): their names, whole-file reads, writes
// that replace a file atomically. How a run fills its folder: run_transaction.hpp. The one place
// that decides what a run folder holds: the runner writes it, and check, report and render read it.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace drapelab::run_folder {

inline constexpr const char* kSceneYaml = "scene.yaml";        // the scene as given
inline constexpr const char* kResolvedYaml = "resolved.yaml";  // every default filled in
inline constexpr const char* kMetricsCsv = "metrics.csv";      // one row per (solver, frame)
inline constexpr const char* kCompareCsv = "compare.csv";      // one row per (solver pair, frame)
inline constexpr const char* kContactsCsv =
    "contacts.csv";  // one row per (solver, frame, collider)
inline constexpr const char* kSummaryJson =
    "summary.json";                                     // per solver status, cost, final metrics
inline constexpr const char* kMeshesFolder = "meshes";  // rest.obj, SOLVER.pc2, SOLVER_NNNN.obj
inline constexpr const char* kRenderFolder = "render";  // drapelab render's default output

// Writes `text` to `path` through a temporary file and a rename, so readers never see half a file.
// Throws WriteError (output_file.hpp); the temporary is removed on failure.
void write_file_atomically(const std::filesystem::path& path, const std::string& text);
// A whole file as bytes ("" when it cannot be read).
std::string read_file(const std::filesystem::path& path);
// A whole file as bytes; nullopt when it cannot be opened.
std::optional<std::string> read_file_bytes(const std::filesystem::path& path);

}  // namespace drapelab::run_folder
