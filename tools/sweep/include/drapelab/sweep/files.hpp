// The two files of a sweep folder: sweep.csv (one row per combination and solver) and sweep.json
// (the command, the varied keys and values, and each combination's status). Both are rebuilt from
// the finished combinations after every run and replaced atomically, so they are whole whenever the
// sweep stops.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "drapelab/sweep/outcome.hpp"
#include "drapelab/sweep/plan.hpp"

namespace drapelab::sweep {

// sweep.csv: a header, then the rows of every finished combination in combination order, each
// combination's solvers in summary.json's order. Columns: combination, one per varied key (named
// by its key path), solver, type, status, exit_code, message, the final metrics and the solver's
// measures (outcome.hpp), run_folder.
std::string sweep_csv(const SweepPlan& plan,
                      const std::map<std::size_t, CombinationOutcome>& finished);

// The columns of sweep.csv that hold wall-clock times (vary from run to run; everything else is
// deterministic for a given build).
const std::vector<std::string>& sweep_timing_columns();

struct SweepRecord {
  std::string command;     // as typed
  std::string executable;  // the drapelab that ran every child
  std::string scene_file;
  std::string scene_name;
  std::vector<std::string> overrides;  // --set, applied to every combination before its own values
  int jobs = 1;                  // local: runs at a time; slurm: the array's throttle (0: none)
  std::string engine = "local";  // local | slurm
  std::string job_id;            // slurm: the job array's id
  std::string state;  // running | complete | interrupted; slurm also submitted (--detach)
};

// sweep.json. A combination not finished is "pending" while the sweep runs and "not_run" once it
// has stopped.
std::string sweep_json(const SweepRecord& record, const SweepPlan& plan,
                       const std::map<std::size_t, CombinationOutcome>& finished);

}  // namespace drapelab::sweep
