// What one combination of a sweep gave: read from its child's exit status, its run folder's
// summary.json and its log, as rows of sweep.csv (one per solver, or one with no solver when the
// run gave no per-solver results).
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "drapelab/sweep/children.hpp"

namespace drapelab::sweep {

// The final measures of a solver copied into sweep.csv, in column order: the first eight from
// summary.json's "final" metrics (docs/metrics.md), the rest from the solver's own entry.
const std::vector<std::string>& sweep_final_metrics();
const std::vector<std::string>& sweep_solver_measures();

// One row of sweep.csv for one solver of one combination.
struct SweepRow {
  std::string solver;  // empty when the run gave no per-solver results (bad input, crash)
  std::string type;    // the solver's type (spring_damper, bullet_softbody, ...)
  // ok | unstable | error | bad_input | interrupted | crashed, and for Slurm: cancelled | lost
  std::string status;
  std::string message;  // why not ok; one line
  // Cells of sweep_final_metrics() then sweep_solver_measures(), as text (empty = no value).
  std::vector<std::string> measures;
};

struct CombinationOutcome {
  std::size_t index = 0;
  std::string status;  // the combination's: ok, or the first problem's status
  std::optional<int>
      exit_code;  // the child's; 2 for a combination refused before running; none after a signal
  std::string message;        // the first problem, one line; empty when ok
  std::string folder;         // the run folder relative to the sweep folder; empty when not run
  double wall_seconds = 0.0;  // s, from start to end of the child (0 when not run)
  std::vector<SweepRow> rows;
};

// A combination refused by the in-process validation: one bad_input row, exit code 2 (what
// `drapelab run` returns for it), nothing run.
CombinationOutcome refused_outcome(std::size_t index, const std::string& error);

// A combination whose child could not be started.
CombinationOutcome unstarted_outcome(std::size_t index, const std::string& folder,
                                     const std::string& error);

// A combination whose run left no word of how it ended: a Slurm task cancelled before it started
// (`status` cancelled) or one that vanished from the queue without writing its status (lost: a
// node failure, or SIGKILL at the time limit). `message` says which.
CombinationOutcome silent_outcome(std::size_t index, const std::string& folder,
                                  const std::string& status, const std::string& message);

// A finished child. `run_dir` and `log` are paths to read; `folder` is how sweep.csv names the run
// folder; `stopped_by_sweep` is set when the sweep itself stopped the child (Ctrl-C), so a signal
// reads as interrupted rather than crashed.
CombinationOutcome finished_outcome(std::size_t index, const ChildExit& exit,
                                    const std::filesystem::path& run_dir,
                                    const std::filesystem::path& log, const std::string& folder,
                                    bool stopped_by_sweep);

// The first line of a child's log that starts with "error: " (without that prefix), else its last
// non-empty line, else "".
std::string first_error_line(const std::filesystem::path& log);

}  // namespace drapelab::sweep
