// The arguments of drapelab sweep, apart from the command line's parser: the sweep's engines
// include this, not verbs.hpp, and so compile without CLI11.
#pragma once

#include <string>
#include <vector>

namespace drapelab::sweep {

// drapelab sweep: a `drapelab run` per combination of the varied keys' values, as a child process
// (--engine local) or a Slurm array task (--engine slurm).
struct SweepArguments {
  std::string scene;
  std::vector<std::string> varies;       // --vary key.path=v1,v2,... (commas inside [] or {} stay)
  std::string out;                       // the sweep folder: sweep.csv, sweep.json, runs/
  int jobs = 0;                          // runs at a time; 0 = the number of cores
  std::vector<std::string> overrides;    // --set key.path=value, in every run
  bool force = false;                    // replace a sweep already in the folder
  std::string engine = "local";          // local | slurm
  bool detach = false;                   // slurm: return once submitted
  std::string collect;                   // --collect DIR: gather a submitted Slurm sweep
  std::string partition;                 // slurm: sbatch --partition
  std::string time_limit;                // slurm: sbatch --time, per task
  int cpus_per_task = 0;                 // slurm: sbatch --cpus-per-task; 0 = 1
  std::vector<std::string> sbatch_args;  // slurm: more sbatch arguments, as given
  double lost_after = 0.0;   // slurm: s a task may be gone without its status; 0 = the default
  bool no_progress = false;  // no progress line (runs done of total) on stderr
};

}  // namespace drapelab::sweep
