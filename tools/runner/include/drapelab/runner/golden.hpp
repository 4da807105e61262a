// Golden regression files: the metrics of a short run averaged over windows of frames, kept in a
// JSON file with one tolerance per quantity, and compared by `drapelab check`. They change only
// through `drapelab check --update` (tools/update-golden.sh for the project's scenes), which prints
// what changed. docs/contact.md ("Golden files") gives the design and the measured sensitivity.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace drapelab::runner {

// How a golden file's tolerances are set when it is recorded. A quantity's tolerance is
// relative x scale: its scale is the size of what it measures over the run (golden_scales), and
// `relative` is the larger of `relative_floor` and `noise_factor` times the largest change, over
// the windows and over the quantities of its kind for the same solver, that a relative change of
// `probe` in gravity makes, relative to scale. The probe stands for the rounding differences of
// another compiler or machine: a quantity that roundoff moves (a chaotic fold, Bullet's contact
// estimate) gets a tolerance that covers it, and one that roundoff does not move keeps the floor.
struct GoldenRule {
  int windows = 8;               // the run's frames are averaged over this many equal windows
  double relative_floor = 5e-3;  // of the scale
  double noise_factor = 4.0;     // times the probes' largest change
  double probe = 1e-10;          // relative change of gravity of the two probe runs, + and -
};

// Values of one window (or frame): row ("ours", "ours/ball" for a collider's contacts,
// "ours/bullet" for a pair of solvers) -> column -> value. An empty CSV cell, or a window without
// any value, is nullopt.
using GoldenRows = std::map<std::string, std::map<std::string, std::optional<double>>>;
// One number per row and column: scales and relative tolerances.
using GoldenNumbers = std::map<std::string, std::map<std::string, double>>;

struct Golden {
  std::string scene;                   // the scene's name
  std::vector<std::string> overrides;  // --set values the run used
  GoldenRule rule;
  // Window means, keyed by the window's last frame: "0" is frame 0 alone, and key k holds the mean
  // over the frames after the previous key up to k.
  std::map<int, GoldenRows> windows;
  GoldenNumbers scale;     // row -> column -> scale, in the column's unit
  GoldenNumbers relative;  // row -> column -> tolerance / scale

  // The absolute tolerance of a row's column (in the column's unit); nullopt when the file has
  // none.
  std::optional<double> tolerance(const std::string& row, const std::string& column) const;
  // How many values the file compares.
  std::size_t value_count() const;
};

// Every frame of a run folder's metrics.csv, contacts.csv and compare.csv: frame -> rows.
// Throws std::runtime_error naming a file that cannot be read.
std::map<int, GoldenRows> read_run_values(const std::filesystem::path& run_dir);

// The last frame of each window: 0, then `windows` equal windows of frames 1..frame_count.
std::vector<int> golden_window_ends(int frame_count, int windows);
// The mean of each value over each window ending at `ends` (sorted; the first window is frame
// `ends[0]` alone). Values missing from some frames are averaged over the frames that have them.
std::map<int, GoldenRows> window_means(const std::map<int, GoldenRows>& frames,
                                       const std::vector<int>& ends);

// The kind of a column: position, energy, strain, penetration, clearance, force, count, area,
// distance or drape. Quantities of one kind share a scale rule and a relative tolerance.
std::string golden_kind(const std::string& column);
// The scale of every row's column from a whole run (every frame), never below its kind's floor:
// see docs/contact.md ("Golden files") for the rule of each kind.
GoldenNumbers golden_scales(const std::map<int, GoldenRows>& frames);
// Relative tolerances from the recorded window means and the probe runs' (GoldenRule).
GoldenNumbers golden_relative(const GoldenRule& rule, const GoldenNumbers& scale,
                              const std::map<int, GoldenRows>& recorded,
                              const std::vector<std::map<int, GoldenRows>>& probes);

struct GoldenDifference {
  int frame = 0;  // the window's last frame
  std::string row, column;
  std::optional<double> expected, actual;
  std::optional<double> tolerance;  // absolute, in the column's unit
  std::optional<double> scale;
};

// Values outside their tolerance, and values present on one side only.
std::vector<GoldenDifference> compare_golden(const Golden& golden,
                                             const std::map<int, GoldenRows>& actual);
std::string describe_difference(const GoldenDifference& difference);

std::string golden_to_json(const Golden& golden);
// Parses a golden file; returns an error message instead when it is not one, or when it compares
// nothing (no window, or no value with a tolerance).
std::optional<Golden> golden_from_json(const std::string& text, std::string* error);

// Writes `text` to `path` through a temporary file beside it and a rename, so a reader sees the old
// file or the new one, never half of one. Returns an error message, or nullopt when written.
std::optional<std::string> write_golden_file(const std::filesystem::path& path,
                                             const std::string& text);

}  // namespace drapelab::runner
