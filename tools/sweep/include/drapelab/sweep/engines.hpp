// The two ways a sweep's runs are carried out once the sweep is validated and its folder prepared:
// child processes on this machine (local) or one Slurm job array (slurm).
#pragma once

#include <atomic>
#include <filesystem>
#include <optional>
#include <string>

#include "drapelab/sweep/arguments.hpp"
#include "drapelab/sweep/folder.hpp"
#include "drapelab/sweep/plan.hpp"
#include "drapelab/sweep/validation.hpp"

namespace drapelab::sweep {

// What both engines start from.
struct SweepStart {
  const SweepArguments& arguments;
  const SweepPlan& plan;
  const SweepValidation& validation;
  SweepFolder& folder;  // refused combinations are already rows
  const std::atomic<bool>& interrupt;
};

// The combinations to run, in order: those the validation did not refuse.
std::vector<std::size_t> combinations_to_run(const SweepStart& start);

// `drapelab run` of combination `index`, as the program's arguments (arguments[0] the program's
// name): the scene, its run folder with --force (a run replaces only drapelab's own files) and
// --no-progress, the --set overrides and then the combination's values.
std::vector<std::string> run_arguments(const SweepStart& start, std::size_t index,
                                       const std::string& program);

// Up to --jobs child processes at a time. Returns the sweep's exit code.
int run_local_sweep(SweepStart& start);

// Submits the job array and waits for it (or, with --detach, returns once it is submitted).
int run_slurm_sweep(SweepStart& start);

// Why --force may not replace the sweep in `out`: a Slurm job array of its still has tasks queued
// or running (they would write into the new sweep's folders). Nothing when there is none, or when
// squeue cannot be asked.
std::optional<std::string> queued_slurm_job(const std::filesystem::path& out);

// drapelab sweep --collect DIR: waits for a submitted Slurm sweep and writes its tables; an
// `interrupt` (the caller's Ctrl-C) stops the wait, and the job goes on.
// `lost_after`: as --lost-after (s; 0: the default).
int collect_slurm_sweep(const std::string& out, double lost_after, cli::ProgressMode progress,
                        const std::atomic<bool>& interrupt);

}  // namespace drapelab::sweep
