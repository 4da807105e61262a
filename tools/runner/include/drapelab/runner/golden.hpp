// Golden regression files: the key metrics of a short run at chosen frames, kept in a JSON file and
// compared with tolerances (drapelab check). They change only through `drapelab check --update`
// (tools/update-golden.sh for the project's scenes), which prints what changed.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace drapelab::runner {

struct GoldenTolerance {
  double relative = 1e-4;  // of the recorded value
  double absolute = 1e-6;  // in the column's unit (m, J, N, m^2)
  double count = 1.0;      // for whole-number columns (contact_count, drape_nodes)
};

// Values at one frame: row ("ours" or "ours/ball" for a collider's contacts) -> column -> value.
// A missing optional value (an empty CSV cell) is stored as nullopt.
using GoldenRows = std::map<std::string, std::map<std::string, std::optional<double>>>;

struct Golden {
  std::string scene;                   // the scene's name
  std::vector<std::string> overrides;  // --set values the run used
  GoldenTolerance tolerance;
  std::map<int, GoldenRows> frames;  // frame -> rows
};

// Reads metrics.csv and contacts.csv of a run folder at the given frames.
std::map<int, GoldenRows> read_golden_values(const std::filesystem::path& run_dir,
                                             const std::vector<int>& frames);

// Five frames spread over the run: 0, a quarter, half, three quarters, the last.
std::vector<int> golden_frames(int frame_count);

struct GoldenDifference {
  int frame = 0;
  std::string row, column;
  std::optional<double> expected, actual;
};

// Values outside the tolerance, and values present on one side only.
std::vector<GoldenDifference> compare_golden(const Golden& golden,
                                             const std::map<int, GoldenRows>& actual);
std::string describe_difference(const GoldenDifference& difference);

std::string golden_to_json(const Golden& golden);
// Parses a golden file; returns an error message instead when it is not one.
std::optional<Golden> golden_from_json(const std::string& text, std::string* error);

}  // namespace drapelab::runner
