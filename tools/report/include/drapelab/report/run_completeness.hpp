// Whether a run folder holds the whole run: summary.json's state, the frames each solver recorded
// in metrics.csv against the frames planned, and CSV files whose last row was cut mid-line (a
// writer killed while writing). report and render both say what is missing.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace drapelab::report {

struct SolverFrameSpan {
  std::string name;
  std::string status;        // summary.json's status ("" when absent)
  std::vector<int> frames;   // recorded in metrics.csv, sorted
  std::vector<int> missing;  // planned frames not recorded, sorted
};

struct RunCompleteness {
  std::string state;        // summary.json run.state: running, finished, interrupted
  int frames_planned = -1;  // frames after frame 0; -1 when summary.json does not say
  std::vector<SolverFrameSpan> solvers;
  std::vector<std::string> cut_files;  // CSV files whose last row ends mid-line
  // The pid of the run still writing the folder (a staging folder whose run holds its lock); empty
  // when no live run writes it, so a "running" state means its writer was killed.
  std::string live_writer;

  // The writer did not end the run: state "running" (killed, or still being written), or a CSV
  // cut mid-row.
  bool incomplete() const;
  // Stopped by Ctrl-C: a normal end, with frames missing.
  bool interrupted() const { return state == "interrupted"; }
  // One line per fact, for the page and for stderr; empty for a whole, finished run.
  std::vector<std::string> notices() const;
};

// Reads summary.json and metrics.csv of a run folder (no exception: what cannot be read is left
// unknown).
RunCompleteness inspect_run(const std::filesystem::path& folder);

// The text of a CSV file without a last row cut mid-line (the bytes after the last newline);
// `cut` is set when there was one.
std::string whole_rows(const std::string& text, bool* cut);

// "0-17, 20, 22-30": sorted frame numbers as ranges.
std::string frame_ranges(const std::vector<int>& frames);

}  // namespace drapelab::report
